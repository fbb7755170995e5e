"""Results and reports: what every job returns, prints and serialises (the JSON card of DESIGN.md).

The names are loaded on first use (PEP 562), so that ``lkverify list`` can print the
schema key without importing SymPy.
"""

import importlib

_SOURCES = {"Kind": ".results", "Report": ".results", "Result": ".results", "jsonable": ".results",
            "value_json": ".results", "check_writable_file": ".files", "save_figure": ".files",
            "SCHEMA_ID": ".schema", "validate": ".schema"}

__all__ = sorted(_SOURCES)


def __getattr__(name):
    if name not in _SOURCES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(_SOURCES[name], __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
