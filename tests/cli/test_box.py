"""``lkverify check ITEM --box NAME=LO:HI`` (issue 23): one line and exit 2 for bad boxes; JSON of a box run."""

import json

import pytest

from lkverify.cli import main

T3 = "aleksandrov2023.theorem3"


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("argv, needle", [
    (["check", T3, "--box", "b=1:x"], "unknown name 'x'"),
    (["check", T3, "--box", "b=2:1"], "LO ≤ HI"),
    (["check", T3, "--box", "b=1"], "NAME=LO:HI"),
    (["check", T3, "--box", "b=nan:1"], "finite"),
    (["check", T3, "--box", "tau=-1:1"], "tau > 0"),
    (["check", T3, "--box", "Theta=1:2"], "scalar parameter"),
    (["check", T3, "--box", "zz=1:2"], "no such parameter"),
    (["check", T3, "--box", "b=-1:0", "--set", "b=-1"], "also given with --set"),
    (["check", T3, "--box", "b=-1:0", "--box", "b=-2:0"], "twice"),
    (["check", T3, "--box", "b=-1:0", "--max-boxes", "0"], "--max-boxes"),
    (["check", T3, "--max-boxes", "3"], "only with --box"),
    (["check", "aleksandrov2023.fig6", "--box", "b=-1:0"], "expected theorems"),
    (["check", T3, "--box", "b=__import__('os').getcwd():1"], "b"),
])
def test_bad_boxes_exit_2_with_one_line(capsys, argv, needle):
    code, out, err = run(capsys, *argv, "--quiet")
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and needle in err and "Traceback" not in err


def test_a_box_across_the_hypothesis_is_failed_at_a_point_in_json(capsys):
    code, out, _ = run(capsys, "check", T3, "--box", "b=-1/10:1/10", "--box", "tau=9/10:11/10", "--json", "--quiet")
    assert code == 1
    doc = json.loads(out)
    assert doc["status"] == "failed" and doc["box"] == {"b": ["-1/10", "1/10"], "tau": ["9/10", "11/10"]}
    (f,) = doc["failing"]
    assert f["link"] == "hypothesis b*tau < a" and f["point"]["b"] == "1/10"
    assert doc["verdict"].startswith("failed at the point b = 1/10")


def test_a_box_variable_written_in_a_set_value(capsys):
    code, out, err = run(capsys, "check", T3, "--set", "F=diag(h,h,h)", "--box", "h=-1/10:1", "--quiet")
    assert code == 2 and "positive-definite matrix at every point" in err
    code, out, err = run(capsys, "check", T3, "--set", "F=diag(h,h,h)", "--quiet")
    assert code == 2 and "unknown name 'h'" in err
