"""The hypotheses of Theorem 1 of paper 002 for the instance of :mod:`.system3`, decided.

* μ > 1 and (6) 2σ > μ + 1: exact (rational margins);
* Π, Π̃ homogeneous of order μ + 1: exact (the degrees of the instance's forms);
* Π + τΠ̃ positive definite: a certified positive lower bound of its minimum on the unit
  circle (:func:`lkverify.certify.homogeneous_positive_on_sphere`, arb branch and bound), or
  a rational point where it is ≤ 0;
* (4) ‖P(q)‖ ≤ p0‖q‖^{σ−1}: with P(q) = φ(q)J, ‖P(q)‖ = |φ(q)|.  When φ is a form of degree
  d = σ − 1 this is p0²‖q‖^{2d} − φ(q)² > 0 on the circle (certified the same way); a form
  of another degree fails it near 0 or near infinity, shown at an exact point.
"""

from __future__ import annotations

import sympy

from lkverify import Result, Status
from lkverify.certify import homogeneous_positive_on_sphere
from lkverify.declare.parameters import apply_substitution
from lkverify.options import Budget

from .system3 import X, Pi, Pi_t, mu, p0, phi, sigma, tau

__all__ = ["FormHypothesis", "Homogeneity", "SkewBound", "positive_definite", "skew_bound", "homogeneity"]



def _at(expr, substitution):
    return sympy.expand(apply_substitution(sympy.sympify(expr), substitution))


def _symbols(*exprs) -> set:
    return set().union(*(sympy.sympify(e).free_symbols for e in exprs)) - set(X)


class FormHypothesis:
    """``form`` positive definite in x = (x1, x2), certified on the unit circle at the run's values.

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2023.system3 import P3
    >>> sub = P3.substitution(P3.resolve({}, use_defaults=True))
    >>> positive_definite.evaluate(sub).status.value
    'certified'
    >>> P3b = P3.substitution(P3.resolve({"pi04": "-1/2"}, use_defaults=True))
    >>> positive_definite.evaluate(P3b).status.value                # Π + τΠ̃ < 0 at q = (0, 1)
    'failed'
    """

    def __init__(self, name, form, *, reference=""):
        self.name, self.form, self.reference = name, form, reference

    def symbols(self) -> set:
        """The parameters the hypothesis is stated in."""
        return _symbols(self.form)

    def evaluate(self, substitution, *, budget=None) -> Result:
        f = _at(self.form, substitution)
        seconds = None if budget is None else max(float(budget), 0.5)  # no budget: the boxes alone limit it
        res = homogeneous_positive_on_sphere(f, X, name=self.name, budget=Budget(seconds=seconds, boxes=50_000))
        ref = f"{self.reference} " if self.reference else ""
        return Result("hypothesis", self.name, res.status, res.margin.lo if res.margin is not None else None,
                      f"{ref}{f} on ‖x‖ = 1: {res.detail}")


class Homogeneity:
    """Every form of the instance is homogeneous of degree ``degree`` (exact)."""

    def __init__(self, name, forms, degree, *, reference=""):
        self.name, self.forms, self.degree, self.reference = name, forms, degree, reference

    def symbols(self) -> set:
        return _symbols(*self.forms.values(), self.degree)

    def evaluate(self, substitution, *, budget=None) -> Result:
        d = _at(self.degree, substitution)
        bad = []
        for label, form in self.forms.items():
            f = _at(form, substitution)
            degs = {sum(m) for m in sympy.Poly(f, *X).monoms()} if f != 0 else set()
            if degs and degs != {d}:
                bad.append(f"{label} = {f} has degree(s) {sorted(degs)}")
        ref = f"{self.reference} " if self.reference else ""
        if bad:
            return Result("hypothesis", self.name, Status.FAILED, None, f"{ref}fails: expected degree μ + 1 = {d}; "
                          + "; ".join(bad))
        return Result("hypothesis", self.name, Status.EXACT, d, f"{ref}holds: every form is homogeneous of degree {d}")


