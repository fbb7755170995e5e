"""The conclusions of a chain of bound steps: :class:`Decay` (V̇ ≤ −c̃V^p on the region, the envelope) and
:class:`Krasovskii` (sign conditions on the coefficients of L, U, W), with their monomial helpers.

Split from :mod:`lkverify.certify.steps.chain`, which re-exports them.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import sympy

from ...errors import InputError
from ...report.results import Kind, Result
from ...status import Status
from ..monomials import collect_monomials
from .measures import Region
from .rules import nonnegative

__all__ = ["Decay", "Krasovskii", "coefficient_sign", "collect_monomials"]


@dataclasses.dataclass(frozen=True)
class Decay:
    """The last links of a theorem: from checked V ≥ L, V ≤ U, V̇ ≤ W to a certified decay.

    The three steps' right-hand sides (at the checked values, with their certified
    constants) form a :class:`~lkverify.certify.decay.DecayModel` on the box the region
    implies; :func:`~lkverify.certify.decay.certify_model` estimates and certifies
    L ≥ l_v x_v², W + c̃U^p ≤ 0, V(t0) ≤ C0‖χ‖² and the envelope.

    Parameters
    ----------
    p : Rational
        The target V̇ ≤ −c̃V^p.
    point_variables : tuple of str
        Measures bounded jointly at t0 by the history norm.
    history_variables : mapping
        Measure name → κ (an expression in the parameters) with measure ≤ κ‖χ‖ at t0.
    outputs : mapping
        Output name → measure name whose decay is bounded (``{"d1": "e", "d2": "w"}``).
    descriptions : mapping
        Output name → the sentence shown before its value.
    paper : mapping
        The paper's printed constants, for comparison.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, Region, TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> def step(role, c, eig, rel="<="):                # the term c‖x‖² bounded by c·eig·n²
    ...     rule = Rayleigh(x(t), sympy.eye(2), factor=c, eigenvalue=eig, norm_squared=N**2)
    ...     return TermwiseBound(role, None, sys_, "terms", [TermBound("T", c * eig * N**2, rule)], c * eig * N**2,
    ...                          [n], relation=rel, region=Region({n: 1}), role=role,
    ...                          terms=(Term(c * x(t).dot(x(t)), text="T"),))
    >>> steps = {s.role: (s, s.check(P.resolve({}))) for s in (step("lower", 1, 1, ">="), step("upper", 1, 2),
    ...                                                         step("vdot", -2, 1))}
    >>> m = Decay(1, ("n",), {}, {"d1": "n"}).model(steps, P.resolve({}))
    >>> m.lower, m.upper, m.vdot, m.region
    (n**2, 2*n**2, -2*n**2, {n: 1})
    """

    p: object
    point_variables: tuple
    history_variables: Mapping
    outputs: Mapping
    rate_name: str = "d3"
    descriptions: Mapping = dataclasses.field(default_factory=dict)
    paper: Mapping = dataclasses.field(default_factory=dict)

    def model(self, steps: Mapping, values: Mapping, parameter_box: Mapping | None = None):
        """The DecayModel of the checked steps (``steps``: role → (TermwiseBound, ChainResult)).

        ``parameter_box`` (boxed symbol → (lo, hi)): the values hold these symbols; the
        steps' right-hand sides must already be uniform over the box
        (:func:`lkverify.certify.boxes.uniform_bound`), the history factors κ are replaced by
        their suprema and the region's bounds by their infima over the box.
        """
        from ..decay import DecayModel

        lower, upper, vdot = (steps[r] for r in ("lower", "upper", "vdot"))
        claim = vdot[0]
        sub = claim.system.parameters.substitution(values)
        measures = {m.name: m for m in claim.measures}
        used = set()
        for _, res in (lower, upper, vdot):
            used |= {s_.name for s_ in sympy.sympify(res.rhs).free_symbols}
        variables = tuple(m.symbol for name, m in measures.items() if name in used)
        if claim.region is None:
            raise InputError(f"{claim.name}: the decay needs the region of the V̇ step")
        box = claim.region.box([measures[v.name] for v in variables], sub)
        from ...declare.parameters import apply_substitution

        hist = {measures[k].symbol: apply_substitution(sympy.sympify(v), sub) for k, v in self.history_variables.items()}
        if parameter_box:
            from ..boxes import _end_of

            from ...errors import UnsupportedInput

            hist = {k: _end_of(v, parameter_box, "upper") for k, v in hist.items()}
            points = {measures[k].symbol for k in self.point_variables}
            moving = [str(k) for k, v in box.items() if k in points and sympy.sympify(v).free_symbols & set(parameter_box)]
            if moving:  # the invariance argument needs the point bounds themselves, not an enclosure of them
                raise UnsupportedInput(f"the region's bounds on {', '.join(moving)} depend on a boxed parameter; "
                                       f"fix them per box")
            # a derived bound (a window norm ≤ τ^{1/p}·δ): the model's box must contain it at every point
            box = {k: _end_of(v, parameter_box, "upper") for k, v in box.items()}
        return DecayModel(claim.name, variables, box, lower[1].rhs, upper[1].rhs, vdot[1].rhs, sympy.sympify(self.p),
                          tuple(measures[k].symbol for k in self.point_variables), hist,
                          {k: measures[v].symbol for k, v in self.outputs.items()}, self.rate_name,
                          derivation="the checked bound steps V ≥ L, V ≤ U, V̇ ≤ W")

    def certify(self, steps: Mapping, values: Mapping, *, budget=None, progress=None, claimed: Mapping | None = None,
                region: Region | None = None, parameter_box: Mapping | None = None, explain: dict | None = None):
        """(results, status, detail): the certified decay of the checked steps, or why not.

        ``claimed``: the constants a proof states (``c_tilde``, ``delta_tilde`` and ``l_<measure>``)
        are checked as given instead of estimated; ``region`` replaces the V̇ step's region.
        ``explain``: a dict that gets ``smaller_region_helps`` (False when W is refuted at a point where
        its lowest-order homogeneous part is positive: every smaller region has such a point too).
        """
        from ...errors import UnsupportedInput
        from ..decay import certify_decay, certify_model

        if region is not None:
            role, (step, res) = "vdot", steps["vdot"]
            steps = {**steps, role: (dataclasses.replace(step, region=region), res)}
        try:
            model = self.model(steps, values, parameter_box)
        except UnsupportedInput as exc:
            return [], Status.UNDECIDED, str(exc)
        bad = [str(v) for v in model.region.values() if not sympy.sympify(v).is_number]
        if bad:
            return [], Status.UNDECIDED, f"the region's bounds have no value ({', '.join(bad)}); set them"
        try:
            if claimed is None:
                cert = certify_model(model, budget=budget, progress=progress)
            else:
                from ...options import Budget

                ls = {v: sympy.Rational(claimed[f"l_{v}"]) for v in model.outputs.values()}
                cert = certify_decay(model, c_tilde=sympy.Rational(claimed["c_tilde"]), lower_coefficients=ls,
                                     delta_tilde=sympy.Rational(claimed["delta_tilde"]),
                                     budget=Budget.of(budget if budget is not None else 60.0), progress=progress)
        except UnsupportedInput as exc:
            return [], Status.UNDECIDED, str(exc)
        if cert is None:
            point = _positive_rate_point(model)
            loose = [name for _, (_, res) in steps.items() for tr in res.terms for a in tr.applications
                     for name, _, info in a.constants if not (info or {}).get("accurate", True)]
            if point is not None and loose:
                at, value = point
                where = ", ".join(f"{k} = {v}" for k, v in at.items())
                return [], Status.UNDECIDED, (f"W = {float(value):.4g} ≥ 0 at the point {where} of the region's box, "
                                              f"but the template constants {', '.join(loose)} were not tightened to "
                                              f"their accuracy target in the budget: raise --budget")
            if point is not None:
                at, value = point
                where = ", ".join(f"{k} = {v}" for k, v in at.items())
                near_zero = _lowest_order_positive(model, at)
                if explain is not None:
                    explain["smaller_region_helps"] = not near_zero
                advice = ("W's lowest-order part is positive at that point too, so W > 0 along its ray near 0 and "
                          "no smaller region helps: choose other functional parameters" if near_zero else
                          "choose a smaller region or other functional parameters")
                return [], Status.FAILED, (f"refuted on this region: at the point {where} of its box W = "
                                           f"{float(value):.4g} ≥ 0 (rechecked in interval arithmetic), so V̇ ≤ W "
                                           f"gives no decay there; {advice}")
            return [], Status.UNDECIDED, (
                "the estimator finds no admissible constants: V̇ ≥ 0 is sampled on the region or the model's "
                "shape is not covered (choose a smaller region or other functional parameters)")
        results = cert.results(self.paper, self.descriptions, values)  # printed values: only where stated
        for env in cert.envelopes:
            results.append(Result(Kind.ENVELOPE, f"envelope {env.name}", cert.status,
                                  {"d": env.d, "rate": env.kappa, "p": env.p}, env.text()))
        if cert.status is Status.CERTIFIED:
            dt = cert.constants.get("delta_tilde")
            detail = (f"V̇ ≤ −c̃V^({self.p}) with c̃ = {cert.constants.get('c_tilde', float('nan')):.4g} on the region; "
                      f"certified for ‖χ‖ < δ̃ = {dt:.4g}; " + "; ".join(env.text() for env in cert.envelopes))
        else:
            detail = cert.detail
            if cert.counterexamples:
                what, point = cert.counterexamples[0]
                detail += f"; witness (a point of the region's box where it fails): {what} at {point}"
        return results, cert.status, detail


def _positive_rate_point(model, grid: int = 41):
    """A point of the region's box (on an outer face) where W ≥ 0, rechecked exactly; None if none is found.

    W is the right-hand side of the checked V̇ ≤ W: at such a point the decay model cannot
    hold on this region whatever c̃ is.
    """
    import numpy as np

    from ..intervals import sign_of

    vs = list(model.variables)
    his = [float(model.region[v]) for v in vs]
    f = sympy.lambdify(vs, model.vdot, "numpy")
    ticks = np.concatenate([[0.0], np.geomspace(1e-6, 1.0, grid - 1)])
    best = None
    for k in range(len(vs)):
        axes = [np.array([his[i]]) if i == k else ticks * his[i] for i in range(len(vs))]
        mesh = np.meshgrid(*axes, indexing="ij")
        with np.errstate(all="ignore"):
            val = np.broadcast_to(f(*mesh), mesh[0].shape)
        idx = np.unravel_index(np.nanargmax(val), val.shape)
        if np.isfinite(val[idx]) and (best is None or val[idx] > best[0]):
            best = (float(val[idx]), [float(m[idx]) for m in mesh])
    if best is None or best[0] < 0:
        return None
    at = {str(v): sympy.Rational(x).limit_denominator(10**6) for v, x in zip(vs, best[1])}
    at = {k: min(v, sympy.sympify(model.region[sympy.Symbol(k, nonnegative=True)])) for k, v in at.items()}
    value = model.vdot.xreplace({v: at[str(v)] for v in vs})
    sign = sign_of(value)
    if sign.sign is None or sign.sign < 0 or all(x == 0 for x in at.values()):
        return None
    return at, value


def _lowest_order_positive(model, at: Mapping) -> bool:
    """Whether W's lowest-degree homogeneous part (in the model's variables) is > 0 at the point ``at``
    (exact; False where W is not a polynomial in them or the sign is not decided).

    Then W(εx) = ε^k (W_k(x) + O(ε)) > 0 for every small ε: every region scaled down still holds
    a point where W > 0, and shrinking the region cannot give a decay (used to stop a search early).

    >>> import sympy
    >>> from types import SimpleNamespace
    >>> w, e = sympy.symbols("w e", nonnegative=True)
    >>> _lowest_order_positive(SimpleNamespace(variables=(w, e), vdot=w**2 - e**2 - w**3), {"w": 1, "e": 0})
    True
    >>> _lowest_order_positive(SimpleNamespace(variables=(w, e), vdot=-w**2 + w**3), {"w": 2, "e": 0})
    False
    >>> _lowest_order_positive(SimpleNamespace(variables=(w, e), vdot=w*e - e**2), {"w": sympy.sqrt(2), "e": 1})
    True
    """
    from ..intervals import sign_of

    vs = list(model.variables)
    try:
        poly = sympy.Poly(sympy.expand(model.vdot), *vs)
    except (sympy.PolynomialError, sympy.GeneratorsNeeded):
        return False
    if poly.is_zero:
        return False
    low = min(sum(m) for m in poly.monoms())
    if low == 0:
        return False  # a constant term: W(0) ≠ 0, another failure
    part = sum((c * sympy.Mul(*[v ** k for v, k in zip(vs, m)]) for m, c in poly.terms() if sum(m) == low),
               sympy.S.Zero)
    value = part.xreplace({v: sympy.sympify(at[str(v)]) for v in vs})  # exact (a region's edge may be irrational)
    res = sign_of(value)
    return res.sign is not None and res.sign > 0


def _prime_powers(expr):
    """``expr`` with every power q^e of a positive rational q (e not an integer) written over q's primes.

    SymPy keeps 6875^(1/5) and 5^(4/5)·11^(1/5) apart; over the primes both are one canonical
    product, so an exact difference of such terms expands to 0 (bases above 10^30 are left).

    >>> fifth = sympy.Rational(1, 5)
    >>> _prime_powers(sympy.Integer(6875) ** fifth) - 5 ** (4 * fifth) * 11 ** fifth
    0
    """
    def split(p):
        b, e = p.base, p.exp
        num = sympy.Mul(*[sympy.Pow(q, k * e) for q, k in sympy.factorint(b.p).items()])
        den = sympy.Mul(*[sympy.Pow(q, k * e) for q, k in sympy.factorint(b.q).items()])
        return num / den

    def wanted(x):
        return (isinstance(x, sympy.Pow) and x.base.is_Rational and x.base > 0 and x.exp.is_Rational
                and not x.exp.is_Integer and max(x.base.p, x.base.q) < 10**30)

    return sympy.sympify(expr).replace(wanted, split)


def _coefficients_nonnegative(expr, symbols) -> tuple:
    """(True, exact/certified) when every coefficient of ``expr`` is a number ≥ 0 (its monomials are ≥ 0)."""
    worst = Status.EXACT
    for mono, c in collect_monomials(expr, symbols).items():
        sign, how = coefficient_sign(c)
        if sign is None or sign < 0 or not nonnegative(mono):
            return False, Status.UNDECIDED
        worst = Status.CERTIFIED if how is Status.CERTIFIED else worst
    return True, worst


def coefficient_sign(c):
    """``(sign, status)`` of a numeric coefficient: exact for rationals, certified by arb enclosures otherwise.

    ``sign`` is −1, 0 or 1; ``(None, undecided)`` for a coefficient with symbols, or one the
    interval layer cannot enclose.

    >>> import sympy
    >>> coefficient_sign(sympy.Rational(-3, 7)), coefficient_sign(sympy.sqrt(2) - sympy.Rational(141, 100))
    ((-1, <Status.EXACT: 'exact'>), (1, <Status.CERTIFIED: 'certified'>))
    >>> coefficient_sign(sympy.Symbol("a"))
    (None, <Status.UNDECIDED: 'undecided'>)
    """
    from ..intervals import sign_of

    c = sympy.sympify(c)
    if c.free_symbols:
        return None, Status.UNDECIDED
    if c.is_Rational:
        return (0 if c == 0 else 1 if c > 0 else -1), Status.EXACT
    try:
        res = sign_of(c)
    except Exception:  # noqa: BLE001 - an unsupported node: not decided
        return None, Status.UNDECIDED
    return res.sign, Status.CERTIFIED


@dataclasses.dataclass(frozen=True)
class Krasovskii:
    """The last link of a theorem that concludes asymptotic stability (Krasovskii's theorem).

    From the checked steps V ≥ L, V ≤ U and V̇ ≤ W on the region (their right-hand sides at
    the checked values, sums of monomials in nonnegative measures) it proves

    * V ≥ φ(‖x(t)‖): every coefficient of L is ≥ 0 and each point measure x (``point``, the
      norms that make up the state x(t)) has a pure power x^a with a positive coefficient;
    * V ≤ U(‖x_t‖_τ): every coefficient of U is ≥ 0 and U has no constant term (the measures
      are continuous in x_t and vanish at 0, so U does);
    * V̇ ≤ −ψ(‖x(t)‖): every coefficient of W is ≤ 0 and each point measure has a pure power
      with a negative one.

    A coefficient's sign is decided exactly (rationals) or with arb enclosures (certified).
    The first monomial of the wrong sign is named.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, Region, TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> def step(role, c, rel="<="):
    ...     rule = Rayleigh(x(t), sympy.eye(2), factor=c, eigenvalue=1, norm_squared=N**2)
    ...     return TermwiseBound(role, None, sys_, "terms", [TermBound("T", c * N**2, rule)], c * N**2, [n],
    ...                          relation=rel, region=Region({n: 1}), role=role,
    ...                          terms=(Term(c * x(t).dot(x(t)), text="T"),))
    >>> steps = {s.role: (s, s.check(P.resolve({}))) for s in (step("lower", 1, ">="), step("upper", 2),
    ...                                                         step("vdot", -2))}
    >>> rows, status, detail = Krasovskii(("n",)).certify(steps, P.resolve({}))
    >>> status.value, rows[0].detail.split("): ")[1].split(";")[0]
    ('exact', 'V ≥ φ: L = n**2')
    >>> steps["vdot"] = (step("vdot", 2), step("vdot", 2).check(P.resolve({})))
    >>> Krasovskii(("n",)).certify(steps, P.resolve({}))[2]
    'V̇ ≤ −ψ fails: W has the monomial n**2 with the coefficient 2 > 0'
    """

    point: tuple
    link = "V ≥ φ(‖x(t)‖), V ≤ U(‖x_t‖), V̇ ≤ −ψ(‖x(t)‖) on the region (Krasovskii)"

    def certify(self, steps: Mapping, values: Mapping, *, budget=None, progress=None, **_):
        """(results, status, detail) of the three sign conditions; nothing is estimated."""
        (ls, lres), (us, ures), (ws, wres) = (steps[r] for r in ("lower", "upper", "vdot"))
        syms = {m.symbol for s_ in (ls, us, ws) for m in s_.measures}
        by_name = {m.name: m for s_ in (ls, us, ws) for m in s_.measures}
        unknown = [p for p in self.point if p not in by_name]
        if unknown:
            return [], Status.UNDECIDED, f"the point measures {', '.join(unknown)} are not measures of the steps"
        point = [by_name[p].symbol for p in self.point]
        statuses, parts = [], []

        def check(name, expr, want, pure_sign):
            coeffs = collect_monomials(expr, syms)
            pure = set()
            for mono, c in coeffs.items():
                if not mono.free_symbols & syms:
                    if name == "U":
                        return f"U has the constant term {c}, so U(0) ≠ 0"
                    continue
                sign, st = coefficient_sign(c)
                if sign is None:
                    statuses.append(Status.UNDECIDED)
                    return f"the sign of the coefficient {c} of {mono} in {name} is not decided"
                statuses.append(st)
                if sign * want < 0:
                    return (f"{name} has the monomial {mono} with the coefficient {float(c):.4g} "
                            f"{'<' if want > 0 else '>'} 0")
                if sign == pure_sign and len(mono.free_symbols) == 1 and mono.free_symbols <= set(point):
                    pure |= mono.free_symbols
            if pure_sign and set(point) - pure:
                return (f"{name} has no pure power of {', '.join(sorted(map(str, set(point) - pure)))} with a "
                        f"{'positive' if pure_sign > 0 else 'negative'} coefficient")
            return None

        for name, res, want, pure, text in (("L", lres, 1, 1, "V ≥ φ"), ("U", ures, 1, 0, "V ≤ U"),
                                            ("W", wres, -1, -1, "V̇ ≤ −ψ")):
            why = check(name, res.rhs, want, pure)
            if why is not None:
                failed = "not decided" not in why
                return [], Status.FAILED if failed else Status.UNDECIDED, f"{text} fails: {why}" if failed else why
            parts.append(f"{text}: {name} = {sympy.N(sympy.expand(res.rhs), 4)}")
        status = Status.EXACT if all(s_ is Status.EXACT for s_ in statuses) else Status.CERTIFIED
        sub = ws.system.parameters.substitution(values)
        region = ws.region.at(sub).describe() if ws.region is not None else "everywhere"
        detail = (f"on the region {region}: V ≥ φ, V ≤ U, V̇ ≤ −ψ with x(t) = ({', '.join(self.point)}), every "
                  f"coefficient of L, U, W of its sign ({status})")
        row = Result("region", "Krasovskii conditions", status, {"region": region}, f"{detail}: " + "; ".join(parts))
        return [row], status, detail
