"""Memory measures ∫_0^t κ(t−ξ)‖v(ξ)‖^p dξ and their rules (lkverify.certify.steps.memory).

Each rule proves what it should, and refuses a misapplication: another kernel, power or
vector, a kernel inequality that fails at some u (Assumption 1 with too small a σ, or a kernel
violating it), Hölder the wrong way round or with a non-integrable kernel, a bound used in the
wrong direction, a window region where the whole history is needed.
"""

import pytest
import sympy

from lkverify import Equation, Parameters, Status, System, Term, Vector, memory_integral, norm_power, t, xi, zeta
from lkverify.certify.steps import (CauchySchwarz, Evaluated, KernelBound, MemoryHolder, MemoryMeasure, MemoryWeight,
                                    Region, memory_integral_of, memory_measure, norm_measure, sup_norm)
from lkverify.certify.steps.memory import U, evaluate_constant_integrals, kernel_integral
from lkverify.certify.steps.rewrites import OnRegion
from lkverify.certify.steps.rules import Context, Equal, measured
from lkverify.errors import InputError

P = Parameters()
x, y = Vector("x", 2), Vector("y", 2)
SYS = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
HALF = sympy.Rational(1, 2)
exp2 = lambda u: sympy.exp(-2 * u)  # noqa: E731  G = e^{−2ζ}
tail2 = lambda u: sympy.exp(-2 * u) / 2  # noqa: E731  K₊(u) = ∫_u^∞ e^{−2ζ}dζ


def _ctx(*measures, region=None):
    return Context(SYS, P.resolve({}), {m.name: m for m in measures}, region)


def _sup(bound=HALF, window=sympy.oo):
    return Region({sup_norm("m", x(xi), window=window): bound})


# -- the measure and its region bound -----------------------------------------------------------
def test_memory_measure_definition_and_region_bound():
    J = memory_measure("J", x(xi), p=3, kernel=exp2)
    assert isinstance(J, MemoryMeasure) and J.kind == "memory_integral" and J.window == sympy.oo
    assert J.definition == sympy.Integral(sympy.exp(-2 * t + 2 * xi) * norm_power(x(xi), 3), (xi, 0, t))
    assert _sup().bound_of(J) == HALF * HALF**3  # (∫e^{−2u})·δ^p
    # a sup over a window [t − 1, t] says nothing of the memory before t − 1
    assert _sup(window=1).bound_of(J) is None
    # a non-integrable kernel: no bound
    assert _sup().bound_of(memory_measure("Z", x(xi), p=1, kernel=lambda u: 1 / (1 + u))) is None


def test_memory_measure_refuses_a_vector_not_at_xi():
    with pytest.raises(InputError, match="written at xi"):
        memory_measure("J", x(t), p=2, kernel=exp2)


def test_kernel_integral_is_exact():
    assert kernel_integral(sympy.Lambda(U, sympy.Integral(sympy.exp(-2 * zeta), (zeta, U, sympy.oo)))) == \
        sympy.Rational(1, 4)
    assert kernel_integral(sympy.Lambda(U, 1 / (1 + U))) is None
    assert evaluate_constant_integrals(2 + sympy.Integral(sympy.exp(-zeta), (zeta, 0, sympy.oo))) == 3


def test_on_region_lowers_a_memory_power():
    J = memory_measure("J", x(xi), p=2, kernel=exp2)
    app = OnRegion("J", 1).rewrite(J.symbol**3, _ctx(J, region=_sup()), "upper")
    assert app.status is Status.EXACT and app.bound == (HALF * HALF**2) ** 2 * J.symbol


# -- the term written in its measures ---------------------------------------------------------
def test_memory_weight_reads_the_term_and_refuses_another_kernel_or_power():
    J1, J2 = memory_measure("J1", x(xi), p=2, kernel=exp2), memory_measure("J2", y(xi), p=2, kernel=exp2)
    ctx = _ctx(J1, J2)
    term = -7 * memory_integral(sympy.exp(2 * xi - 2 * t) * (norm_power(x(xi), 2) + norm_power(y(xi), 2)))
    app = MemoryWeight(("J1", "J2")).apply(term, "upper", ctx)
    assert app.status is Status.EXACT and app.bound == -7 * (J1.symbol + J2.symbol)
    other_kernel = -7 * memory_integral(sympy.exp(3 * xi - 3 * t) * (norm_power(x(xi), 2) + norm_power(y(xi), 2)))
    other_power = -7 * memory_integral(sympy.exp(2 * xi - 2 * t) * (norm_power(x(xi), 3) + norm_power(y(xi), 2)))
    dropped = -7 * memory_integral(sympy.exp(2 * xi - 2 * t) * norm_power(x(xi), 2))
    for bad in (other_kernel, other_power, dropped):
        assert MemoryWeight(("J1", "J2")).apply(bad, "upper", ctx).status is Status.FAILED
    # a window integral is not a memory integral
    window = sympy.Integral(norm_power(x(xi), 2), (xi, t - 1, t))
    assert MemoryWeight(("J1",)).apply(window, "upper", ctx).status is Status.FAILED


