"""The sweep engine on a toy delay equation with a closed-form stability boundary.

x'(t) = −a x(t − τ) is asymptotically stable iff 0 < aτ < π/2; the sweep must find
converged points below the boundary and not above it, give the same table serially and
on a two-worker LocalCluster, resume from finished chunks, and report bad input and
troubled points clearly.
"""

import math
import sys

import cloudpickle
import numpy as np
import pyarrow.parquet as pq
import pytest

from lkverify import Equation, InputError, Parameters, Series, System, Term, Vector, t
from lkverify.catalogue.examples import Example
from lkverify.simulate import Run
from lkverify.sweep import Grid, SweepOptions, build_plan, classify, sweep
from lkverify import parallel as cluster_module
from lkverify.sweep import engine as engine_module
from lkverify.simulate.solver import Outcome

cloudpickle.register_pickle_by_value(sys.modules[__name__])   # Dask workers need the toy's distance by value


def distance(states):
    return np.abs(states["x"][:, 0])


def toy(t_end=40.0):
    P = Parameters()
    a = P.scalar("a", positive=True, default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    system = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P, name="toy")
    return Example("user.toy", runs=[Run("x ≡ 1", system, {"a": "1/2"}, {"x": [1]})], t_end=t_end,
                   series=[Series("x", lambda S: S["x"][:, 0])], distance=distance, equilibrium={"x": [0]})


SERIAL = SweepOptions(scheduler="synchronous", chunk_size=3)


def columns(table, names):
    """Column values with NaN written as the string 'nan' (NaN != NaN would hide equal tables)."""
    def same(v):
        return "nan" if isinstance(v, float) and math.isnan(v) else v
    return {n: [same(v) for v in table.column(n).to_pylist()] for n in names}


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    out = tmp_path_factory.mktemp("serial") / "toy.parquet"
    return sweep(toy(), grid=["a=0.25:2.5:10"], out=out, options=SERIAL)


def test_boundary_a_tau_pi_over_2(serial):
    a = np.array(serial.table.column("a").to_pylist())
    cls = np.array(serial.table.column("simulated").to_pylist())
    assert serial.complete and serial.table.num_rows == 10
    assert set(cls[a < 1.2]) == {"converged"}           # well inside aτ < π/2
    assert "converged" not in set(cls[a > math.pi / 2])   # outside: oscillations grow
    assert set(cls[a > 2.0]) <= {"diverged", "bounded"}


def test_table_on_disk_has_meta_and_rows(serial):
    tbl = pq.read_table(serial.path)
    assert tbl.num_rows == 10 and b"lkverify.sweep" in tbl.schema.metadata
    assert not (serial.path.parent / (serial.path.name + ".parts")).exists()     # parts removed when complete
    t_conv = np.array(tbl.column("t_to_1e-2").to_pylist(), dtype=float)
    a = np.array(tbl.column("a").to_pylist())
    # the slowest of the converged points converges last
    conv = np.isfinite(t_conv)
    assert conv.any() and t_conv[conv][np.argmax(a[conv])] == np.nanmax(t_conv)


def test_linear_margin_matches_the_closed_form(serial):
    a = np.array(serial.table.column("a").to_pylist())
    verdict = np.array(serial.table.column("linear_verdict").to_pylist())
    assert set(verdict[a < math.pi / 2 - 0.1]) == {"stable"}
    assert set(verdict[a > math.pi / 2 + 0.1]) == {"unstable"}


@pytest.mark.slow
def test_two_worker_local_cluster_equals_serial(serial, tmp_path):
    par = sweep(toy(), grid=["a=0.25:2.5:10"], out=tmp_path / "par.parquet",
                options=SweepOptions(workers=2, chunk_size=3))
    names = [n for n in serial.table.column_names]
    assert par.complete
    assert columns(par.table, names) == columns(serial.table, names)


