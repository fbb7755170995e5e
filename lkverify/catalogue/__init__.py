"""The catalogue: items (theorems, checks, examples) and the loading of proof files.

The catalogue's own proofs are the packages :mod:`lkverify.proofs`; a user's proof
file is loaded by path through the same loader (:func:`find_items`).  A theorem over a
box of parameters, split until it closes, is :mod:`.boxrun` (``Theorem.run(box=…)``).  The
names and titles of the catalogue's items, without importing them, are :mod:`.index`.
"""


__all__ = ["Check", "Item", "Link", "ProofFile", "SignalTheorem", "Theorem", "catalogue", "find_items",
           "load_proof_file", "theorem_verdict"]

from .._lazy import lazy_exports

#: public name → the submodule that defines it, imported on first use (PEP 562): ``lkverify list`` reads the
#: catalogue's index (:mod:`.index`) without importing the items or SymPy
_SOURCES = {"Check": ".items", "Item": ".items", "Link": ".items", "Theorem": ".items", "theorem_verdict": ".items",
            "SignalTheorem": ".signal_theorem", "ProofFile": ".loader", "catalogue": ".loader", "find_items": ".loader", "load_proof_file": ".loader"}


__getattr__, __dir__ = lazy_exports(__name__, _SOURCES, __all__)
