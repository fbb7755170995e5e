"""Every Template constant of the catalogue against its supremum sampled independently of the rule.

The rule derives its ratio through a chart (and once halved the directions of odd ratios:
paper 002 Theorem 1 was established on a λc9 4.6 % too small).  Here the ratio is not
taken from the rule: the term of the step is evaluated at random states — each measured
vector a random point v = c + E·û (û uniform on the sphere, E random), a unit state a
random point of the region's cap — divided by the monomial of the measures computed as
norms, and maximised from the best samples (Nelder–Mead).  The certified constant must
never be below the sampled supremum and at most 1 % above it.
"""

import numpy as np
import pytest
import sympy
from scipy.optimize import minimize
from sympy.core.function import AppliedUndef

from lkverify.catalogue import find_items
from lkverify.certify.steps.rules import Context, Template
from lkverify.declare.symbols import t

ITEMS = ["aleksandrov2023.theorem1", "aleksandrov2023.theorem3"]


def _template_rows(item_name):
    (item,) = find_items(item_name)
    values = item.parameters.resolve(dict(item.chosen({})), use_defaults=True)
    rows = []
    for step in item.steps:
        labels = {tm.text: tm for tm in step.lhs_terms()}
        res = step.check(values)
        ctx = Context(step.system, values, {m.name: m for m in step.measures}, step.region)
        ctx.constants = step.named_constants(values)
        for tb, tr in zip(step.bounds, res.terms):
            if not isinstance(tb.rule, Template):
                continue
            consts = dict((name, value) for a in tr.applications for name, value, _ in a.constants)
            expr = sum((labels[label].expr for label in tb.terms), sympy.S.Zero)
            rows.append((step, tb.rule, ctx, ctx.at(expr), float(consts[tb.rule.constant]), tr.status))
    return rows


def _sampler(step, rule, ctx, expr, rng):
    """(f, dim, draw): f(params) = ratio at a state given by params; draw() random params."""
    sign = 1 if step.direction == "upper" else -1
    pieces, syms = [], []
    for name, power in rule.exponents.items():
        m = ctx.measure(name)
        (state,) = {ctx.system.state_functions()[a.func][0] for a in m.vector.atoms(AppliedUndef)}
        ref = np.array([float(x) for x in sympy.Matrix(ctx.at(sympy.Matrix(state(t)) - sympy.Matrix(m.vector)))])
        bound = None
        if state.unit:
            bound = float(ctx.region.bound_of(m, ctx.sub))
        pieces.append((state, ref, float(power), bound))
        syms += [f(t) for f in state.functions]
    dummies = sympy.symbols(f"z0:{len(syms)}", real=True)
    f_num = sympy.lambdify(dummies, expr.xreplace(dict(zip(syms, dummies))), "numpy")
    dim = sum(len(p[1]) + 1 for p in pieces)

    def state_of(params):
        vals, den, i = [], 1.0, 0
        for state, ref, power, bound in pieces:
            n = len(ref)
            d = np.asarray(params[i:i + n], float)
            d = d / max(np.linalg.norm(d), 1e-300)
            if state.unit:  # a point of the cap ‖s − r‖ ≤ bound: rotate r towards d by an angle ρ
                rho_max = 2 * np.arcsin(min(bound / 2, 1.0))
                rho = rho_max * (1e-3 + (1 - 1e-3) * np.sin(params[i + n]) ** 2)  # off s = r: no cancellation
                perp = d - ref * np.dot(d, ref)
                perp = perp / max(np.linalg.norm(perp), 1e-300)
                v = np.cos(rho) * ref + np.sin(rho) * perp
            else:
                E = 1e-2 + np.sin(params[i + n]) ** 2
                v = ref + E * d
            vals += list(v)
            den *= np.linalg.norm(v - ref) ** power
            i += n + 1
        return vals, den

    def f(params):
        vals, den = state_of(params)
        if den == 0:
            return -np.inf
        return sign * float(f_num(*vals)) / den

    return f, dim, lambda: rng.normal(size=dim)


@pytest.mark.slow
@pytest.mark.parametrize("item_name", ITEMS)
def test_every_template_constant_is_at_least_its_sampled_supremum(item_name):
    rng = np.random.default_rng(7)
    rows = _template_rows(item_name)
    assert rows, "the item has Template steps"
    for step, rule, ctx, expr, kappa, status in rows:
        assert status.is_proof
        f, dim, draw = _sampler(step, rule, ctx, expr, rng)
        starts = sorted((draw() for _ in range(4000)), key=lambda p: -f(p))[:8]
        best = max(-minimize(lambda p: -f(p), p0, method="Nelder-Mead",
                             options={"xatol": 1e-10, "fatol": 1e-13, "maxiter": 4000}).fun for p0 in starts)
        scale = max(abs(best), 1e-12)
        assert kappa >= best - 1e-9 * scale, f"{rule.constant}: certified {kappa} below the sampled {best}"
        assert kappa <= best + 0.01 * scale + 1e-9, f"{rule.constant}: certified {kappa} far above {best}"
