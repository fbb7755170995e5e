"""Canonical polynomial forms of LK expressions, modulo the state constraints.

Everything that is not a polynomial operation becomes an *atom*: a state value
``s_x(t)``, a non-integer power ``(‖s−r‖²)^((μ−1)/2)`` (its base put in normal
form first), a function value, an integral after linear normalisation (integrand
expanded, factors free of the integration variable pulled out), and the inverse
``z = 1/b`` of every polynomial denominator ``b`` (``det F``, ``A``), recorded
with the relation ``z·b − 1 = 0``.  Non-integer powers of a sum ``B`` whose exponents differ
by integers (``B^{(σ−3)/2}``, ``B^{(σ−1)/2}``, ``B^{(σ+1)/2}``) share one atom ``a = B^{e0}``,
``e0`` the smallest such exponent among the expressions put in normal form together, and
become ``a·B^k``, ``k ≥ 0``: no inverse of ``B`` is needed (its relation ``z·B − 1`` with
the constraints of ``B``'s variables makes Gröbner bases very costly).  An expression is then a polynomial in
parameter symbols and atoms; its normal form is the remainder modulo a Gröbner
basis of the constraint polynomials (‖s‖ = 1, orthonormal frames, unit constant
vectors) and the inverse relations.

A zero normal form proves an identity (treating distinct atoms as independent
only makes zero harder to reach, so a zero is sound).  A nonzero normal form is
*not* a disproof: relations between atoms may be unknown; the identity checker
relies on a numeric witness to refute.

>>> import sympy
>>> from lkverify import UnitVector, t
>>> s = UnitVector("s")
>>> c = Canonicalizer(lambda times: [p for x in times for p in s.constraint_polynomials(x)])
>>> nf = c.normal_forms([s(t)[0]**2 + s(t)[1]**2 + s(t)[2]**2 - 1, 1 / (2 * sympy.Symbol("A")) * sympy.Symbol("A")])
>>> [nf.to_expr(p) for p in nf.polys]
[0, 1/2]
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Sequence

import sympy
from sympy.core.function import AppliedUndef
from sympy.polys.groebnertools import groebner
from sympy.polys.orderings import lex
from sympy.polys.rings import PolyRing

from ..memo import Memo
from ..options import Deadline
from ..declare.functional import split_outer
from ..errors import UnsupportedInput

#: Gröbner bases (lex, variables in ``_sorted`` order) of relation blocks, by the block's sorted relations: a
#: basis depends on nothing else, and the same unit-vector and frame constraints recur in every claim of a system
_GROEBNER = Memo(256)

__all__ = ["Canonicalizer", "NormalForms"]


def _is_integer_power(e) -> bool:
    return isinstance(e, sympy.Pow) and e.exp.is_Integer


def _sorted(symbols: Iterable) -> tuple:
    return tuple(sorted(symbols, key=sympy.default_sort_key))


class Canonicalizer:
    """Turns expressions into polynomials in symbols and canonical atoms, then into normal form.

    Parameters
    ----------
    constraints : callable, optional
        ``constraints(times)`` → vanishing polynomials (in state values at those
        times and in constant parameters); typically ``System.constraint_polynomials``.
    deadline : Deadline, optional

    Examples
    --------
    >>> import sympy
    >>> from lkverify import UnitVector, Vector, t, xi
    >>> s = UnitVector("s")
    >>> c = Canonicalizer(lambda times: [p for u in times for p in s.constraint_polynomials(u)])
    >>> c.normal_expr(s(t)[0] ** 2 + s(t)[1] ** 2)         # reduced modulo ‖s(t)‖ = 1
    1 - s_z(t)**2
    >>> x, eta = Vector("x", 1), sympy.Symbol("eta")      # the integration variable's name is irrelevant
    >>> c.normal_expr(sympy.Integral(x(xi)[0] ** 2, (xi, 0, t)) - sympy.Integral(x(eta)[0] ** 2, (eta, 0, t)))
    0
    """

    def __init__(self, constraints=None, *, deadline: Deadline | None = None):
        self._constraints = constraints or (lambda times: [])
        self.deadline = deadline or Deadline(None)
        self._atom: dict = {}  # canonical expression -> Dummy
        self.atom_expr: dict = {}  # Dummy -> canonical expression
        self._inverse_relation: dict = {}  # Dummy z -> atomized polynomial z*b - 1
        self._memo: dict = {}
        self._constraint_memo: dict = {}
        self._power_floor: dict = {}  # (normal base, exponent class) -> integer offset of the class's atom
        self._power_hint: dict = {}  # (base as written, exponent class) -> smallest offset in the expressions

    # -- atoms ---------------------------------------------------------------------------
    def _atom_for(self, expr) -> sympy.Dummy:
        d = self._atom.get(expr)
        if d is None:
            d = sympy.Dummy(f"a{len(self._atom)}")
            self._atom[expr] = d
            self.atom_expr[d] = expr
        return d

    def restore(self, expr):
        """Replace atom symbols by the expressions they stand for (repeatedly, for nested atoms)."""
        for _ in range(8):
            new = expr.xreplace(self.atom_expr)
            if new == expr:
                break
            expr = new
        return expr

    def atomize(self, expr) -> sympy.Expr:
        """``expr`` as a polynomial expression in parameter symbols and atom symbols."""
        hit = self._memo.get(expr)
        if hit is not None:
            return hit
        self.deadline.check()
        out = self._atomize(expr)
        self._memo[expr] = out
        return out

    def _atomize(self, e):
        if e.is_Rational or isinstance(e, sympy.Symbol):
            return e
        if e.is_Number or isinstance(e, sympy.NumberSymbol):
            return self._atom_for(e)
        if isinstance(e, sympy.Add):
            return sympy.Add(*[self.atomize(a) for a in e.args])
        if isinstance(e, sympy.Mul):
            return sympy.Mul(*[self.atomize(a) for a in self._merge_powers(e.args)])
        if isinstance(e, sympy.Pow):
            exp = sympy.expand(e.exp)
            if exp.is_Integer and exp > 0:
                return sympy.Pow(self.atomize(e.base), exp)
            base = self.normal_expr(e.base)
            if exp.is_Integer:  # negative integer power: the inverse atom
                return sympy.Pow(self._inverse(base), -exp)
            value = sympy.Pow(base, exp)
            if value.is_Rational:
                return value
            # b^(e' + c): split the integer part n = ⌊c⌋ of the constant c off the exponent,
            # so that h^(ν−1), h^ν/h and h^ν·h^(−1) all become atom(h^(ν + c − n))·b^n; for a sum b the
            # atom is b^(e' + c − n + n0), n0 the smallest offset of the class (see _scan_powers): a·b^(n − n0)
            const, _ = exp.as_coeff_Add()
            n = sympy.floor(const) if const.is_Rational else sympy.S.Zero
            rest = sympy.expand(exp - n)
            n0 = self._class_offset(e.base, base, rest) if isinstance(base, sympy.Add) else 0
            n -= n0
            rest = sympy.expand(rest + n0)
            if n != 0:
                power = self._atom_for(sympy.Pow(base, rest, evaluate=False)) if rest != 0 else sympy.S.One
                factor = sympy.Pow(self.atomize(base), n) if n > 0 else sympy.Pow(self._inverse(base), -n)
                return power * factor
            return self._atom_for(sympy.Pow(base, exp if n0 == 0 else rest, evaluate=False))
        if isinstance(e, sympy.Integral):
            return self._integral(e)
        if isinstance(e, AppliedUndef):
            return self._atom_for(e.func(*[sympy.expand(a) for a in e.args]))
        if isinstance(e, (sympy.Function, sympy.Derivative, sympy.Subs)):
            return self._atom_for(e)
        raise UnsupportedInput(f"cannot put {type(e).__name__} in normal form: {e}; identities support polynomial operations, powers, integrals and function values")

    @staticmethod
    def _power_class(exp) -> tuple:
        """(exp − n, n), n = ⌊c⌋ for the constant c of the exponent: exponents differing by integers share a class."""
        const, _ = sympy.expand(exp).as_coeff_Add()
        n = int(sympy.floor(const)) if const.is_Rational else 0
        return sympy.expand(exp - n), n

    def _class_offset(self, written, base, rest) -> int:
        """The offset n0 of the class (base, rest), fixed when first needed: the smallest hint whose base normalises to it."""
        key = (base, rest)
        if key not in self._power_floor:
            hints = [n for (b, r), n in self._power_hint.items() if r == rest and (b == written or
                                                                                   self.normal_expr(b) == base)]
            self._power_floor[key] = min([0] + hints)
        return self._power_floor[key]

    def _merge_powers(self, factors) -> list:
        """Factors ``B^p`` (B a sum, p not a positive integer) of one base in normal form multiplied together.

        ``B^((σ−1)/2) · B'^(−1)`` with B' another spelling of B becomes ``B^((σ−3)/2)`` (one class atom, no
        inverse of B); the factors are returned as they are when no two share a base.
        """
        candidates = [f for f in factors if isinstance(f, sympy.Pow) and isinstance(f.base, sympy.Add)
                      and not (f.exp.is_Integer and f.exp > 0)]
        if len(candidates) < 2:
            return list(factors)
        groups: dict = {}
        for f in candidates:
            groups.setdefault(self.normal_expr(f.base), []).append(f.exp)
        if all(len(v) == 1 for v in groups.values()):
            return list(factors)
        others = [f for f in factors if not any(f is c for c in candidates)]
        return others + [sympy.Pow(b, sympy.expand(sympy.Add(*v))) for b, v in groups.items()]

    def _scan_powers(self, exprs) -> None:
        """Hints for :meth:`_class_offset`: the smallest offset of every non-integer power of a sum, as written.

        Bases are not normalised here (that would create atoms in another order than the expressions
        do, and the lex order of the ring follows the atoms' creation).
        """
        for expr in exprs:
            for e in sympy.preorder_traversal(expr):
                if isinstance(e, sympy.Pow) and isinstance(e.base, sympy.Add) and not sympy.expand(e.exp).is_Integer:
                    rest, n = self._power_class(e.exp)
                    key = (e.base, rest)
                    self._power_hint[key] = min(n, self._power_hint.get(key, n))

    def _inverse(self, base):
        """The atom z standing for 1/base, with the relation z·base − 1 recorded."""
        if base.is_Rational:
            if base == 0:
                raise ZeroDivisionError("division by an expression that reduces to 0")
            return 1 / base
        key = ("inverse", base)
        z = self._atom.get(key)
        if z is None:
            z = sympy.Dummy(f"inv{len(self._atom)}")
            self._atom[key] = z
            self.atom_expr[z] = 1 / base
            self._inverse_relation[z] = sympy.expand(z * self.atomize(base) - 1)
        return z

    def _integral(self, I: sympy.Integral):
        var, lo, hi, inner = split_outer(I)
        lo, hi = sympy.expand(lo), sympy.expand(hi)
        if lo == hi:  # ∫_a^a = 0 (the upper limit of a double integral gives ∫_t^t)
            return sympy.S.Zero
        sign = sympy.S.One
        if sympy.default_sort_key(lo) > sympy.default_sort_key(hi):  # one orientation: ∫_b^a = −∫_a^b
            lo, hi, sign = hi, lo, -sympy.S.One
        body = sympy.expand(self.atomize(self.normal_expr(inner, extra_times=(var,))))
        total = sympy.S.Zero
        for mono in sympy.Add.make_args(body):
            inside, outside = [], []
            for f in sympy.Mul.make_args(mono):
                base = f.base if _is_integer_power(f) else f
                expr = self.restore(base)
                (inside if var in expr.free_symbols else outside).append(f)
            if not inside:
                total += sympy.Mul(*outside) * (hi - lo)
                continue
            integrand = self.restore(sympy.Mul(*inside))
            # the name of the integration variable does not matter: rename it canonically, to a
            # symbol that occurs nowhere in the integrand or the limits (free or bound), so that
            # ∫x(η)²dη and ∫x(ξ)²dξ are one atom and no variable is captured
            taken = {s.name for s in (integrand.atoms(sympy.Symbol) | lo.atoms(sympy.Symbol)
                                      | hi.atoms(sympy.Symbol)) if s != var}
            k = 0
            while f"_v{k}" in taken:
                k += 1
            v = sympy.Symbol(f"_v{k}", real=True)
            atom = self._atom_for(sympy.Integral(integrand.xreplace({var: v}), (v, lo, hi)))
            total += sympy.Mul(*outside) * atom
        return sign * total

    # -- normal forms ---------------------------------------------------------------------
    def _times(self, symbols: Iterable) -> list:
        times = []
        for s in symbols:
            e = self.atom_expr.get(s)
            if isinstance(e, AppliedUndef) and len(e.args) == 1:
                times.append(e.args[0])
        return list(dict.fromkeys(times))

    def _constraint_atoms(self, times: tuple) -> list:
        if times not in self._constraint_memo:
            polys = [sympy.expand(self.atomize(p)) for p in self._constraints(times)]
            self._constraint_memo[times] = [p for p in polys if p != 0]
        return self._constraint_memo[times]

    def _relations(self, symbols: set, extra_times: Sequence = ()) -> tuple[list, set]:
        """Constraint and inverse relations relevant to polynomials in ``symbols``."""
        symbols = set(symbols)
        rels: list = []
        seen_inv: set = set()
        changed = True
        while changed:
            changed = False
            for z, rel in self._inverse_relation.items():
                if z in symbols and z not in seen_inv:
                    seen_inv.add(z)
                    rels.append(rel)
                    symbols |= rel.free_symbols
                    changed = True
        times = tuple(dict.fromkeys(self._times(symbols) + list(extra_times)))
        cons = self._constraint_atoms(times)
        for p in cons:
            symbols |= p.free_symbols
        return cons + rels, symbols

    def _groebner(self, ring: PolyRing, relations: list):
        """A Gröbner basis (lex, in ``ring``) of the relations.

        Relations fall apart into blocks with disjoint variables (a frame at one
        time, a unit vector at another, one inverse relation); the union of the
        blocks' bases is a basis of the whole ideal (their leading monomials are
        coprime), so each block is computed once, in its own small ring with the
        variables in the big ring's order, which keeps the monomial order the same.
        """
        blocks: list[tuple[set, list]] = []
        for rel in relations:
            syms = set(rel.free_symbols)
            merged = [rel]
            keep = []
            for bs, brels in blocks:
                if bs & syms:
                    syms |= bs
                    merged += brels
                else:
                    keep.append((bs, brels))
            blocks = keep + [(syms, merged)]
        basis = []
        for syms, rels in blocks:
            key = tuple(sorted(rels, key=sympy.default_sort_key))
            block = _GROEBNER.get(key)
            if block is None:   # the same constraints recur in every claim of a system: once per process
                self.deadline.check()
                sub = PolyRing(_sorted(syms), sympy.QQ, lex)
                block = _GROEBNER[key] = [g.as_expr() for g in groebner([sub.from_expr(p) for p in rels], sub)]
            basis += [ring.from_expr(g) for g in block]
        return basis

    def normal_expr(self, expr, *, extra_times: Sequence = ()) -> sympy.Expr:
        """The normal form of ``expr`` as an expression with atoms restored.

        Used for bases of powers and integrands, which must be canonical before
        they become atoms.
        """
        a = sympy.expand(self.atomize(expr))
        if not a.free_symbols:
            return a
        relations, gens = self._relations(a.free_symbols, extra_times)
        if not relations:
            return self.restore(a)
        ring = PolyRing(_sorted(gens), sympy.QQ, lex)
        p = ring.from_expr(a).rem(self._groebner(ring, relations))
        return self.restore(p.as_expr())

    def normal_forms(self, exprs: Sequence, *, reduce: bool = True) -> "NormalForms":
        """Normal forms of several expressions as polynomials of one ring.

        Two expressions are equal on the constraint manifold when their normal
        forms are equal (the converse holds when no relation between atoms is
        missing).  With ``reduce=False`` the polynomials in the canonical atoms are
        returned unreduced (no constraint, no relation of inverses): equal ones are
        equal everywhere, unequal ones may still agree on the manifold.  The atoms
        are memoised, so a second call with ``reduce=True`` atomizes nothing again.
        """
        self._scan_powers(exprs)
        atomized = [self.atomize(e) for e in exprs]
        self.deadline.check()
        gens: set = set()
        for a in atomized:
            gens |= a.free_symbols
        relations = []
        if reduce:
            relations, gens = self._relations(gens)
        ring = PolyRing(_sorted(gens) or (sympy.Dummy("one"),), sympy.QQ, lex)
        gb = self._groebner(ring, relations) if relations else []
        polys = []
        for a in atomized:
            self.deadline.check()
            p = ring.from_expr(a)
            if gb:
                p = p.rem(gb)
            polys.append(p)
        return NormalForms(ring, polys, self)


@dataclasses.dataclass
class NormalForms:
    """Normal-form polynomials sharing one ring (see :meth:`Canonicalizer.normal_forms`).

    Examples
    --------
    >>> from lkverify import UnitVector, t
    >>> s = UnitVector("s")
    >>> c = Canonicalizer(lambda times: [p for u in times for p in s.constraint_polynomials(u)])
    >>> nf = c.normal_forms([s(t)[0] ** 2 + s(t)[1] ** 2, 1 - s(t)[2] ** 2, s(t)[2]])
    >>> nf.polys[0] == nf.polys[1], nf.polys[0] == nf.polys[2]     # equal normal forms: equal on ‖s‖ = 1
    (True, False)
    >>> nf.to_expr(nf.polys[0])
    1 - s_z(t)**2
    """

    ring: PolyRing
    polys: list
    canonicalizer: Canonicalizer

    def to_expr(self, poly) -> sympy.Expr:
        """A polynomial of this family back as an expression, atoms restored."""
        return self.canonicalizer.restore(poly.as_expr())
