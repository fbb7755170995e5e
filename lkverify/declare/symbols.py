"""The canonical time symbol and integration variables.

Every expression lkverify manipulates is written in the time ``t``; window and
memory integrals run over ``xi``, and kernel tails (the inner integrals of a
double-integral term) over ``zeta``.  Using these shared symbols is what makes
two independently written expressions comparable.
"""

from __future__ import annotations

import sympy

__all__ = ["t", "xi", "zeta", "INTEGRATION_VARIABLES"]

#: Time.
t = sympy.Symbol("t", real=True)
#: Integration variable of window and memory integrals.
xi = sympy.Symbol("xi", real=True)
#: Integration variable of kernel tails, e.g. the inner integral of paper 000's (14).
zeta = sympy.Symbol("zeta", real=True)

INTEGRATION_VARIABLES = (xi, zeta)
