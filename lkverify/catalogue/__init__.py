"""The catalogue: items (theorems, checks, examples) and the loading of proof files.

The catalogue's own proofs are the packages :mod:`lkverify.proofs`; a user's proof
file is loaded by path through the same loader (:func:`find_items`).  A theorem over a
box of parameters, split until it closes, is :mod:`.boxrun` (``Theorem.run(box=…)``).
"""

from .items import Check, Item, Link, Theorem, theorem_verdict
from .loader import ProofFile, catalogue, find_items, load_proof_file

__all__ = ["Check", "Item", "Link", "ProofFile", "Theorem", "catalogue", "find_items", "load_proof_file",
           "theorem_verdict"]
