"""Normal forms: non-integer powers of one sum whose exponents differ by integers share one atom.

B^((σ−3)/2), B^((σ−1)/2)·B'^(−1) (B' another spelling of B on the constraint manifold) and
B^((σ+1)/2) become a·B^k with a = B^((σ−3)/2) and k ≥ 0: no inverse of B (whose relation with the
constraints of B's variables made the Gröbner bases of Theorem 2 of paper 001 with symbolic σ
run for many minutes).  Zero normal forms must stay sound: other bases, other exponent classes
and wrong powers are not identified.
"""

import sympy

from lkverify import Parameters, Status, Term, UnitVector, t
from lkverify.symbolic.canonical import Canonicalizer
from lkverify.symbolic.identity import check_identity

s = UnitVector("s")
P = Parameters()
sigma = P.scalar("sigma", positive=True)
dB = P.scalar("dB")
x, y, z = s(t)
B = 1 + x ** 2                   # > 0
B_other = 2 - y ** 2 - z ** 2    # = B on ‖s‖ = 1
C = 1 + y ** 2                   # another base


def _canonicalizer():
    return Canonicalizer(lambda times: [p for u in times for p in s.constraint_polynomials(u)])


def _check(claimed, reference):
    return check_identity([Term(claimed, text="claimed")], [Term(reference, text="reference")], states=[s],
                          parameters=P, budget=60)


def test_one_atom_per_class_and_no_inverse():
    c = _canonicalizer()
    nf = c.normal_forms([B ** ((sigma - 1) / 2) / B_other - B ** ((sigma - 3) / 2),
                         B ** ((sigma + 1) / 2) - B ** ((sigma - 3) / 2) * B_other ** 2])
    assert [p == 0 for p in nf.polys] == [True, True]
    assert c._inverse_relation == {}
    classes = [e for e in c.atom_expr.values() if isinstance(e, sympy.Pow) and e.exp.has(sigma)]
    assert len(classes) == 1 and sympy.expand(classes[0].exp - (sigma - 3) / 2) == 0


def test_true_identities_with_symbolic_sigma_are_exact():
    assert _check(B ** ((sigma + 1) / 2), B ** ((sigma - 3) / 2) * B_other ** 2).status is Status.EXACT
    # the derivative of ‖·‖^(σ−1) written as the proof writes it: (σ−1)/2 · B^((σ−3)/2) · dB
    lhs = sympy.diff(B ** ((sigma - 1) / 2), x) * dB
    rhs = (sigma - 1) * x * B_other ** ((sigma - 3) / 2) * dB
    assert _check(lhs, rhs).status is Status.EXACT


def test_mutations_are_refuted():
    assert _check(B ** ((sigma + 1) / 2), B ** ((sigma - 3) / 2) * B_other).status is Status.FAILED   # B¹ for B²
    assert _check(B ** ((sigma + 1) / 2), B ** ((sigma - 2) / 2) * B_other ** 2).status is Status.FAILED  # half off
    assert _check(B ** ((sigma - 1) / 2) / C, B ** ((sigma - 3) / 2)).status is Status.FAILED          # other base


def test_other_classes_and_bases_stay_apart():
    c = _canonicalizer()
    nf = c.normal_forms([B ** ((sigma - 1) / 2) / C - B ** ((sigma - 3) / 2),   # C is not B
                         B ** (sigma / 2) - B ** ((sigma - 1) / 2)])              # exponents differ by 1/2
    assert [p == 0 for p in nf.polys] == [False, False]
