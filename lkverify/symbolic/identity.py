"""Identity claims: is a printed expression equal to the derived one?

:func:`check_identity` compares two sums of labelled terms, ``claimed`` (the
paper's print, or any intermediate equality) and ``reference`` (usually the
blocks of a derived V̇):

1. a fast randomized numeric check at witnesses on the constraint manifold
   (:mod:`lkverify.symbolic.witness`); a difference well above the quadrature accuracy
   refutes the claim, and the witness is reported;
2. the exact check: canonical normal forms modulo the constraints
   (:mod:`lkverify.symbolic.canonical`); a zero difference proves the claim ``exact``;
3. the term-by-term report: terms on both sides are grouped by the monomials
   they share, and every group whose difference is nonzero is described
   (opposite sign, wrong coefficient, missing from the claim, absent from the
   derivation, or different), with the difference in plain text and LaTeX and
   its value at the witness.

A budget that runs out gives ``undecided``; so does a residue that the normal
form cannot cancel but no witness can separate from zero.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping, Sequence

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from ..options import BudgetExceeded, Deadline
from .canonical import Canonicalizer
from ..declare.parameters import Parameters
from ..status import Status
from ..declare.symbols import t
from ..declare.terms import Term
from ..errors import InputError
from .witness import Witness, evaluate_many, make_witness, witness_constant

__all__ = ["TermDifference", "IdentityResult", "check_identity"]

#: relative size of a numeric difference that refutes (quadrature is accurate to ~1e-12)
REFUTE_TOL = 1e-7
#: relative size below which a numeric difference counts as zero
ZERO_TOL = 1e-9


@dataclasses.dataclass(frozen=True)
class TermDifference:
    """One group of terms whose claimed and derived sums differ.

    Attributes
    ----------
    kind : str
        ``"sign"``, ``"coefficient"``, ``"missing from claim"``,
        ``"not in derivation"`` or ``"differs"``.
    claimed, derived : tuple of str
        Labels of the claimed terms and of the derived terms in the group.
    message : str
        One readable sentence.
    difference_text, difference_latex : str
        claimed − derived for this group.
    value : float or None
        claimed − derived for this group at the witness.

    Examples
    --------
    >>> from lkverify import Parameters, Term, UnitVector, t
    >>> P = Parameters(); a = P.scalar("a", positive=True); s = UnitVector("s")
    >>> r = check_identity([Term(a * s(t)[0], text="a s_x"), Term(s(t)[1], text="s_y")],
    ...                    [Term(-a * s(t)[0], text="−a s_x"), Term(s(t)[1], text="s_y")],
    ...                    states=[s], parameters=P)
    >>> (d,) = r.differences                    # the s_y terms agree; only the s_x group differs
    >>> d.kind, d.claimed, d.derived
    ('sign', ('a s_x',), ('−a s_x',))
    >>> d.message, d.difference_text
    ('opposite sign: printed [a s_x] = −(derived [−a s_x])', '2·([a s_x]) = 2*a*s_x(t)')
    """

    kind: str
    claimed: tuple
    derived: tuple
    message: str
    difference_text: str
    difference_latex: str
    value: float | None

    def to_json(self) -> dict:
        return dataclasses.asdict(self) | {"claimed": list(self.claimed), "derived": list(self.derived)}


@dataclasses.dataclass(frozen=True)
class IdentityResult:
    """The outcome of an identity check.

    Examples
    --------
    >>> from lkverify import Term, UnitVector, t
    >>> s = UnitVector("s")
    >>> r = check_identity([Term(s(t)[0] ** 2 + s(t)[1] ** 2, text="s_x² + s_y²")],
    ...                    [Term(1 - s(t)[2] ** 2, text="1 − s_z²")], name="(7)", states=[s],
    ...                    constraints=lambda times: [p for u in times for p in s.constraint_polynomials(u)])
    >>> r.holds, r.numeric_points, r.differences
    (True, 1, ())
    >>> print(r.as_text())
    (7): exact — the difference reduces to 0 modulo the constraints; checked numerically at 1 random witness first
      ✓ confirmed: printed [s_x² + s_y²] = derived [1 − s_z²]
    """

    name: str
    status: Status
    detail: str
    differences: tuple = ()
    witness: dict | None = None
    difference_at_witness: float | None = None
    numeric_points: int = 0
    seconds: float = 0.0
    confirmed: tuple = ()  # (claimed labels, derived labels, claimed LaTeX) of the groups that agree exactly

    @property
    def holds(self) -> bool:
        return self.status is Status.EXACT

    def to_json(self) -> dict:
        return {"differences": [d.to_json() for d in self.differences],
                "confirmed": [{"claimed": list(c), "derived": list(d), "claimed_latex": list(lat)}
                              for c, d, lat in self.confirmed],
                "witness": self.witness,
                "difference_at_witness": self.difference_at_witness, "numeric_points": self.numeric_points,
                "seconds": round(self.seconds, 3)}

    def as_text(self) -> str:
        """Every group of terms: the differing ones with their difference, then the confirmed ones."""
        lines = [f"{self.name}: {self.status} — {self.detail}"]
        for d in self.differences:
            lines.append(f"  - {d.message}")
            lines.append(f"      difference: {_short(d.difference_text)}"
                         + (f"  (= {d.value:.6g} at the witness)" if d.value is not None else ""))
        for c, d, _ in self.confirmed:
            printed, derived = " + ".join(f"[{x}]" for x in c), " + ".join(f"[{x}]" for x in d)
            if not c:
                lines.append(f"  ✓ derived terms that cancel each other: {derived}")
            elif not d:
                lines.append(f"  ✓ printed terms that cancel each other: {printed}")
            else:
                lines.append(f"  ✓ confirmed: printed {printed} = derived {derived}")
        return "\n".join(lines)


def _short(s: str, n: int = 300) -> str:
    """``s``, or its first n characters and how long the whole is (the whole is in the JSON card)."""
    return s if len(s) <= n else s[: n - 1] + f"… ({len(s)} characters; the whole expression is in --json)"


def check_identity(claimed: Sequence[Term], reference: Sequence[Term], *, name: str = "identity",
                   states: Sequence = (), parameters: Parameters | None = None,
                   constraints=None, values: Mapping[str, object] | None = None,
                   budget: float | None = 60.0, points: int = 3, seed: int = 0) -> IdentityResult:
    """Check ``Σ claimed == Σ reference`` on the constraint manifold.

    Parameters
    ----------
    claimed, reference : sequence of Term
        Scalar labelled terms (the reference is typically the blocks of V̇).
    name : str
    states : sequence of Vector
        The states whose histories the witnesses draw.
    parameters : Parameters
    constraints : callable, optional
        ``constraints(times)`` → vanishing polynomials (``System.constraint_polynomials``).
    values : mapping, optional
        Checked parameter values already substituted in the terms (kept in witnesses).
    budget : float or None
        Seconds for the whole check; when spent, the result is ``undecided``.
    points : int
        Random witnesses for the numeric check.
    seed : int

    Returns
    -------
    IdentityResult

    Examples
    --------
    >>> from lkverify import Term, UnitVector, t
    >>> s = UnitVector("s")
    >>> lhs = [Term(s(t)[0] ** 2, text="s_x²")]
    >>> rhs = [Term(1 - s(t)[1] ** 2 - s(t)[2] ** 2, text="1 − s_y² − s_z²")]
    >>> unit = lambda times: [p for u in times for p in s.constraint_polynomials(u)]
    >>> str(check_identity(lhs, rhs, states=[s], constraints=unit).status)    # reduced modulo ‖s‖ = 1
    'exact'
    >>> str(check_identity(lhs, rhs, states=[s]).status)    # the same constraint, taken from the unit vector
    'exact'
    >>> str(check_identity(lhs, rhs, states=[s], constraints=lambda times: []).status)  # none: numerically 0 only
    'undecided'
    >>> r = check_identity([Term(2 * s(t)[0], text="2 s_x")], [Term(s(t)[0], text="s_x")], states=[s])
    >>> str(r.status), r.differences[0].message
    ('failed', 'wrong coefficient: printed [2 s_x] = 2 × (derived [s_x])')
    """
    start = time.monotonic()
    deadline = Deadline(budget)
    parameters = parameters or Parameters()
    rng = np.random.default_rng(seed)
    if constraints is None:
        constraints = _state_constraints(states)
    claimed = [_with_derivatives_done(term) for term in claimed]
    reference = [_with_derivatives_done(term) for term in reference]
    all_terms = claimed + reference
    _refuse_floats(name, claimed, reference)
    witnesses: list[Witness] = []
    worst = None  # (relative difference, witness, value, scale)
    residue_check = None
    refuted = exact_zero = False
    differences = ()
    confirmed = ()
    try:
        with deadline.enforced():
            # 1. one numeric witness first (a grossly wrong claim is refuted before the exact reduction;
            #    witnesses are appended one by one, so a budget cut keeps them)
            worst = _numeric_witnesses(claimed, reference, states, parameters, values, rng, min(points, 1),
                                       deadline, witnesses)
            # 2. exact normal forms (also needed for the term-by-term report): the fast path first, the
            #    difference as a polynomial in the canonical atoms without the constraints (zero there is
            #    zero on every manifold); the reduction modulo the constraints only when that is not zero
            canon = Canonicalizer(constraints, deadline=deadline)
            nf, total = _difference(canon, claimed, all_terms, reduce=False)
            exact_zero = total == 0
            how = "as a polynomial, no constraint needed"
            if not exact_zero:
                how = "modulo the constraints"
                nf, total = _difference(canon, claimed, all_terms, reduce=True)
                exact_zero = total == 0
            # 3. the other witnesses only where the exact reduction did not prove the identity (the same
            #    random stream: the witnesses are those of an all-numeric-first check)
            if not exact_zero and points > 1:
                more = _numeric_witnesses(claimed, reference, states, parameters, values, rng, points - 1,
                                          deadline, witnesses)
                if worst is None or (more is not None and more[0] > worst[0]):
                    worst = more
            witness = worst[1] if worst else None
            refuted = worst is not None and worst[0] > REFUTE_TOL
            differences = () if exact_zero else _term_report(claimed, reference, nf, witness)
            confirmed = _confirmed_groups(claimed, reference, nf)
            # 4. a nonzero residue is evaluated by itself (no cancellation against the large terms)
            if not exact_zero:
                residue_check = _residue_at_witnesses(nf, total, witnesses, deadline)
                if residue_check.refutes:
                    witness = residue_check.witness
    except BudgetExceeded as exc:
        w0 = worst[1] if worst else None
        return IdentityResult(name, Status.UNDECIDED, f"{exc} before the check finished",
                              witness=w0.describe(states) if w0 else None,
                              numeric_points=len(witnesses), seconds=time.monotonic() - start)
    result = _verdict(name, exact_zero, how, refuted, worst, residue_check, differences,
                      witness.describe(states) if witness else None, len(witnesses), time.monotonic() - start)
    return dataclasses.replace(result, confirmed=confirmed)


def _difference(canon, claimed, all_terms, *, reduce):
    """The normal forms of the terms and Σ claimed − Σ derived among them (reduced modulo the relations or not)."""
    nf = canon.normal_forms([term.expr for term in all_terms], reduce=reduce)
    return nf, sum(nf.polys[: len(claimed)], nf.ring.zero) - sum(nf.polys[len(claimed):], nf.ring.zero)


def _numeric_witnesses(claimed, reference, states, parameters, values, rng, points, deadline, witnesses):
    """The worst (relative difference, witness, difference, scale) over ``points`` random witnesses."""
    exprs = [term.expr for term in list(claimed) + list(reference)]
    worst = None
    for _ in range(points):
        deadline.check()
        w = make_witness(states, parameters, fixed=values, rng=rng)
        witnesses.append(w)
        vals = evaluate_many(exprs, w)
        diff = sum(vals[: len(claimed)]) - sum(vals[len(claimed):])
        scale = max(1.0, sum(abs(v) for v in vals))
        rel = abs(diff) / scale
        if worst is None or rel > worst[0]:
            worst = (rel, w, diff, scale)
    return worst


def _verdict(name, exact_zero, how, refuted, worst, rc, differences, wjson, points, seconds) -> IdentityResult:
    """The status of an identity from the exact reduction, the residue check and the numeric witnesses."""
    if exact_zero:
        wdiff = worst[2] if worst else None
        note = "" if not refuted else (" (a numeric witness disagreed by a relative "
                                       f"{worst[0]:.2g}; the exact proof stands, the quadrature was inaccurate)")
        return IdentityResult(name, Status.EXACT,
                              f"the difference reduces to 0 {how}; checked numerically at "
                              f"{points} random witness{'' if points == 1 else 'es'} first{note}",
                              (), wjson, wdiff, points, seconds)
    if rc.refutes:
        return IdentityResult(name, Status.FAILED,
                              f"claimed − derived reduces to a nonzero residue of {rc.n_terms} term(s), "
                              f"{rc.describe()}; {len(differences)} differing group(s) of terms",
                              differences, wjson, rc.value, points, seconds)
    if refuted:
        return IdentityResult(name, Status.FAILED,
                              f"claimed − derived = {worst[2]:.6g} at a witness (relative {worst[0]:.2g}; "
                              f"{worst[1].explain()}); "
                              f"{len(differences)} differing group(s) of terms",
                              differences, wjson, worst[2], points, seconds)
    return IdentityResult(name, Status.UNDECIDED, rc.why_undecided(), differences, wjson, rc.value, points, seconds)


def _state_constraints(states):
    """The constraints the states carry (‖s‖ = 1 of unit vectors, the relations of frames), or None."""
    frames = list(dict.fromkeys(s.frame for s in states if getattr(s, "frame", None) is not None))
    if not frames and not any(s.constraint_polynomials(t) for s in states):
        return None

    def constraints(times):
        return ([p for u in times for s in states for p in s.constraint_polynomials(u)]
                + [p for u in times for f in frames for p in f.constraint_polynomials(u)])

    return constraints


def _with_derivatives_done(term):
    """The term with derivatives of expressions carried out (d/dt(x²) → 2x ẋ); ẋ itself stays."""
    expr = term.expr
    if not hasattr(expr, "atoms") or not expr.atoms(sympy.Derivative):
        return term
    done = expr.replace(lambda e: isinstance(e, sympy.Derivative) and not isinstance(e.expr, AppliedUndef),
                        lambda e: e.doit())
    return dataclasses.replace(term, expr=done) if dataclasses.is_dataclass(term) else term


def _refuse_floats(name: str, claimed, reference) -> None:
    """Floating-point numbers in an identity are refused: they may already be rounded."""
    for side, terms in (("claimed", claimed), ("derived", reference)):
        for term in terms:
            floats = sorted(term.expr.atoms(sympy.Float), key=float) if hasattr(term.expr, "atoms") else []
            if floats:
                raise InputError(
                    f"{name}: the {side} term {term.text!r} contains the floating-point number {floats[0]}; "
                    f"expected exact numbers (a float may have been rounded before lkverify sees it): write "
                    f"sympy.Rational(p, q) or a string such as '1/10'")


@dataclasses.dataclass(frozen=True)
class _ResidueCheck:
    """The nonzero residue claimed − derived, evaluated by itself at the witnesses."""

    n_terms: int
    terms: tuple  # (text, value at the refuting witness) of the largest residual terms
    witness: Witness | None
    value: float | None
    relative: float | None  # |Σ| / Σ|terms| at the witness
    how: str  # "interval arithmetic" or "floating point with quadrature"
    refutes: bool
    all_zero: bool

    def describe(self) -> str:
        shown = ", ".join(f"{text} = {value:.6g}" for text, value in self.terms)
        more = "" if len(self.terms) >= self.n_terms else f", … ({self.n_terms - len(self.terms)} more)"
        what = f"; the witness: {self.witness.explain()}" if self.witness is not None else ""
        return (f"which is {self.value:.6g} at a witness ({self.how}{what}); residual terms there: {shown}{more}")

    def why_undecided(self) -> str:
        if self.all_zero:
            return (f"the normal form leaves a residue of {self.n_terms} term(s) that evaluates to 0 "
                    f"(to rounding) at every witness: it may vanish through a relation between its "
                    f"non-polynomial atoms (sin² + cos² = 1, exp·exp, nested powers) that the reduction does "
                    f"not use, so it is neither proved nor refuted")
        return (f"the normal form leaves a residue of {self.n_terms} term(s) whose value at the witnesses "
                f"(relative {self.relative:.2g} of its terms' size) cannot be told from the evaluation error "
                f"({self.how})")


def _residue_at_witnesses(nf, total, witnesses, deadline) -> _ResidueCheck:
    """Evaluate the residue monomial by monomial at each witness; refute when it is clearly nonzero.

    Without integrals the residue is a constant expression at a witness and its sign is
    decided in interval arithmetic (:func:`lkverify.certify.intervals.sign_of`); with integrals it is
    evaluated in floating point with adaptive quadrature, and refutes when its value is
    above ``REFUTE_TOL`` relative to the sum of its terms' absolute values.
    """
    monomials = [nf.canonicalizer.restore(m) for m in sympy.Add.make_args(total.as_expr())]
    best = None
    all_zero = True
    for w in witnesses:
        deadline.check()
        vals = evaluate_many(monomials, w)
        value = float(sum(vals))
        scale = sum(abs(v) for v in vals)
        rel = abs(value) / scale if scale > 0 else 0.0
        certified = None
        how = "floating point with quadrature"
        if not any(m.has(sympy.Integral) for m in monomials):
            certified = _certified_sign(sympy.Add(*monomials), w)
            if certified is not None:
                how = "interval arithmetic"
        refutes = certified in (1, -1) if certified is not None else rel > REFUTE_TOL
        if certified == 0 or (certified is None and rel < ZERO_TOL):
            pass
        else:
            all_zero = False
        if best is None or (refutes and not best[0]) or (refutes == best[0] and rel > best[3]):
            order = sorted(range(len(vals)), key=lambda i: -abs(vals[i]))[:6]
            terms = tuple((_short(sympy.sstr(monomials[i]), 80), vals[i]) for i in order)
            best = (refutes, w, value, rel, how, terms)
    refutes, w, value, rel, how, terms = best
    return _ResidueCheck(len(monomials), terms, w, value, rel, how, refutes, all_zero)


def _certified_sign(expr, w: Witness):
    """The sign (1, −1, or 0 for an exact zero) of ``expr`` at the witness, or None if not decided."""
    try:
        from ..certify.intervals import sign_of
    except ImportError:  # pragma: no cover - the interval layer ships with lkverify
        return None
    value = witness_constant(expr, w)
    if value is None:
        return None
    if value == 0:
        return 0
    try:
        res = sign_of(value, max_prec=1024)
    except Exception:  # noqa: BLE001 - an expression the interval layer cannot enclose: fall back to floats
        return None
    return 0 if res.is_zero else res.sign


def _term_report(claimed, reference, nf, witness) -> tuple:
    """Group terms by shared monomials and describe each group that does not cancel."""
    n = len(claimed)
    polys = nf.polys
    out = []
    zero = nf.ring.zero
    for members in _groups(polys):
        C = [i for i in members if i < n]
        D = [i for i in members if i >= n]
        sc = sum((polys[i] for i in C), zero)
        sd = sum((polys[i] for i in D), zero)
        delta = sc - sd
        if delta == 0:
            continue
        ctext = tuple(claimed[i].text for i in C)
        dtext = tuple(reference[i - n].text for i in D)
        clat = [claimed[i].latex for i in C]
        dlat = [reference[i - n].latex for i in D]
        value = None
        if witness is not None:
            try:
                vals = evaluate_many([claimed[i].expr for i in C] + [reference[i - n].expr for i in D], witness)
                value = sum(vals[: len(C)]) - sum(vals[len(C):])
            except Exception:  # noqa: BLE001 - the value is an aid, the report stands without it
                value = None
        csum = sympy.Add(*[claimed[i].expr for i in C])
        dsum = sympy.Add(*[reference[i - n].expr for i in D])
        ctxt = " + ".join(f"[{c}]" for c in ctext)
        dtxt = " + ".join(f"[{d}]" for d in dtext)
        if sd == 0:
            kind, expr = "not in derivation", csum
            msg = f"printed term(s) {ctxt} do not occur in the derivation"
            dtext_, dlatex = f"+({ctxt})", " + ".join(clat)
        elif sc == 0:
            kind, expr = "missing from claim", -dsum
            msg = f"derived term(s) {dtxt} are missing from the claim"
            dtext_, dlatex = f"−({dtxt})", "-\\left(" + " + ".join(dlat) + "\\right)"
        elif sc == -sd:
            kind, expr = "sign", 2 * csum
            msg = f"opposite sign: printed {ctxt} = −(derived {dtxt})"
            dtext_, dlatex = f"2·({ctxt})", "2\\left(" + " + ".join(clat) + "\\right)"
        else:
            ratio = _ratio(sc, sd)
            if ratio is not None:
                kind, expr = "coefficient", (ratio - 1) * dsum
                msg = f"wrong coefficient: printed {ctxt} = {ratio} × (derived {dtxt})"
                dtext_ = f"({ratio} − 1)·({dtxt})"
                dlatex = rf"\left({sympy.latex(ratio)} - 1\right)\left(" + " + ".join(dlat) + r"\right)"
            else:
                kind, expr = "differs", csum - dsum
                msg = f"printed {ctxt or '(nothing)'} ≠ derived {dtxt or '(nothing)'}"
                dtext_ = f"({ctxt or '0'}) − ({dtxt or '0'})"
                dlatex = "\\left(" + (" + ".join(clat) or "0") + "\\right) - \\left(" + (" + ".join(dlat) or "0") + "\\right)"
        out.append(TermDifference(kind, ctext, dtext, msg, f"{dtext_} = {sympy.sstr(expr)}", dlatex, value))
    return tuple(out)


def _confirmed_groups(claimed, reference, nf) -> tuple:
    """The groups of terms (by shared monomials) whose claimed and derived sums agree exactly."""
    n = len(claimed)
    groups = _groups(nf.polys)
    out = []
    zero = nf.ring.zero
    for members in groups:
        C = [i for i in members if i < n]
        D = [i for i in members if i >= n]
        if sum((nf.polys[i] for i in C), zero) - sum((nf.polys[i] for i in D), zero) == 0 and (C or D):
            out.append((tuple(claimed[i].text for i in C), tuple(reference[i - n].text for i in D),
                        tuple(claimed[i].latex for i in C)))
    return tuple(out)


def _groups(polys) -> list:
    """Indices of the polynomials grouped by shared monomials (union–find)."""
    parent = list(range(len(polys)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner: dict = {}
    for i, p in enumerate(polys):
        for mono in p.keys():
            j = owner.setdefault(mono, i)
            ri, rj = find(i), find(j)
            if ri != rj:
                parent[ri] = rj
    groups: dict = {}
    for i in range(len(polys)):
        groups.setdefault(find(i), []).append(i)
    return list(groups.values())


def _ratio(a, b):
    """The rational k ≠ 1 with a == k·b, if any (a, b polynomials of one ring)."""
    if not b:
        return None
    lm = b.LM
    ka, kb = a.get(lm), b.get(lm)
    if not ka or not kb:
        return None
    k = ka / kb
    return sympy.Rational(k.numerator, k.denominator) if a == b * k else None
