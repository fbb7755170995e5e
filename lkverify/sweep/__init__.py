"""Gain sweeps: where in the gain plane a theorem applies, the linearisation is stable, the system converges.

``lkverify sweep ITEM --grid NAME=START:STOP:N … [--set …]`` (:mod:`.cli`) or :func:`sweep` from
Python: every grid point gets its parameter check and the catalogued theorems' hypotheses with
margins (exact, :mod:`.plan`), the linearisation's spectral abscissa (estimated) and a simulation
(:mod:`.evaluate`), run on Dask (:mod:`.engine`), written as a Parquet table and drawn as a map
(:mod:`.figure`) with the paper's gains marked (:mod:`.marks`).  With ``--prove`` every cell is
a box on which the theorems' chains are run (:mod:`.prove`), the map's proved layer.
"""

import importlib

__all__ = ["Axis", "CLASSES", "DEFAULT_CHUNK_SIZE", "Grid", "MAX_POINTS", "Mark", "Plan", "Simulation", "SweepOptions",
           "SweepResult", "build_plan", "classify", "load_example", "paper_marks", "plot_map",
           "run_chunk", "sweep"]

#: public name → the submodule that defines it, imported on first use (PEP 562): the command line reads
#: :mod:`.cli`'s help without importing NumPy, Dask or the simulator
_SOURCES = {"DEFAULT_CHUNK_SIZE": ".engine", "SweepOptions": ".engine", "SweepResult": ".engine", "sweep": ".engine",
            "CLASSES": ".evaluate", "Simulation": ".evaluate", "classify": ".evaluate", "run_chunk": ".evaluate",
            "Axis": ".grid", "Grid": ".grid", "MAX_POINTS": ".grid", "plot_map": ".figure", "Mark": ".marks",
            "paper_marks": ".marks", "Plan": ".plan", "build_plan": ".plan", "load_example": ".plan"}


def __getattr__(name: str):
    """The public name ``name``, imported from its submodule on first use and kept."""
    source = _SOURCES.get(name)
    if source is None:
        raise AttributeError(f"module 'lkverify.sweep' has no attribute {name!r}")
    value = getattr(importlib.import_module(source, __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
