"""Bound steps: inequality claims ``lhs ≤ rhs`` (or ``≥``) about V and V̇, proved by a checked rule or refuted.

A :class:`BoundClaim` states an inequality for every admissible state and history.
Its left-hand side is taken from the model, not retyped: ``"V"`` (the functional),
``"Vdot"`` (the exact V̇ derived along the system) or an expression.  This first
version of the bound-step engine has one checked rule,
:class:`QuadraticForms`: the slack (``rhs − lhs`` for ``≤``) must be a positive
semidefinite quadratic form in the state values at t and at delayed times plus
nonnegative multiples of window integrals of positive semidefinite quadratic forms.
The rule is decided exactly (rational LDLᵀ, :func:`~lkverify.certify.matrices.matrix_positive_definite`).

When the slack's point part is not positive semidefinite, the claim is false (the state
values at distinct times are independent for unconstrained states): the step is
``failed`` with the exact witness.  Anything else the rule cannot decide is
``undecided`` — never ``exact``.

A theorem lists its bound steps; a step with ``role="lower"`` (V ≥ φ, φ a positive
definite form of the state at t) and one with ``role="decrease"`` (V̇ ≤ −ψ, ψ a
positive definite form) are the links the verdict needs
(:meth:`lkverify.catalogue.items.Theorem.chain`).

Examples
--------
>>> import sympy
>>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t, window_integral, xi
>>> P = Parameters(); a = P.scalar("a", positive=True, default=2); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys_ = System([Equation(x, [Term(-a * x(t)[0])])], parameters=P)
>>> V = Functional([Term(x(t)[0] ** 2 / 2), Term(window_integral(x(xi)[0] ** 2, tau))])
>>> lower = BoundClaim("V ≥ x²/2", V, sys_, lhs="V", relation=">=", rhs=x(t)[0] ** 2 / 2, role="lower")
>>> lower.check(P.resolve({})).status.value
'exact'
>>> decrease = BoundClaim("V̇ ≤ −x²/2", V, sys_, lhs="Vdot", rhs=-x(t)[0] ** 2 / 2, role="decrease")
>>> r = decrease.check(P.resolve({}))        # V̇ = (1 − a)x² − x(t−τ)²: at a = 2 the slack is x²/2 + x(t−τ)²
>>> r.status.value
'exact'
>>> decrease.check(P.resolve({"a": "1/4"})).status.value   # (1 − a − 1/2) x² < 0 is possible
'failed'
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import sympy
from sympy.core.function import AppliedUndef

from ...declare.functional import Functional, split_outer
from ...declare.parameters import apply_substitution
from ...declare.symbols import t
from ...declare.system import System
from ...errors import InputError
from ...report.results import Kind, Result
from ...status import Status
from ..matrices import matrix_positive_definite

__all__ = ["BoundClaim", "QuadraticForms", "StepResult", "quadratic_upper_bound"]

_RELATIONS = ("<=", ">=")
_ROLES = (None, "lower", "decrease")


@dataclasses.dataclass(frozen=True)
class QuadraticForms:
    """The checked rule "a positive semidefinite quadratic form plus nonnegative window integrals of such forms".

    It applies to a slack that is, exactly, ``zᵀ G z + Σ_k c_k ∫_{lo_k}^{hi_k} w_kᵀ H_k w_k dξ`` with
    z the state values at t and at delayed times, w_k the state values at ξ, constants
    ``c_k ≥ 0``, ``hi_k − lo_k ≥ 0`` and the matrices G, H_k positive semidefinite — each
    side condition decided exactly.  Unit vectors and frames are not allowed (their
    components are not independent), nor are non-polynomial terms.

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=2)
    >>> x = Vector("x", 1)
    >>> sys_ = System([Equation(x, [Term(-a * x(t)[0])])], parameters=P)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2)])
    >>> step = BoundClaim("V̇ ≤ −x²", V, sys_, lhs="Vdot", rhs=-x(t)[0] ** 2, rule=QuadraticForms())
    >>> step.check(P.resolve({})).rule                     # V̇ = −2x²: slack x² ⪰ 0
    'quadratic forms and nonnegative window integrals'
    >>> step.check(P.resolve({})).status.value
    'exact'
    """

    name: str = "quadratic forms and nonnegative window integrals"


@dataclasses.dataclass(frozen=True)
class StepResult:
    """The outcome of one bound step.

    Attributes
    ----------
    name : str
    status : Status
    detail : str
        One sentence: what was proved or why not (the failing side condition).
    rule : str
    witness : dict or None
        For ``failed``: state values that violate the step and the violation there.
    slack : sympy.Expr or None
        ``rhs − lhs`` (``≤``) or ``lhs − rhs`` (``≥``), exact.

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=2)
    >>> x = Vector("x", 1)
    >>> sys_ = System([Equation(x, [Term(-a * x(t)[0])])], parameters=P)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2)])
    >>> step = BoundClaim("V̇ ≤ −x²", V, sys_, lhs="Vdot", rhs=-x(t)[0] ** 2)
    >>> r = step.check(P.resolve({"a": "1/2"}))            # V̇ = −x²/2: slack −x²/2
    >>> r.status.value, r.slack, r.witness["slack"]
    ('failed', -x_1(t)**2/2, '-1/2')
    >>> r.to_result().kind.value
    'bound'
    """

    name: str
    status: Status
    detail: str
    rule: str
    witness: dict | None = None
    slack: object = None

    def to_result(self) -> Result:
        """As a report row of kind ``bound``."""
        value = {"rule": self.rule, "witness": self.witness}
        return Result(Kind.BOUND, self.name, self.status, value, self.detail)


@dataclasses.dataclass(frozen=True)
class BoundClaim:
    """``lhs ≤ rhs`` (or ``≥``) for every admissible state and history.

    Parameters
    ----------
    name : str
    functional : Functional
    system : System
        The theorem's own system (V̇ is derived along it).
    lhs : {"V", "Vdot"} or sympy expression
        ``"V"``: the functional; ``"Vdot"``: the exact derived V̇ (never retyped).
    rhs : sympy expression
        Written in state values (``x(t)[0]**2``), parameters and constants.
    relation : {"<=", ">="}, default "<="
    role : {None, "lower", "decrease"}
        ``"lower"``: V ≥ φ with φ a positive definite form of the state at t;
        ``"decrease"``: V̇ ≤ −ψ with ψ a positive definite form.  The verdict uses these.
    rule : QuadraticForms
        The checked rule that justifies the step.

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=2)
    >>> x = Vector("x", 1)
    >>> sys_ = System([Equation(x, [Term(-a * x(t)[0])])], parameters=P)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2)])
    >>> step = BoundClaim("V̇ ≤ −x²", V, sys_, lhs="Vdot", rhs=-x(t)[0] ** 2, role="decrease")
    >>> step.check(P.resolve({})).status.value             # at a = 2, V̇ = −2x² ≤ −x²
    'exact'
    >>> step.check(P.resolve({"a": "1/2"})).detail
    "refuted exactly: at x_1(t) = 1 the slack's point part is -1/2 < 0 (and the window integrals can be made as small as wanted)"
    >>> BoundClaim("bad", V, sys_, lhs="V", relation="<")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: bound step bad: relation: expected '<=' or '>=', got '<'
    """

    name: str
    functional: Functional
    system: System
    lhs: object = "V"
    rhs: object = 0
    relation: str = "<="
    role: str | None = None
    rule: QuadraticForms = QuadraticForms()

    def __post_init__(self):
        problems = []
        if not isinstance(self.functional, Functional):
            problems.append(f"functional: expected a Functional, got {type(self.functional).__name__}")
        if not isinstance(self.system, System):
            problems.append(f"system: expected a System, got {type(self.system).__name__}")
        if self.relation not in _RELATIONS:
            problems.append(f"relation: expected '<=' or '>=', got {self.relation!r}")
        if self.role not in _ROLES:
            problems.append(f"role: expected None, 'lower' or 'decrease', got {self.role!r}")
        if self.role == "lower" and (self.lhs != "V" or self.relation != ">="):
            problems.append("role 'lower' states V ≥ φ: use lhs='V' and relation='>='")
        if self.role == "decrease" and (self.lhs != "Vdot" or self.relation != "<="):
            problems.append("role 'decrease' states V̇ ≤ −ψ: use lhs='Vdot' and relation='<='")
        if not isinstance(self.rule, QuadraticForms):
            problems.append(f"rule: expected QuadraticForms(), got {type(self.rule).__name__}")
        if problems:
            raise InputError(f"bound step {self.name}: " + "; ".join(problems))
        object.__setattr__(self, "rhs", sympy.sympify(self.rhs))

    # -- the two sides ------------------------------------------------------------------
    def left(self) -> sympy.Expr:
        """The left-hand side: V, the exact V̇ along the system, or the given expression."""
        if isinstance(self.lhs, str):
            if self.lhs == "V":
                return self.functional.expr
            if self.lhs == "Vdot":
                from ...symbolic.derivative import derivative_along

                return derivative_along(self.functional, self.system).expr
            raise InputError(f"bound step {self.name}: lhs: expected 'V', 'Vdot' or an expression, got {self.lhs!r}")
        return sympy.sympify(self.lhs)

    def slack(self, values: Mapping) -> sympy.Expr:
        """``rhs − lhs`` (for ``≤``) or ``lhs − rhs`` (for ``≥``) at the values: the step holds iff it is ≥ 0."""
        sub = self.system.parameters.substitution(values)
        lhs = apply_substitution(self.left(), sub)
        rhs = apply_substitution(self.rhs, sub)
        return sympy.expand(rhs - lhs if self.relation == "<=" else lhs - rhs)

    # -- checking ------------------------------------------------------------------------
    def check(self, values: Mapping) -> StepResult:
        """Check the step at resolved parameter values (:meth:`~lkverify.Parameters.resolve`)."""
        rule = self.rule.name
        if any(s.unit or s.frame is not None for s in self.system.states):
            return StepResult(self.name, Status.UNDECIDED, "the rule needs unconstrained states; unit vectors and "
                              "frames need rules of their own (not in lkverify yet)", rule)
        slack = self.slack(values)
        if slack.free_symbols - {t}:
            names = ", ".join(sorted(map(str, slack.free_symbols - {t})))
            return StepResult(self.name, Status.UNDECIDED, f"the step depends on parameters without a value: "
                              f"{names}; give them values", rule, slack=slack)
        return _quadratic_forms(self, slack, rule)

    def positive_definite_bound(self, values: Mapping) -> StepResult:
        """Is the bound of a role step positive definite?  φ (``lower``) or ψ = −rhs (``decrease``)."""
        sub = self.system.parameters.substitution(values)
        bound = apply_substitution(self.rhs, sub)
        bound = bound if self.role == "lower" else -bound
        point_only = self.role == "lower"
        return _definite_form(self, sympy.expand(bound), point_only)


def _state_atoms(expr, system: System):
    funcs = system.state_functions()
    return sorted({a for a in expr.atoms(AppliedUndef) if a.func in funcs}, key=sympy.default_sort_key)


def _gram(expr, atoms):
    """The symmetric rational matrix G with expr == zᵀGz, or None if expr is not such a form."""
    if not atoms:
        return None
    zs = [sympy.Dummy(f"z{k}") for k in range(len(atoms))]
    poly_expr = expr.xreplace(dict(zip(atoms, zs)))
    if poly_expr.atoms(AppliedUndef) or poly_expr.has(sympy.Integral):
        return None
    try:
        poly = sympy.Poly(poly_expr, *zs)
    except sympy.PolynomialError:
        return None
    if not poly.is_homogeneous or poly.total_degree() != 2 or not all(c.is_Rational for c in poly.coeffs()):
        return None
    n = len(zs)
    G = sympy.zeros(n, n)
    for monom, coeff in poly.terms():
        idx = [i for i, e in enumerate(monom) for _ in range(e)]
        i, j = idx
        if i == j:
            G[i, i] += coeff
        else:
            G[i, j] += coeff / 2
            G[j, i] += coeff / 2
    return G


def _split(slack):
    """(point part, [(coefficient, integral)]) of an expanded slack, or None if an integral is not linear."""
    point, integrals = [], []
    for term in sympy.Add.make_args(slack):
        ints = [f for f in sympy.Mul.make_args(term) if isinstance(f, sympy.Integral)]
        if not ints:
            if term.has(sympy.Integral):
                return None
            point.append(term)
            continue
        if len(ints) != 1:
            return None
        coeff = sympy.Mul(*[f for f in sympy.Mul.make_args(term) if f is not ints[0]])
        if coeff.has(sympy.Integral) or coeff.atoms(AppliedUndef):
            return None
        integrals.append((coeff, ints[0]))
    return sympy.Add(*point), integrals


def _quadratic_forms(claim: BoundClaim, slack, rule: str) -> StepResult:
    parts = _split(slack)
    if parts is None:
        return StepResult(claim.name, Status.UNDECIDED, "the slack is not linear in its integrals; the rule does "
                          "not apply", rule, slack=slack)
    point, integrals = parts
    # 1. every integral: a nonnegative constant times ∫ over a window of nonnegative length of a PSD form
    for coeff, integral in integrals:
        var, lo, hi, inner = split_outer(integral)
        if not (coeff.is_Rational and coeff >= 0):
            return StepResult(claim.name, Status.UNDECIDED, f"side condition fails: the coefficient {coeff} of "
                              f"{integral} is not a nonnegative constant", rule, slack=slack)
        width = sympy.simplify(hi - lo)
        if not (width.is_Rational and width >= 0):
            return StepResult(claim.name, Status.UNDECIDED, f"side condition fails: the window {lo} … {hi} of "
                              f"{integral} is not of nonnegative constant length", rule, slack=slack)
        atoms = _state_atoms(inner, claim.system)
        G = _gram(sympy.expand(inner), atoms) if all(a.args[0] == var for a in atoms) else None
        if G is None:
            return StepResult(claim.name, Status.UNDECIDED, f"the integrand of {integral} is not a quadratic form "
                              f"of the state at {var}; the rule does not apply", rule, slack=slack)
        res = matrix_positive_definite(G, name="integrand", semidefinite=True)
        if res.status is not Status.EXACT:
            return StepResult(claim.name, Status.UNDECIDED, f"side condition fails: the integrand of {integral} "
                              f"is not a positive semidefinite form ({res.detail})", rule, slack=slack)
    # 2. the point part: a PSD form of the state values at t and at delayed times
    if point == 0:
        return StepResult(claim.name, Status.EXACT, f"proved by {rule}: the slack is a sum of nonnegative window "
                          f"integrals", rule, slack=slack)
    atoms = _state_atoms(point, claim.system)
    G = _gram(point, atoms)
    if G is None:
        return StepResult(claim.name, Status.UNDECIDED, f"the slack's point part {point} is not a quadratic form of "
                          f"the state values with rational coefficients; the rule does not apply", rule, slack=slack)
    res = matrix_positive_definite(G, name="slack", semidefinite=True)
    if res.status is Status.EXACT:
        return StepResult(claim.name, Status.EXACT, f"proved by {rule}: slack = zᵀGz + (nonnegative integrals), "
                          f"G ⪰ 0 exactly (z = {', '.join(map(str, atoms))})", rule, slack=slack)
    if res.status is Status.FAILED and _independent(atoms):
        x = [sympy.Rational(c) for c in res.witness]
        at = dict(zip(atoms, x))
        value = point.xreplace(at)
        if not value < 0:  # rechecked exactly before it is reported
            return StepResult(claim.name, Status.UNDECIDED, f"the form's witness did not recheck ({value})", rule,
                              slack=slack)
        witness = {"state_values": {str(k): str(v) for k, v in at.items()}, "slack": str(value),
                   "integrals": "histories with ∫ terms → 0 (values at the window ends fixed)"}
        return StepResult(claim.name, Status.FAILED, f"refuted exactly: at {_fmt(at)} the slack's point part is "
                          f"{value} < 0 (and the window integrals can be made as small as wanted)", rule,
                          witness=witness, slack=slack)
    return StepResult(claim.name, Status.UNDECIDED, f"the slack's form is not positive semidefinite: "
                      f"{res.detail}", rule, slack=slack)


def _independent(atoms) -> bool:
    """Values at distinct times of unconstrained states can be chosen freely (some history attains them)."""
    return len(set(atoms)) == len(atoms)


def _definite_form(claim: BoundClaim, form, point_only: bool) -> StepResult:
    atoms = _state_atoms(form, claim.system)
    what = "φ" if point_only else "ψ"
    if point_only and any(a.args[0] != t for a in atoms):
        return StepResult(claim.name, Status.UNDECIDED, f"{what} must be a form of the state at t", claim.rule.name)
    G = _gram(form, atoms)
    if G is None:
        return StepResult(claim.name, Status.UNDECIDED, f"{what} = {form} is not a quadratic form of the state "
                          f"values with rational coefficients", claim.rule.name)
    now = [a for a in atoms if a.args[0] == t]
    if {f for f in claim.system.state_functions()} - {a.func for a in now}:
        return StepResult(claim.name, Status.UNDECIDED, f"{what} = {form} does not involve every state component "
                          f"at t, so it is not positive definite in the state", claim.rule.name)
    res = matrix_positive_definite(G, name=what)
    return StepResult(claim.name, res.status, f"{what} = {form} is positive definite ({res.detail})"
                      if res.status.is_proof else f"{what} = {form} is not proved positive definite ({res.detail})",
                      claim.rule.name)


def _fmt(at: dict) -> str:
    return ", ".join(f"{k} = {v}" for k, v in at.items())


def quadratic_upper_bound(functional: Functional, system: System, values: Mapping) -> StepResult:
    """Is V ≤ U(‖x_t‖) with U quadratic?  Proved structurally for the functionals of :class:`QuadraticForms`.

    V must be, exactly, a quadratic form (any signs) of the state values at t and at
    fixed delays plus constant multiples of integrals over windows of constant length of
    quadratic forms of the state: then ``V ≤ (‖G‖ + Σ |c_k| w_k ‖H_k‖)·‖x_t‖²`` with
    ‖x_t‖ the largest ‖x(s)‖ over the window, and each norm bounded by the sum of the
    absolute entries (exact rationals).

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t, window_integral, xi
    >>> P = Parameters(); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1)
    >>> sys_ = System([Equation(x, [Term(-x(t)[0])])], parameters=P)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2), Term(window_integral(x(xi)[0] ** 2, tau))])
    >>> r = quadratic_upper_bound(V, sys_, P.resolve({}))
    >>> r.status.value, r.detail.split(" (")[0]            # 1/2 + 1·1 (window length τ = 1)
    ('exact', 'V ≤ 3/2·‖x_t‖²')
    """
    name, rule = "V ≤ U(‖x_t‖)", "quadratic forms and window integrals (structural)"
    if any(s.unit or s.frame is not None for s in system.states):
        return StepResult(name, Status.UNDECIDED, "states with constraints: no structural bound", rule)
    sub = system.parameters.substitution(values)
    V = sympy.expand(apply_substitution(functional.expr, sub))
    parts = _split(V) if not (V.free_symbols - {t}) else None
    if parts is None:
        return StepResult(name, Status.UNDECIDED, "V is not linear in its integrals, or has parameters without "
                          "a value", rule)
    point, integrals = parts
    total = sympy.S.Zero
    if point != 0:
        G = _gram(point, _state_atoms(point, system))
        delays_fixed = all((t - a.args[0]).is_Rational and t - a.args[0] >= 0 for a in _state_atoms(point, system))
        if G is None or not delays_fixed:
            return StepResult(name, Status.UNDECIDED, "V's point part is not a quadratic form of the state at t "
                              "and at fixed delays", rule)
        total += sum(abs(e) for e in G)
    for coeff, integral in integrals:
        var, lo, hi, inner = split_outer(integral)
        width = sympy.simplify(hi - lo)
        back = sympy.simplify(t - lo)
        atoms = _state_atoms(inner, system)
        H = _gram(sympy.expand(inner), atoms) if all(a.args[0] == var for a in atoms) else None
        if not (coeff.is_Rational and width.is_Rational and width >= 0 and back.is_Rational and back >= 0
                and H is not None and sympy.simplify(hi - t).is_nonpositive):
            return StepResult(name, Status.UNDECIDED, f"{integral} is not a constant multiple of a window "
                              f"integral of a quadratic form over [t − w, t]", rule)
        total += abs(coeff) * width * sum(abs(e) for e in H)
    return StepResult(name, Status.EXACT, f"V ≤ {total}·‖x_t‖² (‖x_t‖: the largest ‖x(s)‖ over the window), "
                      f"structurally: quadratic forms and window integrals of quadratic forms", rule)
