"""Results and reports: what every job returns, prints and serialises (the JSON card of DESIGN.md).

The names are loaded on first use (PEP 562), so that ``lkverify list`` can print the
schema key without importing SymPy.
"""


from .._lazy import lazy_exports

_SOURCES = {"Kind": ".results", "Report": ".results", "Result": ".results", "jsonable": ".results",
            "value_json": ".results", "check_writable_file": ".files", "save_figure": ".files",
            "SCHEMA_ID": ".schema", "validate": ".schema"}

__all__ = sorted(_SOURCES)


__getattr__, __dir__ = lazy_exports(__name__, _SOURCES, __all__)
