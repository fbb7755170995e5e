"""Rigid-body building blocks: Euler's and Poisson's equations, ‖s − r‖ chains.

The attitude papers share three pieces of notation, declared here once:

* Euler's dynamic equation ``Θ ω̇ = −ω × (Θω) + Σ torques``
  (:func:`euler_equation`, :func:`gyroscopic_term`);
* Poisson's kinematic equation ``ṡ = −ω × s`` for every inertial unit vector
  written in body axes (:func:`poisson_equation`, :func:`poisson_equations`);
* chains over pairs (sᵢ, rᵢ) of a body vector and its target: the restoring
  torque ``Σ aᵢ sᵢ × rᵢ`` (:func:`restoring_torque`), its rate along Poisson's
  equation ``Σ aᵢ (ω × sᵢ) × rᵢ`` (:func:`restoring_torque_rate`), and the distance
  sums ``Σ aᵢ ‖sᵢ − rᵢ‖^p`` (:func:`distance_sum`).

Every constructor returns lkverify objects (:class:`~lkverify.declare.system.Equation`,
:class:`~lkverify.declare.terms.Term`, or SymPy expressions written with
:mod:`lkverify.declare.vectors`), so a proof module reads like the paper.

Examples
--------
Euler's equation with a damping torque and Poisson's equation for one unit vector:

>>> import sympy
>>> from lkverify import Parameters, System, Term, UnitVector, Vector, t
>>> P = Parameters()
>>> Theta = P.diagonal_matrix("Theta", ["A", "B", "C"], latex=r"\\Theta")
>>> k = P.scalar("k", positive=True)
>>> omega, s = Vector("omega", latex=r"\\omega", text="ω"), UnitVector("s")
>>> euler = euler_equation(omega, Theta, [Term(-k * omega(t), text="−kω")])
>>> [term.text for term in euler.terms]
['−ω×(Θω)', '−kω']
>>> poisson = poisson_equation(omega, s)
>>> poisson.terms[0].text, poisson.terms[0].latex
('−ω×s', '-\\\\omega\\\\times s')
>>> system = System([euler, poisson], parameters=P)
>>> system.rhs(s) == -omega(t).cross(s(t))
True
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy

from ..errors import InputError
from .states import Vector
from .symbols import t
from .system import Equation
from .terms import Term
from .vectors import as_column, cross, norm_power

__all__ = [
    "distance_sum",
    "euler_equation",
    "gyroscopic_term",
    "poisson_equation",
    "poisson_equations",
    "restoring_torque",
    "restoring_torque_rate",
]


def _check_vector(v, role: str, function: str) -> None:
    if not isinstance(v, Vector):
        raise InputError(f"{function}: expected {role} as a state (Vector), got {type(v).__name__}; "
                         f"declare it with Vector(name) or UnitVector(name)")
    if v.dim != 3:
        raise InputError(f"{function}: expected {role} of dimension 3, got {v.name} of dimension {v.dim}; "
                         f"rigid-body equations are written in three body axes")


def gyroscopic_term(omega: Vector, Theta, *, time=t, mass_text: str = "Θ", mass_latex: str = r"\Theta",
                    text: str = "", latex: str = "") -> Term:
    """The gyroscopic torque ``−ω × (Θω)`` of Euler's equation, labelled.

    Parameters
    ----------
    omega : Vector
        The angular velocity (body axes), dimension 3.
    Theta : 3 × 3 matrix
        The inertia tensor.
    time : sympy expression, default ``t``
    mass_text, mass_latex : str
        How the inertia tensor is printed; the default label is ``−ω×(Θω)``.
    text, latex : str, optional
        Labels replacing the default ones (e.g. ``"−ω×Jω"``).

    Returns
    -------
    Term

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Vector
    >>> w = Vector("omega", text="ω", latex=r"\\omega")
    >>> term = gyroscopic_term(w, sympy.diag(1, 2, 3), mass_text="J", mass_latex="J", text="−ω×Jω")
    >>> term.text, term.latex
    ('−ω×Jω', '-\\\\omega\\\\times(J\\\\omega)')
    >>> sympy.expand(term.expr.dot(w(t)))     # the gyroscopic torque does no work
    0
    """
    _check_vector(omega, "the angular velocity", "gyroscopic_term")
    w = omega(time)
    Theta = sympy.Matrix(Theta)
    return Term(-cross(w, Theta * w), text=text or f"−{omega.text}×({mass_text}{omega.text})",
                latex=latex or rf"-{omega.latex}\times({mass_latex}{omega.latex})")


def euler_equation(omega: Vector, Theta, torques: Sequence[Term], *, time=t, mass_text: str = "Θ",
                   mass_latex: str = r"\Theta", gyroscopic_text: str = "", gyroscopic_latex: str = "") -> Equation:
    """Euler's dynamic equation ``Θ ω̇ = −ω × (Θω) + Σ torques``.

    Parameters
    ----------
    omega : Vector
        The angular velocity (body axes), dimension 3.
    Theta : 3 × 3 matrix
        The inertia tensor, the mass of the equation.
    torques : sequence of Term
        The control and disturbance torques (3-vectors), in the order the paper prints them.
    time : sympy expression, default ``t``
        The time of the gyroscopic term.
    mass_text, mass_latex : str
        How Θ is printed in term and block labels.
    gyroscopic_text, gyroscopic_latex : str, optional
        Labels of the gyroscopic term replacing ``−ω×(Θω)``.

    Returns
    -------
    Equation
        With terms ``[−ω×(Θω), *torques]`` and mass Θ.

    Raises
    ------
    InputError
        If ``omega`` is not a 3-vector state or a torque is not a :class:`Term`.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Term, Vector, t
    >>> w = Vector("omega", text="ω", latex=r"\\omega")
    >>> eq = euler_equation(w, sympy.diag(5, 6, 4), [Term(-w(t), text="−ω")])
    >>> eq.mass_text, [term.text for term in eq.solved_terms()]
    ('Θ', ['Θ⁻¹(−ω×(Θω))', 'Θ⁻¹(−ω)'])
    >>> euler_equation(w, sympy.eye(3), [w(t)])
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: euler_equation: expected torques as Term objects, got MutableDenseMatrix at position 0; wrap each torque as Term(expr, text=...)
    """
    _check_vector(omega, "the angular velocity", "euler_equation")
    torques = list(torques)
    for i, torque in enumerate(torques):
        if not isinstance(torque, Term):
            raise InputError(f"euler_equation: expected torques as Term objects, got {type(torque).__name__} "
                             f"at position {i}; wrap each torque as Term(expr, text=...)")
    gyro = gyroscopic_term(omega, Theta, time=time, mass_text=mass_text, mass_latex=mass_latex,
                           text=gyroscopic_text, latex=gyroscopic_latex)
    return Equation(omega, [gyro, *torques], mass=Theta, mass_text=mass_text, mass_latex=mass_latex)


def poisson_equation(omega: Vector, vector: Vector, *, time=t) -> Equation:
    """Poisson's kinematic equation ``ṡ = −ω × s`` of an inertial vector ``s`` in body axes.

    The term is labelled ``−ω×s`` with the state's name (text) and LaTeX.

    Parameters
    ----------
    omega : Vector
        The angular velocity, dimension 3.
    vector : Vector
        The inertial vector, usually a :class:`~lkverify.declare.states.UnitVector`
        or a vector of a :class:`~lkverify.declare.states.Frame`.
    time : sympy expression, default ``t``

    Returns
    -------
    Equation

    Examples
    --------
    >>> from lkverify import UnitVector, Vector
    >>> w = Vector("omega", text="ω", latex=r"\\omega")
    >>> eq = poisson_equation(w, UnitVector("s1", latex="s_1"))
    >>> eq.terms[0].text, eq.terms[0].latex
    ('−ω×s1', '-\\\\omega\\\\times s_1')
    """
    _check_vector(omega, "the angular velocity", "poisson_equation")
    _check_vector(vector, "the inertial vector", "poisson_equation")
    return Equation(vector, [Term(-cross(omega(time), vector(time)), text=f"−{omega.text}×{vector.name}",
                                  latex=rf"-{omega.latex}\times {vector.latex}")])


def poisson_equations(omega: Vector, vectors, *, time=t) -> list[Equation]:
    """Poisson's equation for each vector of ``vectors`` (a sequence or a Frame), in order.

    Examples
    --------
    >>> from lkverify import Frame, Vector
    >>> w = Vector("omega", text="ω", latex=r"\\omega")
    >>> [eq.state.name for eq in poisson_equations(w, Frame())]
    ['s1', 's2', 's3']
    """
    return [poisson_equation(omega, v, time=time) for v in vectors]


def _pairs(vectors, targets, weights, function: str):
    vectors, targets = list(vectors), list(targets)
    weights = [sympy.S.One] * len(vectors) if weights is None else [sympy.sympify(a) for a in weights]
    if not (len(vectors) == len(targets) == len(weights)):
        raise InputError(f"{function}: expected as many targets and weights as vectors, got {len(vectors)} "
                         f"vectors, {len(targets)} targets and {len(weights)} weights; pass one target rᵢ "
                         f"(and one weight aᵢ) per vector sᵢ")
    for v in vectors:
        _check_vector(v, "each body vector", function)
    return vectors, [as_column(r) for r in targets], weights


def restoring_torque(vectors, targets, weights=None, *, time=t) -> sympy.Matrix:
    """``Σ aᵢ sᵢ(time) × rᵢ``, the restoring torque of the vectors towards their targets.

    Parameters
    ----------
    vectors : sequence of Vector
        The body vectors s₁, s₂, … (dimension 3).
    targets : sequence of 3-vectors
        Their targets r₁, r₂, … (constants).
    weights : sequence, optional
        The coefficients a₁, a₂, …; all 1 if omitted.
    time : sympy expression, default ``t``
        ``t``, ``t - tau`` or an integration variable ``xi``.

    Returns
    -------
    sympy.Matrix
        A 3 × 1 column.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import UnitVector, t
    >>> s = UnitVector("s"); a = sympy.Symbol("a")
    >>> restoring_torque([s], [[0, 0, 1]], [a]).T
    Matrix([[a*s_y(t), -a*s_x(t), 0]])
    """
    vectors, targets, weights = _pairs(vectors, targets, weights, "restoring_torque")
    return sum((a * cross(v(time), r) for v, r, a in zip(vectors, targets, weights)), sympy.zeros(3, 1))


def restoring_torque_rate(omega: Vector, vectors, targets, weights=None, *, time=t) -> sympy.Matrix:
    """``Σ aᵢ (ω × sᵢ) × rᵢ``: minus the rate of :func:`restoring_torque` along Poisson's equation.

    Since ``ṡᵢ = −ω × sᵢ``, ``d/dt Σ aᵢ sᵢ × rᵢ = −Σ aᵢ (ω × sᵢ) × rᵢ``.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import UnitVector, Vector, cross, t
    >>> w, s = Vector("omega"), UnitVector("s")
    >>> r = sympy.Matrix([0, 0, 1])
    >>> s_dot = poisson_equation(w, s).terms[0].expr          # ṡ = −ω × s
    >>> sympy.expand(cross(s_dot, r) + restoring_torque_rate(w, [s], [r])) == sympy.zeros(3, 1)
    True
    """
    _check_vector(omega, "the angular velocity", "restoring_torque_rate")
    vectors, targets, weights = _pairs(vectors, targets, weights, "restoring_torque_rate")
    w = omega(time)
    return sum((a * cross(cross(w, v(time)), r) for v, r, a in zip(vectors, targets, weights)), sympy.zeros(3, 1))


def distance_sum(vectors, targets, power, weights=None, *, time=t) -> sympy.Expr:
    """``Σ aᵢ ‖sᵢ(time) − rᵢ‖^power``, every norm power written as ``(‖·‖²)^(power/2)``.

    Uses :func:`~lkverify.declare.vectors.norm_power`, so the result is structurally
    comparable with expressions written by hand with it (``power = 2`` gives the
    polynomial ``‖sᵢ − rᵢ‖²``).

    Examples
    --------
    >>> import sympy
    >>> from lkverify import UnitVector, t
    >>> from lkverify.declare.vectors import norm_squared
    >>> s1, s2 = UnitVector("s1"), UnitVector("s2")
    >>> r1, r2 = [1, 0, 0], [0, 1, 0]
    >>> a1, a2 = sympy.symbols("a1 a2")
    >>> d = distance_sum([s1, s2], [r1, r2], 2, [a1 / 2, a2 / 2])
    >>> sympy.expand(d - (a1 * norm_squared(s1(t) - sympy.Matrix(r1)) + a2 * norm_squared(s2(t) - sympy.Matrix(r2))) / 2)
    0
    """
    vectors, targets, weights = _pairs(vectors, targets, weights, "distance_sum")
    return sum((a * norm_power(v(time) - r, power) for v, r, a in zip(vectors, targets, weights)), sympy.S.Zero)
