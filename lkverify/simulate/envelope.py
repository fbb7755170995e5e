"""Envelope cross-check: a predicted decay envelope against a trajectory.

>>> import numpy as np
>>> t = np.linspace(0, 10, 101)
>>> r = cross_check(t, np.exp(-t), np.exp(-t / 2), name="demo")
>>> r.status.value, round(r.max_ratio, 6), r.first_violation
('simulated', 1.0, None)
>>> cross_check(t, np.exp(-t / 3), np.exp(-t / 2)).status.value
'failed'
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..status import Status
from ..errors import InputError

__all__ = ["EnvelopeCheck", "cross_check"]


@dataclasses.dataclass(frozen=True)
class EnvelopeCheck:
    """The largest ratio trajectory / envelope along a run and the first violation.

    Attributes
    ----------
    status : Status
        ``simulated`` when the envelope holds at every sample (it was observed,
        not proved), ``failed`` at the first sample where it does not.
    max_ratio : float
        max over samples of quantity / envelope (≤ 1 when the envelope holds;
        small means a loose envelope).
    t_max_ratio : float
    first_violation : float or None
        The first sample time with quantity > envelope (relative tolerance ``rtol``).

    Examples
    --------
    e^(−t/3) against the envelope e^(−t/2): above it from the first sample after 0.

    >>> import numpy as np
    >>> t = np.linspace(0, 4, 5)
    >>> chk = cross_check(t, np.exp(-t / 3), np.exp(-t / 2), name="e^(-t/2)")
    >>> chk.name, chk.status.value, chk.first_violation, chk.t_max_ratio
    ('e^(-t/2)', 'failed', 1.0, 4.0)
    >>> {k: round(v, 6) for k, v in chk.to_json().items()}         # max ratio e^(4/6)
    {'max_ratio': 1.947734, 't_max_ratio': 4.0, 'first_violation': 1.0, 'samples': 5}
    """

    name: str
    status: Status
    max_ratio: float
    t_max_ratio: float
    first_violation: float | None
    samples: int

    def to_json(self) -> dict:
        return {"max_ratio": self.max_ratio, "t_max_ratio": self.t_max_ratio,
                "first_violation": self.first_violation, "samples": self.samples}


def cross_check(t, quantity, envelope, *, name: str = "envelope", rtol: float = 1e-9) -> EnvelopeCheck:
    """Compare ``quantity(t) ≤ envelope(t)`` sample by sample.

    Parameters
    ----------
    t, quantity, envelope : array_like
        Sample times and the two curves at them.
    rtol : float
        Relative slack for rounding of the simulated values.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.array([0.0, 1.0, 2.0])
    >>> chk = cross_check(t, [1.0, 0.5, 0.2], [1.0, 0.6, 0.4])
    >>> chk.status.value, round(chk.max_ratio, 6), chk.first_violation
    ('simulated', 1.0, None)
    >>> cross_check(t, [1.0, 0.7, 0.2], [1.0, 0.6, 0.4]).first_violation
    1.0
    >>> cross_check(t, [1.0, 0.5], [1.0, 0.6, 0.4])
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: t, quantity and envelope must have one shape, got (3,), (2,), (3,)
    """
    t = np.asarray(t, dtype=float)
    q = np.asarray(quantity, dtype=float)
    e = np.asarray(envelope, dtype=float)
    if not (t.shape == q.shape == e.shape):
        raise InputError(f"t, quantity and envelope must have one shape, got {t.shape}, {q.shape}, {e.shape}")
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(e > 0, q / e, np.inf)
    k = int(np.nanargmax(ratio))
    bad = np.nonzero(q > e * (1 + rtol))[0]
    first = float(t[bad[0]]) if bad.size else None
    return EnvelopeCheck(name, Status.FAILED if bad.size else Status.SIMULATED, float(ratio[k]), float(t[k]),
                         first, int(t.size))
