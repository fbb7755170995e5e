"""``lkverify linear``: output, JSON, figure, bad input (one line on stderr, exit 2)."""

import json

import pytest

from lkverify.cli import main

CLASSIC = ["--set", "A=[[-2,0],[0,-0.9]]", "--set", "Ad=[[-1,0],[-1,-1]]"]


def test_json_and_plot(tmp_path, capsys):
    out = tmp_path / "spectrum.png"
    code = main(["linear", *CLASSIC, "--orders", "1", "--h-max", "8", "--plot", str(out), "--json", "--quiet"])
    assert code == 0 and out.stat().st_size > 10_000
    data = json.loads(capsys.readouterr().out)
    byname = {r["name"]: r for r in data["results"]}
    assert abs(byname["delay margin (spectral)"]["value"]["value"] - 6.17258) < 5e-6
    assert byname["delay margin (spectral)"]["status"] == "estimated"
    w = byname["certified delays (wirtinger)"]
    assert w["status"] == "exact" and abs(w["value"]["upper"] - 6.0593) < 1e-3
    assert "versions" in data and data["item"] == "linear"


def test_one_delay_above_the_margin_is_refuted_by_a_certified_root(capsys):
    code = main(["linear", *CLASSIC, "--orders", "2", "--h", "6.2", "--h-max", "8", "--quiet"])
    text = " ".join(capsys.readouterr().out.split())  # the table wraps its cells: read the words
    assert code == 1  # failed: a root in the open right half-plane, no LMI solved
    assert "stable at h = 31/5" in text and "failed" in text and "spectral abscissa at h = 31/5" in text
    assert "bessel-legendre" not in text


def test_a_stable_delay_beyond_the_orders_reach_is_undecided_not_failed(capsys):
    code = main(["linear", *CLASSIC, "--orders", "0", "--h", "6", "--h-max", "8", "--quiet"])   # Jensen: ≤ 4.47
    text = capsys.readouterr().out
    assert code == 1 and "undecided" in text and "failed" not in text


@pytest.mark.parametrize("args, fragment", [
    (["--set", "A=[[1,2]]"], "square"),
    (["--set", "A=[[1,0],[0,1]]", "--set", "Ad=[[1]]"], "2×2"),
    (["--set", "A=[[nan]]"], "finite"),
    (["--set", "A=[[-1]]", "--h", "-1"], "h ≥ 0"),
    (["--set", "A=[[-1]]", "--h", "abc"], "h ≥ 0"),
    (["--set", "A=[[-1]]", "--orders", "x"], "--orders"),
    (["--set", "A=[[-1]]", "--h-max", "nan"], "--h-max"),
    (["--set", "B=[[-1]]"], "unknown"),
    (["--set", "Ad=[[-1]]"], "got no A"),
    (["--set", "A=[[-1]]", "--plot", "x.txt"], "--plot"),
])
def test_bad_input_one_line_exit_2(args, fragment, capsys):
    code = main(["linear", *args])
    err = capsys.readouterr().err
    assert code == 2 and fragment in err and err.count("\n") == 1
