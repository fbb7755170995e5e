"""Gain sweeps: where in the gain plane a theorem applies, the linearisation is stable, the system converges.

``lkverify sweep ITEM --grid NAME=START:STOP:N … [--set …]`` (:mod:`.cli`) or :func:`sweep` from
Python: every grid point gets its parameter check and the catalogued theorems' hypotheses with
margins (exact, :mod:`.plan`), the linearisation's spectral abscissa (estimated) and a simulation
(:mod:`.evaluate`), run on Dask (:mod:`.engine`), written as a Parquet table and drawn as a map
(:mod:`.figure`) with the paper's gains marked (:mod:`.marks`).  With ``--prove`` every cell is
a box on which the theorems' chains are run (:mod:`.prove`), the map's proved layer.
"""


__all__ = ["Axis", "CLASSES", "DEFAULT_CHUNK_SIZE", "Grid", "MAX_POINTS", "Mark", "Plan", "Simulation", "SweepOptions",
           "SweepResult", "build_plan", "classify", "load_example", "paper_marks", "plot_map",
           "run_chunk", "sweep"]

from .._lazy import lazy_exports

#: public name → the submodule that defines it, imported on first use (PEP 562): the command line reads
#: :mod:`.cli`'s help without importing NumPy, Dask or the simulator
_SOURCES = {"DEFAULT_CHUNK_SIZE": ".engine", "SweepOptions": ".engine", "SweepResult": ".engine", "sweep": ".engine",
            "CLASSES": ".evaluate", "Simulation": ".evaluate", "classify": ".evaluate", "run_chunk": ".evaluate",
            "Axis": ".grid", "Grid": ".grid", "MAX_POINTS": ".grid", "plot_map": ".figure", "Mark": ".marks",
            "paper_marks": ".marks", "Plan": ".plan", "build_plan": ".plan", "load_example": ".plan"}


__getattr__, __dir__ = lazy_exports(__name__, _SOURCES, __all__)
