"""‖χ‖_τ of the Fig. 7 initial data of paper 002: the paper reports 0.25 (inside its region 0.28).

Every reading of the printed angles (convention, matrix direction, unit, norm) is tried
(:func:`lkverify.simulate.rigidbody.chi_norm_table`); a float computation, so at best
``estimated``.
"""

from lkverify import Check, Result, Status
from lkverify.simulate.rigidbody import chi_norm_table

from .equations import PAPER, P
from .section6 import R_TARGET

__all__ = ["fig7_chi", "fig7_chi_check"]

REPORTED_CHI = 0.25  # ‖χ‖_τ printed for the Fig. 7 data


def fig7_chi_check(v):
    """The printed ‖χ‖_τ = 0.25 of the Fig. 7 data against every reading of its angles."""
    table = chi_norm_table((0.8, 0.8, -0.8), (0.1, 0.1, 0.1), list(R_TARGET), reported=REPORTED_CHI)
    values = sorted({round(row.value, 4) for row in table.rows})
    nearest = min(values, key=lambda x: abs(x - REPORTED_CHI))
    status = Status.FAILED if not table.reproduced else Status.ESTIMATED  # a float computation, not a proof
    return [Result("constant", "‖χ‖_τ of the Fig. 7 data (printed 0.25)", status,
                   {"default": table.default, "values": values, "nearest": nearest, "reproduced": table.reproduced},
                   f"computed {table.default:.4g} under the default reading (GOST yzx aircraft angles, radians, "
                   f"uniform norm of (s − r, ω)); over every convention, matrix direction, angle unit and norm "
                   f"definition the values are {values[0]:.3g} … {values[-1]:.3g}, the nearest to 0.25 being "
                   f"{nearest:.3g}: the printed 0.25 is not reproduced")]


fig7_chi = Check("fig7_chi", parameters=P, checks=[fig7_chi_check], relevant=(), paper=PAPER,
                 title="‖χ‖_τ of the Fig. 7 initial data: the printed 0.25 against every reading of the angles")
