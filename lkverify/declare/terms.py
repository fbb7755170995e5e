"""Labelled terms: an expression together with how the paper prints it.

Term-by-term reports name terms by these labels, so a proof module gives each
term of a functional, of a right-hand side and of a printed derivative the text
(and LaTeX) the paper uses.
"""

from __future__ import annotations

import dataclasses

import sympy

__all__ = ["Term"]


@dataclasses.dataclass(frozen=True)
class Term:
    """A labelled scalar or vector expression.

    Parameters
    ----------
    expr : sympy expression or column matrix
    text : str, optional
        Plain-text label, e.g. ``"−γ ωᵀDω"``; defaults to SymPy's string form.
    latex : str, optional
        LaTeX label; defaults to SymPy's LaTeX form.

    Examples
    --------
    >>> import sympy
    >>> Term(sympy.Symbol("x") ** 2, text="x²").text
    'x²'
    """

    expr: object
    text: str = ""
    latex: str = ""

    def __post_init__(self):
        expr = self.expr
        if isinstance(expr, (list, tuple)):
            expr = sympy.Matrix(expr)
        if isinstance(expr, sympy.MatrixBase):
            expr = sympy.ImmutableMatrix(expr)
        else:
            expr = sympy.sympify(expr)
        object.__setattr__(self, "expr", expr)
        if not self.text or not self.latex:
            plain = sympy.sstr(expr)
            if not self.text:
                object.__setattr__(self, "text", _short(plain))
            if not self.latex:
                object.__setattr__(self, "latex", sympy.latex(expr) if len(plain) < 400 else self.text)

    @property
    def is_vector(self) -> bool:
        return isinstance(self.expr, sympy.MatrixBase)

    @property
    def shape(self):
        return self.expr.shape if self.is_vector else ()

    def scaled(self, factor, *, text: str | None = None, latex: str | None = None) -> "Term":
        """This term multiplied by ``factor``."""
        return Term(factor * self.expr, text=text or f"{factor}·({self.text})",
                    latex=latex or rf"{sympy.latex(factor)}\left({self.latex}\right)")


def _short(s: str, n: int = 160) -> str:
    return s if len(s) <= n else s[: n - 1] + "…"
