"""Lazy re-exports (PEP 562): a package's public names imported from their submodules on first use.

>>> import types, sys
>>> pkg = types.ModuleType("demo_pkg"); sys.modules["demo_pkg"] = pkg
>>> pkg.__getattr__, pkg.__dir__ = lazy_exports("demo_pkg", {"sqrt": "math"}, ["sqrt"])
>>> pkg.sqrt(4.0), "sqrt" in dir(pkg)
(2.0, True)
>>> pkg.nothing
Traceback (most recent call last):
    ...
AttributeError: module 'demo_pkg' has no attribute 'nothing'
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Mapping, Sequence

__all__ = ["lazy_exports"]


def lazy_exports(module_name: str, sources: Mapping[str, str], names: Sequence[str]):
    """``(__getattr__, __dir__)`` for the package ``module_name``: ``sources`` maps a public name to the
    (relative) submodule that defines it; a name is imported once and then kept in the package."""

    def __getattr__(name: str):
        source = sources.get(name)
        if source is None:
            raise AttributeError(f"module {module_name!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(source, module_name), name)
        setattr(sys.modules[module_name], name, value)
        return value

    def __dir__():
        return sorted(set(vars(sys.modules[module_name])) | set(names))

    return __getattr__, __dir__
