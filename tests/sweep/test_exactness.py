"""One exactness policy in the sweep: a float value makes a theorem's region at most ``certified``.

Paper 002's Fig. 3 with τ given as the Python float 0.9 (binary 0.9000000000000000222…, not 9/10):
the hypothesis bτ < a is decided at the binary value, but the region is never ``exact``
(lkverify.status); the same run with τ = "0.9" (the decimal 9/10) stays ``exact``.
"""

import copy
import dataclasses

import pytest

from lkverify.sweep import Grid, SweepOptions, build_plan, load_example, sweep

GRID = ["b=2:3:3", "h=0.7:0.7:1"]
SETS = ["F=diag(h,h,h)"]


def fig3_with(tau):
    ex = copy.copy(load_example("aleksandrov2023.fig3"))
    run = ex.runs[0]
    ex.runs = [dataclasses.replace(run, values={**run.values, "tau": tau})]
    return ex


@pytest.mark.parametrize("tau, expected", [("0.9", "exact"), (0.9, "certified")])
def test_float_value_makes_the_region_certified(tmp_path, tau, expected):
    res = sweep(fig3_with(tau), grid=GRID, sets=SETS, out=tmp_path / "f3.parquet",
                options=SweepOptions(scheduler="synchronous", t_end=1.0))
    assert res.meta["theorem_status"] == {"theorem3": expected}
    assert res.table.column("applies:theorem3").to_pylist() == [True, False, False]    # b < 2/0.9 ≈ 2.22: b = 2 only


def test_plan_records_the_float_values():
    assert build_plan(fig3_with(0.9), grid=Grid.parse(GRID), sets=SETS).floated == frozenset({"tau"})
    assert build_plan(fig3_with("0.9"), grid=Grid.parse(GRID), sets=SETS).floated == frozenset()
