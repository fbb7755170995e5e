"""Gain sweeps: where in the gain plane a theorem applies, the linearisation is stable, the system converges.

``lkverify sweep ITEM --grid NAME=START:STOP:N … [--set …]`` (:mod:`.cli`) or :func:`sweep` from
Python: every grid point gets its parameter check and the catalogued theorems' hypotheses with
margins (exact, :mod:`.plan`), the linearisation's spectral abscissa (estimated) and a simulation
(:mod:`.evaluate`), run on Dask (:mod:`.engine`), written as a Parquet table and drawn as a map
(:mod:`.figure`) with the paper's gains marked (:mod:`.marks`).  With ``--prove`` every cell is
a box on which the theorems' chains are run (:mod:`.prove`), the map's proved layer.
"""

from .engine import DEFAULT_CHUNK_SIZE, SweepOptions, SweepResult, sweep
from .evaluate import CLASSES, Simulation, classify, run_chunk
from .grid import Axis, Grid, MAX_POINTS
from .figure import plot_map
from .marks import Mark, paper_marks
from .plan import Plan, build_plan, load_example

__all__ = ["Axis", "CLASSES", "DEFAULT_CHUNK_SIZE", "Grid", "MAX_POINTS", "Mark", "Plan", "Simulation", "SweepOptions",
           "SweepResult", "build_plan", "classify", "load_example", "paper_marks", "plot_map",
           "run_chunk", "sweep"]