@pytest.mark.slow
@pytest.mark.parametrize("method", ["forkserver", "fork", "spawn"])
def test_every_start_method_gives_the_serial_table(serial, tmp_path, monkeypatch, method):
    """A local cluster's workers from a fork server (Linux default), forked or spawned: the same table."""
    monkeypatch.setenv("LKVERIFY_START_METHOD", method)
    assert cluster_module._start_method() == method
    par = sweep(toy(), grid=["a=0.25:2.5:10"], out=tmp_path / f"{method}.parquet",
                options=SweepOptions(workers=2, chunk_size=3))
    names = [n for n in serial.table.column_names]
    assert par.complete and "cluster start" in par.timings
    assert columns(par.table, names) == columns(serial.table, names)


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the fork server is Linux's default")
def test_the_fork_servers_workers_start_with_the_preloaded_modules(monkeypatch):
    monkeypatch.delenv("LKVERIFY_START_METHOD", raising=False)
    watched = ("lkverify.sweep.evaluate", "lkverify.simulate.dop853", "lkverify.catalogue.report_job")

    def loaded():   # pickled by value: importing nothing of lkverify on the worker
        import sys as worker_sys

        return tuple(name in worker_sys.modules for name in watched)

    cluster_module.prepare(cluster_module.Cluster(workers=1))
    ((_, got, exc),) = cluster_module.run_tasks(loaded, {0: ()}, cluster_module.Cluster(workers=1))
    assert exc is None
    assert got == (True, True, False)       # PRELOAD, and nothing else of lkverify's


def test_the_start_method_is_a_fork_server_on_linux_and_a_bad_one_is_refused(monkeypatch):
    monkeypatch.delenv("LKVERIFY_START_METHOD", raising=False)
    assert cluster_module._start_method() == ("forkserver" if sys.platform.startswith("linux") else "spawn")
    monkeypatch.setenv("LKVERIFY_START_METHOD", "threads")
    with pytest.raises(InputError, match="LKVERIFY_START_METHOD: expected fork, spawn or forkserver, got 'threads'"):
        cluster_module._start_method()
    with pytest.raises(InputError, match="LKVERIFY_START_METHOD"):   # prepare asks the same question
        cluster_module.prepare(cluster_module.Cluster())


def test_prepare_starts_nothing_for_a_given_scheduler_or_in_process(monkeypatch):
    import multiprocessing.forkserver as fs

    monkeypatch.delenv("LKVERIFY_START_METHOD", raising=False)
    monkeypatch.setattr(fs, "ensure_running", lambda: pytest.fail("a fork server was started"))
    for where in (cluster_module.Cluster(scheduler="synchronous"), cluster_module.Cluster(scheduler="tcp://h:1")):
        cluster_module.prepare(where)
    monkeypatch.setenv("LKVERIFY_START_METHOD", "spawn")
    cluster_module.prepare(cluster_module.Cluster())


def test_a_small_sweep_runs_in_process_without_a_cluster(serial, tmp_path, monkeypatch):
    """No Dask cluster for a sweep under IN_PROCESS_POINTS points (issue 27), unless a scheduler or workers are given."""
    def no_cluster(options):
        raise AssertionError("a cluster was started for a small sweep")

    monkeypatch.setattr(cluster_module, "_client", no_cluster)
    res = sweep(toy(), grid=["a=0.25:2.5:10"], out=tmp_path / "small.parquet", options=SweepOptions(chunk_size=3))
    names = serial.table.column_names
    assert res.complete and res.timings.get("in process") and columns(res.table, names) == columns(serial.table, names)
    with pytest.raises(AssertionError, match="cluster was started"):   # "local" and --workers still ask for one
        sweep(toy(), grid=["a=0.25:2.5:10"], out=tmp_path / "local.parquet", options=SweepOptions(scheduler="local"))
    with pytest.raises(AssertionError, match="cluster was started"):
        sweep(toy(), grid=["a=0.25:2.5:10"], out=tmp_path / "w.parquet", options=SweepOptions(workers=2))
    assert engine_module.IN_PROCESS_POINTS > 10


