"""``lkverify sweep`` on the command line: the acceptance example on a small grid, and bad input."""

import json

import pyarrow.parquet as pq
import pytest

from lkverify.cli import main

FIG1 = ["sweep", "aleksandrov2023.fig1", "--set", "F=diag(h,h,h)", "--scheduler", "synchronous", "--quiet"]


@pytest.fixture(scope="module")
def fig1_small(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fig1")
    out = folder / "fig1.parquet"
    # b = −2, 2 and h = 0.7 are grid points: the gains of Figs. 1 and 2 lie on the grid
    code = main([*FIG1, "--grid", "b=-2:2:3", "--grid", "h=0.7:1.4:2", "--t-end", "100", "--out", str(out), "--json"])
    return code, out, folder


def test_writes_table_and_map_and_marks_the_papers_gains(fig1_small, capsys):
    code, out, folder = fig1_small
    assert code == 0
    table = pq.read_table(out)
    assert table.num_rows == 6
    meta = json.loads(table.schema.metadata[b"lkverify.sweep"])
    assert meta["item"] == "aleksandrov2023.fig1" and meta["sets"] == {"F": "diag(h,h,h)"}
    assert (folder / "fig1.png").stat().st_size > 10_000
    rows = {(r["b"], r["h"]): r for r in table.to_pylist()}
    assert rows[(2.0, 0.7)]["simulated"] == "converged"             # Fig. 1
    assert rows[(-2.0, 0.7)]["simulated"] in ("bounded", "diverged")   # Fig. 2
    assert rows[(-2.0, 0.7)]["linear_verdict"] == "unstable" and rows[(2.0, 0.7)]["linear_verdict"] == "stable"
    assert not any(rows[k]["applies:theorem3"] for k in rows)         # μ = 1: Theorem 3 needs μ > 1
    # the exact grid values beside the doubles (h = 0.7 is 7/10, not 0.69999…)
    assert rows[(2.0, 0.7)]["h:exact"] == "7/10" and rows[(-2.0, 1.4)]["h:exact"] == "7/5"
    assert {r["b:exact"] for r in rows.values()} == {"-2", "0", "2"}


def test_json_report_has_the_marks(tmp_path, capsys):
    out = tmp_path / "m.parquet"
    code = main([*FIG1, "--grid", "b=-2:2:2", "--grid", "h=0.7:0.7:1", "--t-end", "100", "--out", str(out), "--json"])
    report = json.loads(capsys.readouterr().out)
    assert code == 0
    marks = {r["name"]: r for r in report["results"] if r["name"].startswith("Fig.")}
    assert set(marks) == {"Fig. 1 (b = 2, h = 7/10)", "Fig. 2 (b = -2, h = 7/10)"}
    assert marks["Fig. 1 (b = 2, h = 7/10)"]["value"]["value"] == "converged"
    assert all(r["status"] == "simulated" for r in marks.values())


def test_theorem3_region_at_mu_2(tmp_path, capsys):
    # Fig. 3's gains (μ = 2): Theorem 3 applies where bτ < a, i.e. b < 2/0.9 = 20/9, decided exactly
    out = tmp_path / "f3.parquet"
    code = main(["sweep", "aleksandrov2023.fig3", "--set", "F=diag(h,h,h)", "--grid", "b=2:2.5:6", "--grid",
                 "h=0.7:0.7:1", "--t-end", "5", "--scheduler", "synchronous", "--quiet", "--out", str(out)])
    assert code in (0, 1)
    table = pq.read_table(out)
    b = table.column("b").to_pylist()
    applies = table.column("applies:theorem3").to_pylist()
    assert applies == [x < 20 / 9 for x in b]           # 2, 2.1, 2.2 hold; 2.3, 2.4, 2.5 fail
    margins = table.column("margin:theorem3:1").to_pylist()
    assert margins[0] == pytest.approx(2 - 2 * 0.9)


@pytest.mark.parametrize("argv, message", [
    (["--grid", "b=0:1:0"], "zero points"),
    (["--grid", "zeta=0:1:3"], "no parameter zeta"),
    (["--grid", "b=0:1:3", "--out", "/nonexistent/x.parquet"], "does not exist"),
    (["--grid", "b=0:1:3", "--plot", "x.txt"], "expected a file name ending in"),
    (["--grid", "b=0:1:3", "--t-end", "-1"], "t-end"),
    (["--grid", "b=0:1:3", "--t-end", "nan"], "t-end"),
    (["--grid", "b=nan:1:3"], "--grid"),
    (["--grid", "b=0:1:3", "--set", "F=diag(h,h,h)"], "h"),
    (["--grid", "h=0:1:3", "--set", "F=__import__('os')"], "F"),
])
def test_bad_input_is_one_line_and_exit_2(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code = main(["sweep", "aleksandrov2023.fig1", "--scheduler", "synchronous", *argv])
    err = capsys.readouterr().err
    assert code == 2
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_no_grid_and_not_an_example(capsys):
    assert main(["sweep", "aleksandrov2023.fig1"]) == 2
    assert "--grid" in capsys.readouterr().err
    assert main(["sweep", "aleksandrov2023.theorem3", "--grid", "b=0:1:3"]) == 2
    assert "expected one example" in capsys.readouterr().err


def test_point_outside_a_hypothesis_is_invalid_not_an_error(tmp_path):
    out = tmp_path / "h.parquet"
    code = main([*FIG1, "--grid", "b=2:2:1", "--grid", "h=-0.5:0.5:3", "--t-end", "20", "--out", str(out)])
    table = pq.read_table(out)
    cls = table.column("simulated").to_pylist()
    reasons = table.column("invalid_reason").to_pylist()
    assert code == 0
    assert cls[:2] == ["invalid", "invalid"] and "positive-definite" in reasons[0]      # h = −0.5, 0: F ⊁ 0
    assert cls[2] != "invalid"


def test_an_unwritable_folder_is_bad_input_before_any_work(capsys):
    # /proc: os.access says writable for root, creating a file fails: refused up front, exit 2
    assert main(["sweep", "aleksandrov2023.fig1", "--grid", "b=0:1:2", "--out", "/proc/x.parquet"]) == 2
    err = capsys.readouterr().err
    assert "--out /proc/x.parquet: cannot write" in err and err.count("\n") == 1
    assert main(["sweep", "aleksandrov2023.fig1", "--grid", "b=0:1:2", "--plot", "/proc/x.png"]) == 2
    assert "--plot: cannot write" in capsys.readouterr().err


def test_theorem3_boundary_is_exact_at_a_tiny_difference(tmp_path):
    # b·τ < a with a = 2, τ = 9/10: b = 20/9 − 10⁻¹² holds, b = 20/9 fails (margin exactly 0, strict)
    out = tmp_path / "edge.parquet"
    code = main(["sweep", "aleksandrov2023.fig3", "--set", "F=diag(h,h,h)", "--grid", "b=20/9-10**-12:20/9:2",
                 "--grid", "h=0.7:0.7:1", "--t-end", "1", "--scheduler", "synchronous", "--quiet", "--out", str(out),
                 "--json"])
    table = pq.read_table(out)
    assert code in (0, 1)
    assert table.column("applies:theorem3").to_pylist() == [True, False]
    meta = json.loads(table.schema.metadata[b"lkverify.sweep"])
    assert meta["theorem_status"] == {"theorem3": "exact"}


def test_an_irrational_margin_makes_the_region_certified_not_exact(tmp_path, capsys):
    out = tmp_path / "irr.parquet"
    main(["sweep", "aleksandrov2023.fig3", "--set", "F=diag(h,h,h)", "--set", "tau=sqrt(2)/2", "--grid", "b=2:3:3",
          "--grid", "h=0.7:0.7:1", "--t-end", "1", "--scheduler", "synchronous", "--quiet", "--out", str(out), "--json"])
    report = json.loads(capsys.readouterr().out)
    row = next(r for r in report["results"] if r["kind"] == "hypothesis")
    assert row["status"] == "certified"
    # b < 2/(√2/2) = 2√2 ≈ 2.83: b = 2, 2.5 hold, b = 3 fails
    assert pq.read_table(out).column("applies:theorem3").to_pylist() == [True, True, False]


def test_a_mark_that_disagrees_with_its_figure_fails(tmp_path, capsys, monkeypatch):
    import lkverify.sweep.cli as sweep_cli

    real = sweep_cli.run_chunk

    def contrary(sim, points, valid):       # as if the simulation at the paper's gains said the opposite
        cols = real(sim, points, valid)
        cols["simulated"] = cols["simulated"].copy()
        cols["simulated"][:] = ["bounded" if c == "converged" else "converged" for c in cols["simulated"]]
        return cols

    monkeypatch.setattr(sweep_cli, "run_chunk", contrary)
    code = main([*FIG1, "--grid", "b=2:2:1", "--grid", "h=0.7:0.7:1", "--t-end", "1", "--out",
                 str(tmp_path / "c.parquet"), "--json"])
    report = json.loads(capsys.readouterr().out)
    marks = {r["name"].split(" (")[0]: r["status"] for r in report["results"] if r["name"].startswith("Fig.")}
    assert code == 1 and marks == {"Fig. 1": "failed", "Fig. 2": "failed"}
