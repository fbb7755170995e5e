"""Certified suprema of bound steps: :class:`Homogeneous` (finitely many measures) and :class:`Template`
(a chart of the state manifold).

Split from :mod:`lkverify.certify.steps.rules`, which re-exports both; each rule's docstring tables what it
licenses, the directions and every side condition.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import sympy
from sympy.core.function import AppliedUndef

from ...declare.symbols import t
from ...errors import InputError
from ...status import Status
from ...memo import Memo
from .context import Application, Context, Rule, _cond, _factor_sign  # noqa: F401 (Context: the doctests)

__all__ = ["Homogeneous", "Template"]

#: how a Template rule certifies its supremum (as lkverify.certify.constants.ConstantsTuning's defaults)
TEMPLATE_BOXES = 40_000
TEMPLATE_ENCLOSURE = "taylor"


_HOMOGENEOUS_CACHE = Memo(512)  # (g, T, xs) → a certified (κ, conditions, info): one proof per process


def _homogeneous_sup(g, T, xs, seconds: float | None = None, parameters=None):
    """(κ or None, conditions, info): κ ≥ sup g/T over x ≥ 0, x ≠ 0 for g, T homogeneous of one degree.

    Homogeneity is checked exactly (g(ρx)/T(ρx) = g(x)/T(x)) and T > 0 on x ≥ 0, x ≠ 0 is
    certified (its minimum on the faces max_k x_k = 1 of the unit cube is > 0; with T ≤ 0
    somewhere g ≤ κT would not follow from g/T ≤ κ); the supremum is then the one on those
    faces, certified there with arb.  The work is limited by boxes (deterministic);
    ``seconds`` is the user's wall-clock cap (None: none).  A certified result is kept for the
    process (the same supremum recurs in several steps of one proof).
    """
    free = (sympy.sympify(g).free_symbols | sympy.sympify(T).free_symbols) - set(xs)
    parameters = {s_: b for s_, b in (parameters or {}).items() if s_ in free}  # boxed parameters: sup over them too
    key = (sympy.sympify(g), sympy.sympify(T), tuple(xs), tuple(sorted(parameters.items(), key=str)))
    if key in _HOMOGENEOUS_CACHE:
        return _HOMOGENEOUS_CACHE[key]
    out = _homogeneous_sup_uncached(g, T, xs, seconds, parameters)
    if out[0] is not None:
        _HOMOGENEOUS_CACHE[key] = out
    return out


def _faces(expr, xs, pos):
    """The restrictions of ``expr`` (in the positive symbols ``pos``) to the faces max_k x_k = 1 of the unit cube."""
    for x in xs:
        others = {pos[y]: sympy.Symbol(f"{y.name}_f", nonnegative=True) for y in xs if y != x}
        yield expr.xreplace({pos[x]: sympy.S.One, **others}), {v: (0, 1) for v in others.values()}


def _homogeneous_sup_uncached(g, T, xs, seconds, parameters=None):
    from ..bounds import sup_bound
    from ...options import Budget

    conds = []
    rho = sympy.Symbol("rho_h", positive=True)
    pos = {x: sympy.Symbol(x.name, positive=True) for x in xs}
    ratio = (sympy.sympify(g) / T).xreplace(pos)
    scaled_ratio = ratio.xreplace({pos[x]: rho * pos[x] for x in xs})
    free = sympy.simplify(sympy.powsimp(sympy.expand_power_base(scaled_ratio / ratio, force=True), force=True))
    conds.append(_cond(f"g and T = {T} are homogeneous of one degree", free == 1, f"g(ρx)/T(ρx) ÷ g/T = {free}"))
    if not conds[-1].status.is_proof:
        return None, conds, {}
    budget = Budget(seconds=seconds, boxes=TEMPLATE_BOXES)
    Tpos = sympy.sympify(T).xreplace(pos)
    worst = None
    for on_face, box in _faces(-Tpos, xs, pos):  # sup(−T) < 0 on every face: T > 0 off 0
        box = {**box, **(parameters or {})}
        r = sup_bound(on_face, box, accuracy=TEMPLATE_ACCURACY, budget=budget, enclosure=TEMPLATE_ENCLOSURE)
        if r.certified is None or not r.certified < 0:
            ok = False if (r.estimate is not None and r.estimate >= 0) else None
            conds.append(_cond(f"T = {T} > 0 for x ≥ 0, x ≠ 0", ok, f"sup(−T) on a face: estimate {r.estimate:.3g}, "
                               f"certified {r.certified}", certified=True))
            return None, conds, {}
        worst = r.certified if worst is None else max(worst, r.certified)
    conds.append(_cond(f"T = {T} > 0 for x ≥ 0, x ≠ 0 (min on the faces ≥ {-worst:.6g})", True, certified=True))
    best = None
    for on_face, box in _faces(ratio, xs, pos):
        box = {**box, **(parameters or {})}
        r = sup_bound(on_face, box, accuracy=TEMPLATE_ACCURACY, budget=budget, enclosure=TEMPLATE_ENCLOSURE)
        if r.certified is None or not r.certified < float("inf"):
            conds.append(_cond("κ certified", None, "no finite certified bound on a face", certified=True))
            return None, conds, {}
        if best is None or r.certified > best.certified:
            best = r
    conds.append(_cond(f"κ = sup g/T = {best.certified:.6g} certified on the faces max x_k = 1 (estimate "
                       f"{best.estimate:.6g})", True, certified=True))
    info = {"estimate": best.estimate, "certified": best.certified, "gap": best.gap, "boxes": best.boxes,
            "accurate": best.status is Status.CERTIFIED}
    return sympy.Rational(best.certified), conds, info


@dataclasses.dataclass(frozen=True)
class Homogeneous(Rule):
    """factor·g(x) ≤ factor·κ·T(x) for g, T homogeneous of one degree in the measures x, T > 0 off 0.

    A direct certificate in finitely many variables, applied after another rule
    (``then=``): the previous bound must be ``factor·g(x)``; the ratio g(ρx)/T(ρx) must be
    that at x (homogeneity, checked exactly), so sup g/T over x ≥ 0, x ≠ 0 is its
    supremum on the faces max_k x_k = 1 of the unit cube, certified there with arb.
    ``constant`` names κ.

    ==============================  ==========================================================
    licenses                        g ≤ κ_sup·T and g ≥ κ_inf·T (κ_sup ≥ sup g/T,
                                    κ_inf ≤ inf g/T), multiplied by the factor
    direction                       ≤ step with factor ≥ 0, or ≥ step with factor ≤ 0: κ_sup;
                                    ≥ step with factor ≥ 0, or ≤ step with factor ≤ 0: κ_inf
    side conditions                 the sign of the factor is known (a constant of known sign
                                    times nonnegative measures); g has no other measures;
                                    g, T homogeneous of one degree (exact); T > 0 for x ≥ 0,
                                    x ≠ 0 (certified); κ certified
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x, y = Vector("x", 2), Vector("y", 2)
    >>> a, b = norm_measure("a", x(t)), norm_measure("b", y(t)); A, B = a.symbol, b.symbol
    >>> ctx = Context(System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P),
    ...               P.resolve({}), {"a": a, "b": b})
    >>> up = Homogeneous(("a", "b"), (A**2 + B**2) ** 2, "c").rewrite(A**4 + B**4, ctx)     # a⁴ + b⁴ ≤ (a² + b²)²
    >>> up.status.value, 1 <= up.constants[0][1] < 1.01
    ('certified', True)
    >>> low = Homogeneous(("a", "b"), (A**2 + B**2) ** 2, "c").rewrite(A**4 + B**4, ctx, "lower")   # ≥ ½(a² + b²)²
    >>> low.status.value, 0.49 < low.constants[0][1] <= 0.5
    ('certified', True)
    """

    variables: tuple
    template: object
    constant: str
    factor: object = 1
    name = "homogeneity and a certified supremum on the faces of the unit cube (finitely many variables)"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        xs = [ctx.measure(n).symbol for n in self.variables]
        factor, T = ctx.at(self.factor), ctx.at(self.template)
        g = sympy.simplify(ctx.at(previous) / factor)
        conds = [_cond(f"the bound is ({self.factor})·g({', '.join(self.variables)})",
                       not (g.free_symbols & ({m.symbol for m in ctx.measures.values()} - set(xs))),
                       f"g = {g} involves other measures")]
        sign = _factor_sign(factor, [m.symbol for m in ctx.measures.values()])
        conds.append(_cond(f"the sign of the factor {self.factor} is known", sign is not None,
                           "neither ≥ 0 nor ≤ 0 is shown"))
        if not all(c.status.is_proof for c in conds):
            return Application(self.name, None, tuple(conds))
        want_sup = (direction == "upper") == (sign > 0)
        # κ_inf = −sup(−g/T): a certified upper bound of sup(−g/T) is a certified lower bound of inf g/T
        kappa, hconds, info = _homogeneous_sup(g if want_sup else -g, T, xs, ctx.seconds_left(None),
                                               ctx.parameter_box)
        ctx.box_used = ctx.box_used or bool(ctx.parameter_box)
        conds += hconds
        if kappa is None:
            return Application(self.name, None, tuple(conds))
        if not want_sup:
            kappa = -kappa
            info = dict(info, certified=-info["certified"], estimate=-info["estimate"], bound="infimum")
        return Application(self.name, sympy.expand(factor * kappa * T), tuple(conds),
                           ((self.constant, info["certified"], info),))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


@dataclasses.dataclass(frozen=True)
class Template(Rule):
    """term ≤ κ·Π m_i^{k_i} with κ = sup of term/Π m_i^{k_i} over a chart of the region (certified).

    The ratio is derived from the term, not retyped: every unit state s with a norm
    measure ‖s(t) − r‖ is written s = r + E·u(ρ, ψ) on the cap ρ ≤ ``rho_max`` around r
    (E = 2 sin(ρ/2), u the unit direction of s − r), every other measured vector v as
    W·v̂(θ, φ); the ratio must be free of W after division (homogeneity, checked) and
    its supremum is certified with arb over the chart's box.  Side condition: the
    region lies inside the chart (2 sin(ρ_max/2) ≥ the region's bound on ‖s − r‖).
    ``name`` is the constant's name in bounds; for ``direction="lower"`` κ is the sup of
    −term/… and the bound −κ·(monomial).


    ==============================  ==========================================================
    licenses                        term ≤ κ·Π m_i^{k_i}, κ ≥ sup term/Π m_i^{k_i} (≤ step);
                                    term ≥ −κ·Π m_i^{k_i}, κ ≥ sup(−term)/Π m_i^{k_i} (≥ step)
    direction                       both (the supremum of ±term)
    side conditions                 every measure is ‖x(t) − c‖ of one state (one measure per
                                    state); the term has no other state, history, integral or
                                    explicit t; it is divisible by the monomial and, for a
                                    non-unit vector, homogeneous of its degree; a region is
                                    stated and lies inside the unit-vector caps; the chart
                                    covers every direction — half of them only when the term
                                    is even in that direction (v − c → −(v − c), decided
                                    exactly before the norm is divided out); κ certified (arb)
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, UnitVector, t, xi
    >>> from lkverify.certify.steps.measures import Region, norm_measure, sup_norm
    >>> P = Parameters(); s = UnitVector("s"); r = sympy.Matrix([0, 0, 1])
    >>> e, m = norm_measure("e", s(t) - r), sup_norm("m", s(xi) - r, window=1)
    >>> ctx = Context(System([Equation(s, [Term(0 * s(t))])], parameters=P), P.resolve({}), {"e": e},
    ...               Region({m: sympy.Rational(1, 10)}))
    >>> sxr = s(t).cross(r)                             # ‖s × r‖² = e²(1 − e²/4) ≤ κ e², κ = 1
    >>> app = Template("kappa", {"e": 2}).apply(sxr.dot(sxr), "upper", ctx)
    >>> app.status.value, 1 <= app.constants[0][1] < 1.001
    ('certified', True)
    >>> Template("kappa", {"e": 3}).apply(sxr.dot(sxr), "upper", ctx).detail
    'side condition fails: the ratio is well defined: the term is not divisible by the stated monomial of measures'
    """

    constant: str
    exponents: Mapping
    rho_max: object = sympy.Rational(1, 2)
    text: str = ""
    name = "template constant (supremum over a chart, certified)"

    def ratio(self, term, direction, ctx):
        """(expressions in chart variables, box): κ is the largest of their suprema over the box.

        One expression per combination of the directions ±1 of the 1-vectors (one expression
        without 1-vectors)."""
        from ..charts import unit_vector_angles, unit_vector_near

        e = ctx.at(term) if direction == "upper" else -ctx.at(term)
        rep, box, back, scales, flips, charted, signs = {}, {}, {}, [], [], {}, []
        den = sympy.S.One
        for k, (name, power) in enumerate(self.exponents.items()):
            m = ctx.measure(name)
            if m.kind != "norm":
                raise InputError(f"Template {self.constant}: measure {name} must be a norm at t, got {m.kind}")
            states = {ctx.system.state_functions()[a.func][0] for a in m.vector.atoms(AppliedUndef)}
            if len(states) != 1:
                raise InputError(f"Template {self.constant}: measure {name} must measure one state")
            (state,) = states
            if state in charted:
                raise InputError(f"Template {self.constant}: measures {charted[state]} and {name} measure one state "
                                 f"{state.name}; the chart needs one measure per state (use one of them)")
            charted[state] = name
            ref = sympy.Matrix(ctx.at(sympy.Matrix(state(t)) - sympy.Matrix(m.vector)))
            if ref.free_symbols & {m_.symbol for m_ in ctx.measures.values()} or ref.atoms(AppliedUndef) or ref.has(t):
                raise InputError(f"Template {self.constant}: measure {name} must be ‖{state.name}(t) − c‖ with a "
                                 f"constant c, got {m.text}")
            E = sympy.Dummy(f"E{k}", nonnegative=True)
            scales.append(E)
            if state.unit:
                rho, psi = sympy.Dummy(f"rho{k}", real=True), sympy.Dummy(f"psi{k}", real=True)
                cap = unit_vector_near(ref, rho_max=ctx.at(self.rho_max), rho=rho, psi=psi)
                n = sympy.cos(psi) * cap.extras["e1"] + sympy.sin(psi) * cap.extras["e2"]
                value = ref + E * (-sympy.sin(rho / 2) * ref + sympy.cos(rho / 2) * n)
                box.update(cap.region)
                back[E] = 2 * sympy.sin(rho / 2)
            elif state.dim == 1:  # v = ref ± W: two directions, enumerated below
                sigma = sympy.Dummy(f"sigma{k}", real=True)
                value = ref + E * sympy.Matrix([sigma])
                signs.append((E, sigma))
            elif state.dim == 2:  # v = W·(cos θ, sin θ), θ ∈ [0, 2π]
                th = sympy.Dummy(f"theta{k}", real=True)
                value = ref + E * sympy.Matrix([sympy.cos(th), sympy.sin(th)])
                box[th] = (0, 2 * sympy.pi)
                flips.append((E, th, sympy.pi))
            elif state.dim == 3:
                th, ph = sympy.Dummy(f"theta{k}", real=True), sympy.Dummy(f"phi{k}", real=True)
                ch = unit_vector_angles(th, ph)
                value = ref + E * ch.value
                box.update(ch.region)
                flips.append((E, th, sympy.pi / 2))
            else:
                raise InputError(f"Template {self.constant}: measure {name} is the norm of a {state.dim}-vector; "
                                 f"the chart covers vectors of dimension 1, 2 or 3")
            for f, x in zip(state.functions, value):
                rep[f(t)] = x
            den *= E ** power
        num = sympy.expand(e.xreplace(rep))
        q = sympy.expand(num / den)
        for E in scales:
            for tm in sympy.Add.make_args(q):
                if tm.as_powers_dict().get(E, 0) < 0:
                    raise _NotHomogeneous("the term is not divisible by the stated monomial of measures")
            if E not in back and q.has(E):
                raise _NotHomogeneous("the term is not homogeneous of the stated degree in a vector measure "
                                      "(a power of its norm remains after division)")
        if q.atoms(AppliedUndef) or q.has(sympy.Integral):
            raise _NotHomogeneous("the term involves states or histories that no measure of the template charts")
        if q.has(t):
            raise _NotHomogeneous("the term depends on t explicitly (a time-varying coefficient): a supremum over "
                                  "the chart alone does not bound it for every t")
        # A ratio even in a direction v̂ needs only half the directions (the upper hemisphere
        # θ ∈ [0, π/2] in R³, θ ∈ [0, π] in R²; the other half is its antipodal image).  The
        # antipodal map v̂ → −v̂ is E → −E in the *numerator* — the term at v = ref − E·v̂ — while
        # the denominator E^k stays the norm's power: the test must be made before E is divided
        # out (after it, q is free of E and every ratio would pass, halving odd ratios' domains).
        for E, th, half in flips:
            if sympy.expand(num - num.xreplace({E: -E})) == 0:
                box[th] = (0, half)
        # a 1-vector has the two directions ±1: every combination of them (one when the term is even)
        qs = [q.xreplace(back)]
        for E, sigma in signs:
            even = sympy.expand(num - num.xreplace({E: -E})) == 0
            qs = [qq.xreplace({sigma: sgn}) for qq in qs for sgn in ((1,) if even else (1, -1))]
        return qs, box

    def apply(self, term, direction, ctx):
        conds = []
        # the region inside the chart
        rho = ctx.at(self.rho_max)
        chart_e = 2 * sympy.sin(rho / 2)
        for name in self.exponents:
            m = ctx.measure(name)
            if ctx.region is None:
                conds.append(_cond("a region is stated", False, "the chart needs the region's bounds"))
                break
            b = ctx.region.bound_of(m, ctx.sub)
            state = {ctx.system.state_functions()[a.func][0] for a in m.vector.atoms(AppliedUndef)}
            if any(s_.unit for s_ in state):
                if b is None:
                    conds.append(_cond(f"the region bounds {m.text}", False, "no bound"))
                    continue
                from ..intervals import enclose

                lo = enclose(chart_e - b)
                conds.append(_cond(f"the region ({m.text} ≤ {b}) lies inside the chart (‖s − r‖ ≤ 2 sin(ρ_max/2)"
                                   f" = {float(chart_e):.6g})", True if lo > 0 or (chart_e - b) == 0 else
                                   (False if lo < 0 and (lo + lo.rad() * 0) < 0 and not lo.contains(0) else None),
                                   f"the region's bound {b} exceeds the chart's {float(chart_e):.6g}",
                                   certified=True))
        try:
            qs, box = self.ratio(term, direction, ctx)
        except _NotHomogeneous as exc:
            return Application(self.name, None, tuple(conds) + (_cond("the ratio is well defined", False, str(exc)),))
        if any(not c.status.is_proof for c in conds):
            return Application(self.name, None, tuple(conds))
        boxed = {s_: ctx.parameter_box[s_] for q in qs for s_ in sympy.sympify(q).free_symbols
                 if s_ in (ctx.parameter_box or {})}
        if boxed:  # a supremum over the chart × the parameter box: one κ for every point of the box
            box = {**box, **boxed}
            ctx.box_used = True
            conds.append(_cond("κ is the supremum over the chart × the parameter box ("
                               + ", ".join(f"{s_} ∈ [{lo}, {hi}]" for s_, (lo, hi) in boxed.items()) + ")", True, ""))
        res = None
        for q in qs:
            r = _sup_of_ratio(q, box, ctx)
            if r.certified is None or not r.certified < float("inf"):
                res = r
                break
            if res is None or r.certified > res.certified:
                res = r
        proved = res.certified is not None and res.certified < float("inf")
        kappa = sympy.Rational(res.certified) if proved else None
        conds.append(_cond(f"κ = sup = {res.certified:.6g} certified (estimate {res.estimate:.6g}, gap "
                           f"{res.gap:.2g}, {res.boxes} boxes)" if proved else "κ certified", proved or None,
                           "" if proved else "no finite certified bound in the work limit", certified=True))
        if not proved:
            return Application(self.name, None, tuple(conds))
        mono = sympy.Mul(*[ctx.measure(n).symbol ** p for n, p in self.exponents.items()])
        bound = kappa * mono if direction == "upper" else -kappa * mono
        info = {"estimate": res.estimate, "certified": res.certified, "gap": res.gap, "boxes": res.boxes,
                "accurate": res.status is Status.CERTIFIED,
                "seconds": res.seconds, "maximiser": {str(k): v for k, v in (res.maximiser or {}).items()}
                if isinstance(res.maximiser, dict) else None}
        return Application(self.name, bound, tuple(conds), ((self.constant, res.certified, info),))


_RATIO_CACHE = Memo(256)  # (ratio, box) → a certified SupResult: the same supremum recurs (other choices, pieces)


def _sup_of_ratio(q, box, ctx):
    """The certified supremum of one ratio over the chart's box (a constant ratio is its own supremum).

    A certified result is kept for the process, keyed by the ratio and the box with the chart's
    dummies renamed canonically (the chart is rebuilt with fresh dummies on every check)."""
    from ..bounds import sup_bound
    from ...options import Budget

    if not box:  # no chart variables (1-vectors only): the ratio is a number
        box = {sympy.Dummy("unused"): (0, 1)}
    order = sorted(box, key=lambda s_: (s_.name, str(box[s_])))
    canon = {s_: sympy.Symbol(f"_chart{k}", **{a: v for a, v in s_.assumptions0.items() if v is not None and a in
                                                 ("real", "positive", "nonnegative", "negative")})
             for k, s_ in enumerate(order) if isinstance(s_, sympy.Dummy)}
    q, box = sympy.sympify(q).xreplace(canon), {canon.get(s_, s_): box[s_] for s_ in order}
    key = (q, tuple((str(s_), str(b)) for s_, b in box.items()))
    hit = _RATIO_CACHE.get(key)
    if hit is not None:
        return hit
    # the canonical chart symbols also let the compiled Taylor programs be reused (another cell, other choices)
    res = sup_bound(q, box, accuracy=TEMPLATE_ACCURACY, budget=Budget(seconds=ctx.seconds_left(),
                                                                     boxes=TEMPLATE_BOXES),
                    enclosure=TEMPLATE_ENCLOSURE)
    if res.certified is not None and res.status is Status.CERTIFIED and ctx.seconds_left() is None:
        _RATIO_CACHE[key] = res
    return res


class _NotHomogeneous(Exception):
    pass


def _accuracy():
    from ...options import Accuracy

    return Accuracy(rel_gap=5e-3)


TEMPLATE_ACCURACY = _accuracy()