@pytest.mark.slow
def test_existing_scheduler_with_and_without_workers(serial, tmp_path, monkeypatch):
    from distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        res = sweep(toy(), grid=["a=0.25:2.5:10"], out=tmp_path / "ext.parquet",
                    options=SweepOptions(scheduler=cluster.scheduler_address, chunk_size=4))
    names = serial.table.column_names
    assert res.complete and columns(res.table, names) == columns(serial.table, names)
    monkeypatch.setattr(cluster_module, "WORKER_WAIT_SECONDS", 1.0)
    with LocalCluster(n_workers=0, processes=False, dashboard_address=None) as empty:
        with pytest.raises(InputError, match="no workers"):
            sweep(toy(), grid=["a=0.5:1:2"], out=tmp_path / "none.parquet",
                  options=SweepOptions(scheduler=empty.scheduler_address))


def test_resume_reuses_finished_chunks(tmp_path, monkeypatch):
    real = engine_module.run_chunk
    calls = []

    def flaky(sim, points, valid):
        calls.append(len(points))
        if len(calls) == 2:
            raise RuntimeError("worker lost")
        return real(sim, points, valid)

    out = tmp_path / "resume.parquet"
    monkeypatch.setattr(engine_module, "run_chunk", flaky)
    first = sweep(toy(), grid=["a=0.25:2.5:10"], out=out, options=SERIAL)
    assert not first.complete and len(first.errors) == 1
    assert "undecided" in first.table.column("simulated").to_pylist()
    assert (tmp_path / "resume.parquet.parts").is_dir()
    monkeypatch.setattr(engine_module, "run_chunk", real)
    second = sweep(toy(), grid=["a=0.25:2.5:10"], out=out, options=SERIAL)
    assert second.complete and second.reused == 3                    # 4 chunks of ≤ 3 points, one recomputed
    fresh = sweep(toy(), grid=["a=0.25:2.5:10"], out=tmp_path / "fresh.parquet", options=SERIAL)
    names = fresh.table.column_names
    assert columns(second.table, names) == columns(fresh.table, names)


def test_invalid_and_troubled_points_get_a_status(tmp_path):
    # a ≥ 0 is the parameter's hypothesis (positive): a = 0 is invalid, not simulated
    res = sweep(toy(), grid=["a=0:4:3"], out=tmp_path / "s.parquet", options=SERIAL)
    cls = res.table.column("simulated").to_pylist()
    reason = res.table.column("invalid_reason").to_pylist()
    assert cls[0] == "invalid" and "a" in reason[0] and cls[2] == "diverged"
    tiny = sweep(toy(), grid=["a=0.5:1:2"], out=tmp_path / "b.parquet",
                 options=SweepOptions(scheduler="synchronous", max_steps=5))
    assert set(tiny.table.column("simulated").to_pylist()) == {"undecided"}
    assert set(tiny.table.column("outcome").to_pylist()) == {"budget"}


def test_swept_delay(tmp_path):
    res = sweep(toy(), grid=["tau=0.5:2.5:3"], sets=["a=1"], out=tmp_path / "tau.parquet", options=SERIAL)
    cls = res.table.column("simulated").to_pylist()
    assert cls[0] == "converged" and cls[2] in ("bounded", "diverged")         # aτ = 0.5 vs 2.5


@pytest.mark.parametrize("grid, sets, message", [
    (["q=0:1:3"], [], "no parameter q"),
    (["a=0:1:0"], [], "zero points"),
    (["a=0:1:x"], [], "whole number"),
    (["a=0:1:3", "a=1:2:3"], [], "swept twice"),
    (["a=0:1:3"], ["a=2"], "both swept and set"),
    (["a=0:1:3"], ["zz=1"], "no such parameter"),
])
def test_bad_input(tmp_path, grid, sets, message):
    with pytest.raises(InputError, match=message):
        sweep(toy(), grid=grid, sets=sets, out=tmp_path / "x.parquet", options=SERIAL)


