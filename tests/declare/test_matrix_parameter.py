"""``Parameters.matrix``: a general real matrix parameter (issue 27), and the README's matrix proof."""

import re
from pathlib import Path

import pytest
import sympy

from lkverify import Parameters
from lkverify.catalogue.loader import find_items
from lkverify.errors import InputError
from lkverify.status import Status

README = Path(__file__).resolve().parents[2] / "README.md"


def _spec():
    P = Parameters()
    P.matrix("A", 2, default=[[0, 1], [-2, -3]])
    return P, P["A"]


def test_a_general_matrix_is_accepted_exactly():
    P, spec = _spec()
    value = spec.check(sympy.Matrix([[0, 5], [-1, sympy.Rational(-3, 7)]]))   # not symmetric, not definite
    assert value == sympy.Matrix([[0, 5], [-1, sympy.Rational(-3, 7)]])
    sub = spec.substitution(value)
    assert sub[sympy.Symbol("A_12", real=True)] == 5 and len(sub) == 4
    assert P.resolve({})["A"] == sympy.Matrix([[0, 1], [-2, -3]])


def test_a_rectangular_matrix():
    P = Parameters()
    B = P.matrix("B", 2, 1)
    assert B.shape == (2, 1) and P["B"].check(sympy.Matrix([[1], [2]])).shape == (2, 1)


@pytest.mark.parametrize("value, needle", [
    (sympy.Matrix([[1, 2, 3]]), "2x2 matrix, got a 1x3"),             # wrong shape
    (sympy.Integer(3), "2x2 matrix such as"),                          # a scalar
    (sympy.Matrix([[1, sympy.Symbol("k")], [0, 1]]), "numeric"),      # a symbol
    (sympy.Matrix([[1, sympy.nan], [0, 1]]), "finite"),               # NaN
    (sympy.Matrix([[1, sympy.oo], [0, 1]]), "finite"),                # infinity
    (sympy.Matrix([[1, sympy.I], [0, 1]]), "real"),                   # complex
])
def test_each_side_condition_alone_is_refused(value, needle):
    _, spec = _spec()
    with pytest.raises(InputError, match=re.escape(needle)):
        spec.check(value)


@pytest.mark.parametrize("rows, cols", [(0, 2), (2, -1), (1.5, 2)])
def test_dimensions_must_be_positive_integers(rows, cols):
    with pytest.raises(InputError, match="dimensions"):
        Parameters().matrix("A", rows, cols)


def _matrix_proof(tmp_path):
    text = README.read_text(encoding="utf-8")
    (block,) = [b for b in re.findall(r"```python\n(.*?)```", text, flags=re.S) if b.startswith("# matrix_proof.py")]
    path = tmp_path / "matrix_proof.py"
    path.write_text(block, encoding="utf-8")
    (item,) = find_items(f"{path}::stable")
    return item


def test_the_readme_matrix_proof_is_established_exactly(tmp_path):
    rep = _matrix_proof(tmp_path).run({})
    assert rep.exit_code == 0 and rep.verdict.startswith("established")
    assert all(r.status is Status.EXACT for r in rep.results)


@pytest.mark.parametrize("values", [{"Ad": "[[3,0],[0,3]]"}, {"A": "[[1,0],[0,-2]]"}, {"eps": "2"}])
def test_its_failing_variants_are_refused_with_a_witness(tmp_path, values):
    from lkverify.declare.parse import parse_value

    rep = _matrix_proof(tmp_path).run({k: parse_value(v) for k, v in values.items()})
    assert rep.exit_code == 1 and rep.verdict.startswith("not established")
    failed = [r for r in rep.results if r.status is Status.FAILED]
    assert failed and all(r.kind.value == "bound" for r in failed)
    assert any("refuted exactly" in r.detail for r in failed)