# -- ‖∫ w(t−ξ) F(ξ) dξ‖ in Cauchy–Schwarz ------------------------------------------------------
def _cs(weight_term, weight_tree, kernel=exp2, limits=None):
    M, n = memory_measure("M", x(xi), p=1, kernel=kernel), norm_measure("n", y(t))
    integral = (memory_integral(weight_term * x(xi)) if limits is None
                else sympy.Matrix([sympy.Integral(weight_term * c, (xi, *limits)) for c in x(xi)]))
    nb = memory_integral_of(measured(M, at=xi), measures=(M,), power=1, weight=weight_tree)
    return CauchySchwarz(y(t), integral, (measured(n), nb)).apply(y(t).dot(integral), "upper", _ctx(M, n)), M, n


def test_memory_integral_norm_proves_and_refuses():
    w = sympy.exp(2 * xi - 2 * t)
    app, M, n = _cs(w, w)
    assert app.status is Status.EXACT and app.bound == M.symbol * n.symbol
    # the signed tail K(u) = ∫_u^∞ g is dominated by K₊ = ∫_u^∞ |g| (|∫f| ≤ ∫|f|)
    K = sympy.Integral(sympy.exp(-2 * zeta), (zeta, t - xi, sympy.oo))
    app, M, n = _cs(K, K, kernel=tail2)
    assert app.status is Status.EXACT and app.bound == M.symbol * n.symbol
    # a weight larger than the measures' kernel
    assert _cs(2 * w, 2 * w)[0].status is not Status.EXACT
    # the tree's weight is not the integrand's
    assert _cs(w, 2 * w)[0].status is Status.FAILED
    # a window [t − 1, t] is not the memory [0, t]
    assert _cs(w, w, limits=(t - 1, t))[0].status is Status.FAILED


# -- Assumption 1: a kernel bound -----------------------------------------------------------------
def test_kernel_bound_is_assumption1_with_sigma():
    R, S = memory_measure("R", x(xi), p=1, kernel=tail2), memory_measure("S", x(xi), p=1, kernel=exp2)
    ctx = _ctx(R, S)
    app = KernelBound("R", "S", HALF).rewrite(3 * R.symbol * 5, ctx)
    assert app.status is Status.EXACT and app.bound == 15 * HALF * S.symbol
    # σ too small: refuted at u = 0 with the value of c·κ_t − κ_s
    bad = KernelBound("R", "S", sympy.Rational(49, 100)).rewrite(R.symbol, ctx)
    assert bad.status is Status.FAILED and "< 0" in bad.detail
    # used the wrong way: −R ≤ −σS is false
    assert KernelBound("R", "S", HALF).rewrite(-R.symbol, ctx, "upper").status is not Status.EXACT
    # another power
    S3 = memory_measure("S3", x(xi), p=3, kernel=exp2)
    assert KernelBound("R", "S3", HALF).rewrite(R.symbol, _ctx(R, S3)).status is Status.FAILED


def test_kernel_bound_refutes_a_kernel_violating_assumption1():
    # g = 1/(1+ζ)²: K₊(u) = 1/(1+u), and K₊ ≤ σ|g| fails for every σ (here at the sample u = 10 for σ = 5)
    R = memory_measure("R", x(xi), p=1, kernel=lambda u: 1 / (1 + u))
    S = memory_measure("S", x(xi), p=1, kernel=lambda u: 1 / (1 + u) ** 2)
    app = KernelBound("R", "S", 5).rewrite(R.symbol, _ctx(R, S))
    assert app.status is Status.FAILED and "u = 5" in app.detail


# -- Hölder on the memory (the paper's c12) -----------------------------------------------------
def test_memory_holder_gives_c12_and_refuses_misuse():
    nu = sympy.Rational(3, 10)
    S = memory_measure("S", x(xi), p=2 * nu + 1, kernel=exp2)
    J = memory_measure("J", x(xi), p=2 * nu + 2, kernel=exp2)
    ctx = _ctx(S, J)
    app = MemoryHolder("S", "J").rewrite(4 * S.symbol, ctx)
    c12 = HALF ** (1 / (2 * nu + 2))  # (∫_0^∞ e^{−2u}du)^{1/(2ν+2)}
    assert app.status is Status.EXACT
    assert sympy.expand(app.bound - 4 * c12 * J.symbol ** ((2 * nu + 1) / (2 * nu + 2))) == 0
    assert MemoryHolder("J", "S").rewrite(J.symbol, ctx).status is Status.FAILED  # k > P
    assert MemoryHolder("S", "J").rewrite(-S.symbol, ctx, "upper").status is not Status.EXACT  # wrong direction
    # another kernel, and a non-integrable one
    J3 = memory_measure("J3", x(xi), p=2 * nu + 2, kernel=lambda u: sympy.exp(-3 * u))
    assert MemoryHolder("S", "J3").rewrite(S.symbol, _ctx(S, J3)).status is Status.FAILED
    Sd, Jd = (memory_measure(n, x(xi), p=p, kernel=lambda u: 1 / (1 + u)) for n, p in (("Sd", 1), ("Jd", 2)))
    assert MemoryHolder("Sd", "Jd").rewrite(Sd.symbol, _ctx(Sd, Jd)).status is Status.FAILED


# -- constant integrals ---------------------------------------------------------------------------
def test_evaluated_rule():
    n = norm_measure("n", x(t))
    ctx = _ctx(n)
    term = (1 + sympy.Integral(sympy.exp(-2 * zeta), (zeta, 0, sympy.oo))) * x(t).dot(x(t))
    assert Evaluated(Equal(sympy.Rational(3, 2) * n.symbol**2)).apply(term, "upper", ctx).status is Status.EXACT
    assert Evaluated(Equal(2 * n.symbol**2)).apply(term, "upper", ctx).status is Status.FAILED