class SkewBound:
    """(4) ‖φ(q)J‖ = |φ(q)| ≤ p0‖q‖^{σ−1} for every q (J = [[0, 1], [−1, 0]], ‖J‖ = 1).

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2023.system3 import P3
    >>> skew_bound.evaluate(P3.substitution(P3.resolve({}, use_defaults=True))).status.value
    'certified'
    >>> r = skew_bound.evaluate(P3.substitution(P3.resolve({"p0": "1"}, use_defaults=True)))
    >>> r.status.value                                        # max |φ| on the circle is (1 + √(5/4))/2 > 1
    'failed'
    >>> sub = P3.substitution(P3.resolve({"p11": 1, "p12": 0, "p0": 1}, use_defaults=True))
    >>> skew_bound.evaluate(sub).status.value                 # |q1²| ≤ ‖q‖² holds, with equality at (1, 0)
    'undecided'
    """

    def __init__(self, name, phi_form, p0_, sigma_, *, reference=""):
        self.name, self.phi, self.p0, self.sigma, self.reference = name, phi_form, p0_, sigma_, reference

    def symbols(self) -> set:
        return _symbols(self.phi, self.p0, self.sigma)

    def evaluate(self, substitution, *, budget=None) -> Result:
        f, c, s = (_at(e, substitution) for e in (self.phi, self.p0, self.sigma))
        ref = f"{self.reference} " if self.reference else ""
        if f == 0:
            return Result("hypothesis", self.name, Status.EXACT, 0, f"{ref}holds: P ≡ 0")
        degs = {sum(m) for m in sympy.Poly(f, *X).monoms()}
        if len(degs) != 1 or degs != {s - 1}:
            return self._refuted(f, c, s, degs, ref)
        (d,) = degs
        g = sympy.expand(c**2 * (X[0] ** 2 + X[1] ** 2) ** d - f**2)
        if g == 0:  # |φ(q)| = p0‖q‖^{σ−1} identically: (4) holds with equality
            return Result("hypothesis", self.name, Status.EXACT, 0, f"{ref}holds with equality: |φ| = p0‖q‖^(σ−1), φ = {f}")
        seconds = None if budget is None else max(float(budget), 0.5)  # no budget: the boxes alone limit it
        res = homogeneous_positive_on_sphere(g, X, name="p0²‖q‖^{2(σ−1)} − φ²",
                                             budget=Budget(seconds=seconds, boxes=50_000))
        status = res.status
        if status is Status.FAILED and res.witness is not None:
            # the sphere test is strict; (4) is ≤: a zero of g (‖P(q)‖ = p0‖q‖^{σ−1} there) refutes nothing
            at = dict(zip(X, (sympy.Rational(x.numerator, x.denominator) for x in res.witness)))
            if not sympy.expand(g.xreplace(at)).is_negative:
                found = _negative_point(g)
                status = Status.UNDECIDED if found is None else Status.FAILED
                if found is not None:
                    return Result("hypothesis", self.name, Status.FAILED, None,
                                  f"{ref}fails: ‖P(q)‖ = |φ(q)|, φ = {f}: p0²‖q‖^{{2(σ−1)}} − φ² = {g} is "
                                  f"{found[1]} < 0 at q = {found[0]} (exact)")
        return Result("hypothesis", self.name, status, res.margin.lo if res.margin is not None else None,
                      f"{ref}‖P(q)‖ = |φ(q)|, φ = {f}: p0²‖q‖^{{2(σ−1)}} − φ² = {g} on ‖q‖ = 1: {res.detail}"
                      + ("; g ≥ 0 at that point (equality in (4)): not refuted, and not shown without the "
                         "strict test (take p0 larger)" if status is not res.status else ""))

    def _refuted(self, f, c, s, degs, ref) -> Result:
        """φ of degree ≠ σ − 1: |φ(ρu)|/‖ρu‖^{σ−1} is unbounded as ρ → 0 or ∞; an exact point where (4) fails."""
        u = next(p for p in ((1, 0), (0, 1), (1, 1), (1, -1), (1, 2)) if f.xreplace(dict(zip(X, p))) != 0)
        for k in range(0, 200):
            for rho in (sympy.Integer(2) ** k, sympy.Integer(2) ** -k):
                pt = dict(zip(X, (rho * u[0], rho * u[1])))
                lhs = abs(f.xreplace(pt))
                rhs = c * (pt[X[0]] ** 2 + pt[X[1]] ** 2) ** ((s - 1) / 2)
                if sympy.simplify(lhs - rhs).is_positive:
                    return Result("hypothesis", self.name, Status.FAILED, None,
                                  f"{ref}fails: φ = {f} has degree(s) {sorted(degs)}, σ − 1 = {s - 1}; at q = "
                                  f"({pt[X[0]]}, {pt[X[1]]}) ‖P(q)‖ = {lhs} > p0‖q‖^(σ−1) = {rhs} (exact)")
        return Result("hypothesis", self.name, Status.UNDECIDED, None,
                      f"{ref}φ = {f} has degree(s) {sorted(degs)} ≠ σ − 1 = {s - 1}, but no point found")


def _negative_point(g, grid: int = 96):
    """A rational point (1 − s², 2s), s = 4k/grid, |k| ≤ grid, or (0, 1), where the binary form g < 0 (exact)."""
    for p in [(1 - s * s, 2 * s) for s in (sympy.Rational(4 * k, grid) for k in range(-grid, grid + 1))] + [(0, 1)]:
        value = sympy.expand(g.xreplace(dict(zip(X, p))))
        if value.is_negative:
            return p, value
    return None


positive_definite = FormHypothesis("Pi + tau*Pi~ positive definite", Pi + tau * Pi_t, reference="(Theorem 1)")
homogeneity = Homogeneity("Pi, Pi~ homogeneous of order mu+1", {"Π": Pi, "Π̃": Pi_t}, mu + 1, reference="(3)")
skew_bound = SkewBound("||P(q)|| <= p0 ||q||^(sigma-1)", phi, p0, sigma, reference="(4)")
