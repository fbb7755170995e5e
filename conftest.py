"""Suite-wide settings.

The proof cache (:mod:`lkverify.cache`) is off for the whole suite, in this process and in the
command-line subprocesses the tests start: a test sees what the code computes now, never an
entry of an earlier run (tests/test_cache.py switches it on in a directory of its own).
"""

import os

os.environ["LKVERIFY_CACHE"] = "off"

# the same SymPy cache size as ``import lkverify`` sets (test modules import SymPy first)
from lkverify import SYMPY_CACHE_SIZE  # noqa: E402

os.environ.setdefault("SYMPY_CACHE_SIZE", str(SYMPY_CACHE_SIZE))
