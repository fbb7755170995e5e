"""The proved layer of a sweep (issue 23, point 4): cells as boxes, the chain per cell, in-region runs.

Default run: the cells, the in-region history, and the cross-check that must fail (an envelope too
tight for the run raises InternalError, never a map).  Slow: Fig. 6's and Fig. 3's (b, h) planes
around the paper's gains, every proved cell inside the hypotheses' region and rechecked by `check`
at a random interior point.
"""

import json

import numpy as np
import pytest
import sympy

from lkverify.catalogue.boxrun import BoxPiece, BoxStatus
from lkverify.declare.boxes import ParameterBox
from lkverify.errors import InternalError
from lkverify.report.results import Kind, Report, Result
from lkverify.status import Status
from lkverify.sweep.grid import Grid
from lkverify.sweep.prove import _history, cell_box, in_region_run

R = sympy.Rational


def test_cells_are_the_maps_cells_half_a_step_each_side():
    g = Grid.parse(["b=-11/10:-9/10:2", "h=9/10:11/10:3"])
    assert cell_box(g, 0) == {"b": (R(-6, 5), R(-1)), "h": (R(17, 20), R(19, 20))}
    cells = [cell_box(g, k) for k in range(g.size)]
    # the cells tile [−6/5, −4/5] × [17/20, 23/20] without overlap: the b-widths and h-widths add up
    assert sum((c["b"][1] - c["b"][0]) * (c["h"][1] - c["h"][0]) for c in cells) == R(2, 5) * R(3, 10)


def test_the_in_region_history_has_the_requested_norm_and_keeps_unit_vectors_unit():
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    values = theorem3.parameters.resolve({}, use_defaults=True)
    history, chi = _history(theorem3.system, values, {"s": "r", "omega": [0, 0, 0]}, 1e-3)
    s = np.asarray(history["s"])
    r = np.array([float(x) for x in values["r"]])
    assert abs(np.linalg.norm(s) - 1) < 1e-12 and abs(chi - 1e-3) < 1e-12
    assert abs(np.sqrt(np.sum((s - r) ** 2) + np.sum(np.asarray(history["omega"]) ** 2)) - 1e-3) < 1e-12


def _piece(d, rate, delta=1e-3):
    rows = (Result(Kind.CONSTANT, "delta_tilde", Status.CERTIFIED, {"value": delta}, ""),
            Result(Kind.ENVELOPE, "envelope d1", Status.CERTIFIED, {"d": d, "rate": rate, "p": 1.5}, ""),
            Result(Kind.ENVELOPE, "envelope d2", Status.CERTIFIED, {"d": d, "rate": rate, "p": 1.5}, ""))
    return BoxPiece(ParameterBox({"b": ("-11/10", "-9/10")}), BoxStatus.ESTABLISHED,
                    Report("aleksandrov2023.theorem3", {}, rows, "established"))


def test_an_envelope_the_run_leaves_is_an_internal_error_and_a_loose_one_passes():
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    eq = {"s": "r", "omega": [0, 0, 0]}
    with pytest.raises(InternalError, match="leaves the certified envelope"):
        in_region_run(theorem3, {}, _piece(d=0.5, rate=1.0), eq, t_end=5)     # ‖s−r‖(0) ≈ 0.7‖χ‖ > 0.5‖χ‖
    ratio = in_region_run(theorem3, {}, _piece(d=20.0, rate=0.01), eq, t_end=5)
    assert ratio > 0 and ratio < 1


@pytest.mark.slow
@pytest.mark.parametrize("item, grid", [
    ("aleksandrov2023.fig6", ["b=-11/10:-9/10:2", "h=9/10:11/10:2"]),
    ("aleksandrov2023.fig3", ["b=-21/10:-19/10:2", "h=13/20:3/4:2"]),
])
def test_proved_cells_lie_in_the_hypotheses_region_and_hold_at_random_interior_points(tmp_path, item, grid):
    from lkverify.catalogue.loader import find_items
    from lkverify.sweep import SweepOptions, sweep

    res = sweep(item, grid=grid, sets=["F=diag(h,h,h)"], out=tmp_path / "s.parquet",
                options=SweepOptions(scheduler="synchronous", prove=True, t_end=50))
    tbl = res.table.to_pydict()
    proved = np.array(tbl["proved:theorem3"]) == "established"
    applies = np.array(tbl["applies:theorem3"], dtype=bool)
    assert proved.any() and np.all(applies[proved])
    assert np.all(np.isfinite(np.array(tbl["proved_envelope:theorem3"])[proved]))
    (theorem,) = find_items("aleksandrov2023.theorem3")
    rng = np.random.default_rng(1)
    k = int(rng.choice(np.flatnonzero(proved)))
    cell = cell_box(res.plan.grid, k)
    point = {n: lo + (hi - lo) * R(int(rng.integers(1, 99)), 100) for n, (lo, hi) in cell.items()}
    choices = json.loads(tbl["proved_choices:theorem3"][k])[0]
    h = point.pop("h")
    rep = theorem.run({**res.plan.example.runs[0].values, **{n: str(v) for n, v in point.items()},
                       "F": f"diag({h},{h},{h})", **choices})
    assert rep.verdict.startswith("established"), rep.verdict
