"""``Auto``: a term bound whose rule lkverify finds (the user states *what* is bounded).

A :class:`~lkverify.certify.steps.chain.TermBound` with ``rule=Auto()`` is checked by trying
candidate rules in a fixed, documented order; the first whose every side condition holds and
whose bound implies the stated one proves the step, and the report names it.  Nothing is
trusted that a named rule would not prove: each candidate is an ordinary checked rule, applied
and compared with the stated bound exactly as when a user names it.  When no candidate proves
the step, the adversarial witness search runs as for any unproved step (a witness refutes it;
otherwise it is ``undecided``, with what each candidate said).

The order (:meth:`Auto.candidates`):

1. :class:`~.rules.Equal` with the stated bound (the term *is* the bound in measures);
2. :class:`~.rules.Nonpositive` (a term of known sign dropped: bound 0, which implies any
   stated bound ≥ 0 of a ≤ step or ≤ 0 of a ≥ step);
3. :class:`~.rules.Rayleigh` for a quadratic form uᵀMu in the vector u of a norm measure m
   when the stated bound is k·m² (M read off the term exactly, the eigenvalue k from the
   bound, so the rule's side condition kI − M ⪰ 0 or M − kI ⪰ 0 decides it);
4. the rules given to ``Auto(...)``, in the order given.
"""

from __future__ import annotations

import sympy
from sympy.core.function import AppliedUndef

from ...errors import InputError
from .context import Rule
from .rules import Equal, Nonpositive, Rayleigh

__all__ = ["Auto"]


class Auto(Rule):
    """The rule of a term bound found by lkverify: candidates tried in a documented order.

    Parameters
    ----------
    *rules : Rule
        Further candidates, tried after the automatic ones, in this order.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> M = sympy.Matrix([[2, 1], [1, 2]])                     # eigenvalues 1 and 3
    >>> V = Functional([Term((x(t).T * M * x(t))[0], text="xᵀMx"), Term(-x(t)[0] ** 2, text="−x1²")])
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> step = TermwiseBound("V ≤ 3n²", V, sys_, "V", [TermBound("xᵀMx", 3 * N**2, Auto()),
    ...                                              TermBound("−x1²", 0, Auto())], 3 * N**2, [n])
    >>> [(r.status.value, r.rule) for r in step.check(P.resolve({})).terms]
    [('exact', 'Rayleigh quotient (eigenvalue bound), found by Auto'), ('exact', 'a term of known sign dropped, found by Auto')]
    >>> V1 = Functional([Term((x(t).T * M * x(t))[0], text="xᵀMx")])
    >>> wrong = TermwiseBound("V ≤ 2n²", V1, sys_, "V", [TermBound("xᵀMx", 2 * N**2, Auto())], 2 * N**2, [n])
    >>> r = wrong.check(P.resolve({})).terms[0]                                   # λ_max = 3 > 2: refuted
    >>> r.status.value, r.rule
    ('failed', 'Auto (no rule found)')
    >>> Auto("Rayleigh")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: Auto: expected rules of lkverify.certify.steps (e.g. Auto(CauchySchwarz(...))), got str
    """

    name = "found by Auto"
    finds_rule = True  # the chain asks it for candidates instead of applying it

    def __init__(self, *rules):
        for rule in rules:
            if not isinstance(rule, Rule) or isinstance(rule, Auto):
                raise InputError(f"Auto: expected rules of lkverify.certify.steps (e.g. Auto(CauchySchwarz(...))), "
                                 f"got {type(rule).__name__}")
        self.rules = tuple(rules)

    def __repr__(self) -> str:
        return f"Auto({', '.join(map(repr, self.rules))})"

    def candidates(self, term, stated, ctx) -> list:
        """The rules to try for ``term`` with the stated bound ``stated`` (constants substituted), in order."""
        out = [Equal(stated), Nonpositive()]
        rayleigh = _rayleigh(ctx.at(term), sympy.sympify(stated), ctx)
        if rayleigh is not None:
            out.append(rayleigh)
        return out + list(self.rules)

    def apply(self, term, direction, ctx):
        raise InputError("Auto needs the stated bound of its term: use it as the rule of a TermBound")


def _rayleigh(term, stated, ctx):
    """Rayleigh(u, M, eigenvalue=k, norm_squared=m²) when ``stated`` = k·m² for a norm measure m of vector u
    and ``term`` is a quadratic form in u's entries (M read off exactly); None when the shapes do not match."""
    for m in ctx.measures.values():
        if m.kind != "norm":
            continue
        k = sympy.simplify(stated / m.symbol ** 2)
        if k.free_symbols & {mm.symbol for mm in ctx.measures.values()} or k.atoms(AppliedUndef):
            continue
        u = sympy.Matrix(ctx.at(sympy.Matrix(m.vector)))
        zs = sympy.symbols(f"_z0:{u.rows}", real=True)
        rep = {}
        for z, entry in zip(zs, u):
            atoms = entry.atoms(AppliedUndef)
            if len(atoms) != 1:
                break
            (atom,) = atoms
            offset = sympy.simplify(entry - atom)
            if offset.has(atom) or offset.atoms(AppliedUndef):
                break
            rep[atom] = z - offset
        else:
            q = sympy.expand(term.xreplace(rep))
            if q.atoms(AppliedUndef) or not q.is_polynomial(*zs):
                continue
            poly = sympy.Poly(q, *zs)
            if poly.is_zero or not poly.is_homogeneous or poly.total_degree() != 2:
                continue
            M = sympy.hessian(q, zs) / 2
            return Rayleigh(m.vector, M, eigenvalue=k, norm_squared=m.symbol ** 2)
    return None
