"""The catalogue: items (theorems, checks, examples) and the loading of proof files.

The catalogue's own proofs are the packages :mod:`lkverify.proofs`; a user's proof
file is loaded by path through the same loader (:func:`find_items`).  A theorem over a
box of parameters, split until it closes, is :mod:`.boxrun` (``Theorem.run(box=…)``).  The
names and titles of the catalogue's items, without importing them, are :mod:`.index`.
"""

import importlib

__all__ = ["Check", "Item", "Link", "ProofFile", "Theorem", "catalogue", "find_items", "load_proof_file",
           "theorem_verdict"]

#: public name → the submodule that defines it, imported on first use (PEP 562): ``lkverify list`` reads the
#: catalogue's index (:mod:`.index`) without importing the items or SymPy
_SOURCES = {"Check": ".items", "Item": ".items", "Link": ".items", "Theorem": ".items", "theorem_verdict": ".items",
            "ProofFile": ".loader", "catalogue": ".loader", "find_items": ".loader", "load_proof_file": ".loader"}


def __getattr__(name: str):
    """The public name ``name``, imported from its submodule on first use and kept."""
    source = _SOURCES.get(name)
    if source is None:
        raise AttributeError(f"module 'lkverify.catalogue' has no attribute {name!r}")
    value = getattr(importlib.import_module(source, __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