def test_bad_output_path_and_scheduler(tmp_path, monkeypatch):
    monkeypatch.setattr(cluster_module, "SCHEDULER_TIMEOUT_SECONDS", 2.0)
    with pytest.raises(InputError, match="does not exist"):
        sweep(toy(), grid=["a=0:1:3"], out=tmp_path / "no" / "x.parquet", options=SERIAL)
    with pytest.raises(InputError, match="ending in .parquet"):
        sweep(toy(), grid=["a=0:1:3"], out=tmp_path / "x.csv", options=SERIAL)
    with pytest.raises(InputError, match="cannot reach a Dask scheduler"):
        sweep(toy(), grid=["a=0.5:1:2"], out=tmp_path / "x.parquet",
              options=SweepOptions(scheduler="tcp://127.0.0.1:9", chunk_size=2))


def test_classify_levels():
    tt = np.linspace(0.0, 10.0, 101)
    assert classify(Outcome.SUCCESS, tt, 0.02 * np.exp(-tt), 1e-2)[1] == pytest.approx(0.7, abs=0.05)
    assert classify(Outcome.BUDGET, tt, np.zeros(101), 1e-2)[0] == "undecided"
    assert classify(Outcome.STEP_COLLAPSE, tt, np.zeros(101), 1e-2)[0] == "undecided"
    # converges then leaves again: not converged
    d = np.where(tt < 9.5, 1e-3, 1.0)
    assert classify(Outcome.SUCCESS, tt, d, 1e-2)[0] == "bounded"


def test_plan_values_at_substitutes_templates():
    grid = Grid.parse(["b=-1:1:3"])
    plan = build_plan(toy(), grid=Grid.parse(["a=1:2:2"]), sets=[])
    assert plan.values_at({"a": 2})["a"] == 2 and plan.swept_parameters == ("a",)
    assert grid.size == 3


def memory_toy():
    """x' = −a x − ∫_0^t x(ξ)/(1 + t − ξ)³ dξ: a general (non-exponential) kernel, quadrature only."""
    from lkverify import memory_integral, xi

    P = Parameters()
    a = P.scalar("a", positive=True, default=1)
    x = Vector("x", 1)
    system = System([Equation(x, [Term(-a * x(t)[0] - memory_integral(x(xi)[0] / (1 + t - xi) ** 3))])],
                    parameters=P, name="memory toy")
    return Example("user.memory", runs=[Run("x ≡ 1", system, {"a": "1"}, {"x": [1]})], t_end=6.0,
                   series=[Series("x", lambda S: S["x"][:, 0])], distance=distance)


@pytest.mark.slow
def test_a_system_the_fast_path_does_not_take_runs_point_by_point(tmp_path):
    res = sweep(memory_toy(), grid=["a=1:3:2"], out=tmp_path / "m.parquet",
                options=SweepOptions(scheduler="synchronous", samples=61))
    assert "point by point" in res.meta["simulation"] or "on its own" in res.meta["simulation"]
    assert res.table.column("simulated").to_pylist() == ["converged", "converged"]
    assert res.table.column("linear_verdict").to_pylist() == ["", ""]       # no equilibrium declared
    assert "no equilibrium" in res.meta["linear"]


def test_budget_spent_leaves_points_undecided_and_resumable(tmp_path):
    out = tmp_path / "budget.parquet"
    res = sweep(toy(), grid=["a=0.25:2.5:10"], out=out,
                options=SweepOptions(scheduler="synchronous", chunk_size=3, budget=1e-9))
    assert not res.complete
    assert set(res.table.column("simulated").to_pylist()) == {"undecided"}
    assert set(res.table.column("outcome").to_pylist()) == {"budget"}
    again = sweep(toy(), grid=["a=0.25:2.5:10"], out=out, options=SERIAL)
    assert again.complete and again.reused == 0 and "undecided" not in again.table.column("simulated").to_pylist()
