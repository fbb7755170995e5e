"""The job behind ``lkverify linear``: spectrum, stability intervals, certified delays per order.

Examples
--------
>>> rep = linear_report({"A": [[-2, 0], [0, "-0.9"]], "Ad": [[-1, 0], [-1, -1]]}, orders=(0,), h_max=10)
>>> [(r.name, r.status.value) for r in rep.results]       # doctest: +NORMALIZE_WHITESPACE
[('stability intervals (spectral)', 'estimated'), ('stability intervals (certified)', 'certified'),
 ('delay margin (spectral)', 'estimated'), ('certified delays (jensen)', 'exact')]
>>> rep.results[1].value["stable"], rep.results[1].value["unstable"]          # doctest: +ELLIPSIS
([[0.0, 6.172581...]], [[6.172581..., 10.0]])
"""

from __future__ import annotations

import dataclasses
import math
import time

import sympy

from ..errors import InputError
from ..report.results import Report, Result
from ..status import Status
from .crossing import stability_intervals
from .hierarchy import certify_delay, method_name
from .independent import FUNCTIONAL, certificate_detail, delay_independence
from .instability import refute_stability
from .margin import certified_interval
from .model import LinearDelaySystem, parse_delay
from .spectrum import rightmost_roots

__all__ = ["LINEAR_NAMES", "linear_report", "system_from_values"]

#: the names ``--set`` accepts: A, Ad, D (constant kernel) or D0, D1, … (kernel Σ D_j u^j)
LINEAR_NAMES = ("A", "Ad", "D", "D0", "D1", "D2", "D3", "D4", "D5")
#: the default orders: Jensen, Wirtinger, Bessel–Legendre 2, 3, 4
DEFAULT_ORDERS = (0, 1, 2, 3, 4)


def system_from_values(values: dict) -> LinearDelaySystem:
    """A :class:`LinearDelaySystem` from ``--set`` values (A required; Ad; D or D0, D1, …).

    >>> system_from_values({"A": [[-1]], "D": [[-1]]}).has_distributed
    True
    >>> system_from_values({"Ad": [[1]]})
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: A: expected the matrix A of ẋ = A x + A_d x(t−h) + ∫ D x (e.g. A=[[-2,0],[0,-1]]), got no A
    """
    unknown = sorted(set(values) - set(LINEAR_NAMES))
    if unknown:
        raise InputError(f"{', '.join(unknown)}: unknown name(s); expected some of {', '.join(LINEAR_NAMES)} "
                         "(A, Ad, and D for a constant kernel or D0, D1, … for K(u) = Σ D_j u^j)", topic="parameters",
                         example="A=[[-2,0],[0,-1]]")
    if "A" not in values:
        raise InputError("A: expected the matrix A of ẋ = A x + A_d x(t−h) + ∫ D x (e.g. A=[[-2,0],[0,-1]]), "
                         "got no A", topic="parameters", example="A=[[-2,0],[0,-1]]")
    if "D" in values and "D0" in values:
        raise InputError("D and D0: expected one of them (both name the constant part of the kernel)",
                         topic="parameters")
    kernel = []
    degrees = [int(k[1:]) for k in values if k.startswith("D") and k != "D"]
    top = max(degrees, default=0 if "D" in values else -1)
    for j in range(top + 1):
        key = "D" if j == 0 and "D" in values else f"D{j}"
        kernel.append(values.get(key))
    n = _size(values["A"])
    kernel = [K if K is not None else [[0] * n for _ in range(n)] for K in kernel]
    return LinearDelaySystem(_matrix(values["A"], "A"), Ad=_matrix(values.get("Ad"), "Ad"),
                             kernel=[_matrix(K, "D") for K in kernel], name="user system")


def _matrix(v, name):
    """A scalar given for a 1×1 system becomes [[v]]; matrices pass through (validated by the model)."""
    if v is None:
        return None
    if isinstance(v, sympy.MatrixBase):
        return v
    if isinstance(v, (sympy.Basic, int, float)):
        return [[v]]
    return v


def _size(v) -> int:
    if isinstance(v, sympy.MatrixBase):
        return v.rows
    if isinstance(v, (list, tuple)):
        return len(v)
    return 1


def linear_report(values: dict, *, orders=DEFAULT_ORDERS, h_max: float = 20.0, h=None, plot=None,
                  say=None) -> Report:
    """Spectral abscissa, stability intervals and, per order, the certified delays; one :class:`Report`.

    Parameters
    ----------
    values : dict
        ``A``, ``Ad``, ``D`` / ``D0``, ``D1``, … (matrices, exact).
    orders : sequence of int
        Orders of the LMI hierarchy (0 Jensen, 1 Wirtinger, ≥ 2 Bessel–Legendre).
    h_max : float
        The largest delay of the stability analysis.
    h : number, optional
        A delay at which the spectrum is reported and each order's LMI is solved and verified.
    plot : str or Path, optional
        Write the figure (spectrum at h or at the margin, abscissa over h) there.
    say : callable, optional
        Progress messages.

    Returns
    -------
    Report
        Results of kind ``linear``: the spectral results ``estimated``; each order's certified
        delays ``exact`` (rational data) or ``certified`` when verified, ``undecided`` otherwise.
        With ``h``: "stable at h" is ``failed`` when a characteristic root is certified in the
        open right half-plane (:func:`~lkverify.linear.instability.refute_stability`; no LMI is
        solved then), ``exact``/``certified`` when an order's LMI verified, else ``undecided``.
        Without ``h``, a system whose stability does not depend on the delay (no crossing
        frequency ω > 0, decided exactly: :func:`~lkverify.linear.independent.delay_independence`)
        gets no margin search: the row "stable for every delay h ≥ 0" (``exact``, its value's
        ``margin_infinite`` True and ``delay_margin`` "infinite"; ``failed`` when A + A_d is not
        Hurwitz: stable for no delay) and, when stable, "delay-independent LK certificate"
        (P, Q of V = xᵀPx + ∫_{t−h}^t xᵀQx as exact rational strings, verified exactly; ``undecided``
        when the LMI, only sufficient, gave none).

    Examples
    --------
    >>> rep = linear_report({"A": [[-1]], "Ad": [["0.5"]]}, orders=(1,), h="2", h_max=5)
    >>> rep.results[-1].name, rep.results[-1].status.value, rep.exit_code
    ('stable at h = 2', 'exact', 0)
    >>> rep = linear_report({"A": [[1]], "Ad": [["-1/2"]]}, orders=(1,), h="1", h_max=5)   # x′ = x − x(t−1)/2
    >>> rep.results[-1].status.value, rep.exit_code, rep.verdict[:40]
    ('failed', 1, 'unstable at h = 1: a characteristic root')
    >>> rep = linear_report({"A": [[-2]], "Ad": [[1]]})                 # x′ = −2x + x(t−h): no crossing
    >>> [(r.name, r.status.value) for r in rep.results], rep.results[0].value["margin_infinite"]
    ([('stable for every delay h ≥ 0', 'exact'), ('delay-independent LK certificate', 'exact')], True)
    >>> rep.verdict[:60], rep.results[1].value["P"]                        # doctest: +ELLIPSIS
    ('stable for every delay h ≥ 0, delay margin infinite (exact: ', [['.../...']])
    """
    say = say or (lambda *a, **k: None)
    if not (isinstance(h_max, (int, float)) and math.isfinite(h_max) and h_max > 0):
        raise InputError(f"h-max: expected a positive finite delay, got {h_max}")
    hq = None if h is None else parse_delay(h)
    system = system_from_values(values)
    results = []
    if hq is not None:
        sp = rightmost_roots(system, float(hq))
        results.append(Result("linear", f"spectral abscissa at h = {hq}", Status.ESTIMATED, sp.abscissa,
                              f"rightmost root {sp.roots[0]:.6g}; {sp.detail}"))
    if hq is None:
        say("delay independence: crossing frequencies and A + A_d at h = 0, exactly")
        di = delay_independence(system)
        if di.applies:  # stable (or not) for every delay: no margin to search, no h_max in the answer
            return _independent_report(values, system, di, h_max, plot)
    t0 = time.perf_counter()
    iv = stability_intervals(system, h_max=h_max)
    t_spec = time.perf_counter() - t0
    if hq is None:
        say("certified intervals: crossing delays enclosed, one proof per interval")
        iv, certified_row = _certified(system, iv, h_max)
    shown = ", ".join(f"({lo:.7g}, {hi:.7g})" if lo > 0 else f"[0, {hi:.7g})" for lo, hi in iv.intervals) or "none"
    results.append(Result("linear", "stability intervals (spectral)", Status.ESTIMATED,
                          {"intervals": [list(x) for x in iv.intervals], "method": iv.method},
                          f"stable for h in {shown} within [0, {h_max:g}]; {iv.detail}; {t_spec:.2f} s"))
    if iv.certified:
        results.append(certified_row)
    if iv.margin is not None:
        results.append(Result("linear", "delay margin (spectral)", Status.ESTIMATED, iv.margin,
                              f"the first crossing delay, from the crossing analysis ({iv.method}); "
                              f"{len(iv.crossings)} crossing(s) in [0, {h_max:g}]"))
    target = iv.intervals[0] if iv.intervals else None
    if not system.constant_kernel:
        results.append(Result("linear", "certified delays", Status.UNDECIDED, None,
                              f"the LMI hierarchy here covers constant kernels; this kernel has degree "
                              f"{system.kernel_order} (the spectral results above still hold as estimates)"))
        orders = ()
    if hq is not None:
        results += _at_delay(system, h, hq, orders, say)
    else:
        results += _margins(system, target, orders, h_max, say)
    verdict = _verdict(results, iv)
    details = ()
    if plot is not None:
        from .figures import plot_linear
        certified = [(r.name[len("certified delays ("):-1], r.value) for r in results
                     if r.name.startswith("certified") and r.status.is_proof]
        path = plot_linear(system, plot, intervals=iv, h=None if hq is None else float(hq), certified=certified)
        details = (f"figure: {path}",)
    return Report("linear", dict(values), tuple(results), verdict, text_details=details)


def _independent_rows(di) -> list:
    """The exact decision for every delay (and, when stable, the delay-independent LK certificate)."""
    value = {**({"value": math.inf} if di.stable else {}), "stable": di.stable,
             "delay_margin": "infinite" if di.stable else None,
             "margin_infinite": di.margin_infinite, "hurwitz_at_h0": di.hurwitz,
             "positive_crossing_frequencies": di.positive_roots,
             "frequency_polynomial": None if di.polynomial is None else str(di.polynomial.as_expr())}
    rows = [Result("linear", "stable for every delay h ≥ 0", di.status, value, di.detail)]
    if di.stable:
        cert = {"certified": di.certified, "functional": FUNCTIONAL, "margin_infinite": di.certified,
                **(di.certificate.to_json() if di.certificate is not None else {"P": None, "Q": None})}
        status = di.check.status if di.certified else Status.UNDECIDED   # not found refutes nothing
        rows.append(Result("linear", "delay-independent LK certificate", status, cert, certificate_detail(di)))
    return rows


def _independent_verdict(di) -> str:
    if not di.stable and di.detail.startswith("unstable"):
        return (f"unstable for every delay h ≥ 0: A + A_d has a root with Re λ > 0 and no root crosses the "
                f"imaginary axis for any h ({di.status.value}; decided exactly)")
    if not di.stable:
        return (f"asymptotically stable for no delay h ≥ 0: det(A + A_d) = 0, λ = 0 is a characteristic root for "
                f"every h ({di.status.value}; decided exactly)")
    text = (f"stable for every delay h ≥ 0, delay margin infinite ({di.status.value}: no crossing frequency, "
            "A + A_d Hurwitz)")
    if di.certified:
        return text + f"; certified by {FUNCTIONAL}, P and Q verified exactly ({di.check.status.value})"
    return text + "; no delay-independent LK certificate found (the LMI is only sufficient)"


def _independent_report(values, system, di, h_max, plot) -> Report:
    """The report of a system whose stability does not depend on the delay (:mod:`lkverify.linear.independent`)."""
    details = ()
    if plot is not None:
        from .figures import plot_linear
        path = plot_linear(system, plot, intervals=stability_intervals(system, h_max=h_max),
                           title="spectral abscissa (stability does not depend on h)")
        details = (f"figure: {path}",)
    return Report("linear", dict(values), tuple(_independent_rows(di)), _independent_verdict(di),
                  text_details=details)


def _certified(system, iv, h_max):
    """``iv`` with its certified stretches (:mod:`lkverify.linear.stretches`), and their report row."""
    from .stretches import certify_stretches

    t0 = time.perf_counter()
    iv = dataclasses.replace(iv, certified=certify_stretches(system, h_max, estimated=iv.intervals))
    return iv, (_certified_row(iv, h_max, time.perf_counter() - t0) if iv.certified else None)


def _certified_row(iv, h_max, seconds) -> Result:
    """Stable and unstable delays, each proved (``certified``), or undecided where a proof was not found."""
    parts = iv.certified
    points = parts[0].point
    value = {kind: [[c.lo, c.hi] for c in parts if c.kind == kind] for kind in ("stable", "unstable", "undecided")}
    value["points_only"] = points

    def shown(kind):
        got = [c for c in parts if c.kind == kind]
        if points:
            return ", ".join(f"h = {c.sample}" for c in got) or "none"
        return ", ".join(f"({c.lo:.10g}, {c.hi:.10g})" for c in got) or "none"

    status = Status.CERTIFIED if all(c.holds for c in parts) else Status.UNDECIDED
    what = "at the single delays" if points else "on the open intervals"
    detail = (f"proved stable {what} {shown('stable')}; proved unstable {what} {shown('unstable')}"
              + (f"; undecided: {shown('undecided')}" if value["undecided"] else "")
              + f" (within (0, {h_max:g}); {seconds:.2f} s). "
              + " | ".join(c.detail for c in parts))
    name = "stability at sample delays (certified)" if points else "stability intervals (certified)"
    return Result("linear", name, status, value, detail)


def _at_delay(system, h, hq, orders, say) -> list:
    """At one delay: a right half-plane root certified (``failed``), else each order's LMI; then "stable at h"."""
    say("instability: interval Newton on the rightmost roots")
    inst = refute_stability(system, h)
    name = f"stable at h = {hq}"
    if inst.refuted:
        root = inst.root
        value = {"h": hq, "root": {"real": list(root.real), "imag": list(root.imag), "ball": root.enclosure}}
        return [Result("linear", name, Status.FAILED, value,
                       f"{inst.detail}; no LMI is solved at this delay (no Lyapunov–Krasovskii certificate exists "
                       f"for an unstable system)")]
    rows = []
    for order in orders:
        label = method_name(order)
        say(f"LMI {label}")
        res = certify_delay(system, h, order=order)        # h as given: a float stays at most certified
        rows.append(Result("linear", f"{label} at h = {hq}", res.status, float(hq),
                           f"{res.detail} (solve {res.solve_seconds:.2f} s, check {res.check_seconds:.2f} s)"))
    proved = [r for r in rows if r.status.is_proof]
    if proved:
        best = min(proved, key=lambda r: r.status is not Status.EXACT)
        rows.append(Result("linear", name, best.status, float(hq), f"stability at h = {hq} proved by {best.name}"))
    else:
        rows.append(Result("linear", name, Status.UNDECIDED, float(hq),
                           f"neither proved (no LMI order verified) nor refuted ({inst.detail})"))
    return rows


def _margins(system, target, orders, h_max, say) -> list:
    """Per order: the certified delays inside the first stability interval (bisection, ends verified)."""
    rows = []
    for order in orders:
        name = method_name(order)
        say(f"LMI {name}")
        if target is None:
            rows.append(Result("linear", f"certified delays ({name})", Status.UNDECIDED, None,
                               f"no stability interval in [0, {h_max:g}]: nothing to certify"))
            continue
        m = certified_interval(system, target, order=order)
        value = {"value": m.upper, "lower": m.lower, "upper": m.upper, "solves": m.solves, "seconds": m.seconds}
        rows.append(Result("linear", f"certified delays ({name})", m.status, value, m.detail))
    return rows


def _verdict(results, iv) -> str:
    text = _verdict_spectral(results, iv)
    row = next((r for r in results if r.name.endswith("(certified)")), None)
    if row is not None and not row.value["points_only"]:
        def ends(kind):
            got = row.value[kind]
            shown = ", ".join(f"({a:.7g}, {b:.7g})" for a, b in got[:3]) or "none"
            return shown + (f" and {len(got) - 3} more up to {got[-1][1]:.7g}" if len(got) > 3 else "")
        text += f"; proved stable on {ends('stable')} and unstable on {ends('unstable')} ({row.status.value})"
    return text


def _verdict_spectral(results, iv) -> str:
    at = next((r for r in results if r.name.startswith("stable at h")), None)
    if at is not None:
        h = at.name[len("stable at h = "):]
        if at.status is Status.FAILED:
            root = at.value["root"]
            return (f"unstable at h = {h}: a characteristic root certified in the open right half-plane, "
                    f"s = {root['ball']} (Re s ≥ {root['real'][0]:.6g} > 0)")
        if at.status.is_proof:
            return f"stable at h = {h} ({at.detail}, {at.status.value})"
        return f"stability at h = {h} undecided: {at.detail}"
    certified = [r for r in results if r.name.startswith("certified") and r.status.is_proof]
    spectral = (f"delay margin {iv.margin:.7g} (spectral, estimated)" if iv.margin is not None else
                ("stability intervals " + ", ".join(f"({a:.7g}, {b:.7g})" for a, b in iv.intervals)
                 if iv.intervals else "no stability interval found"))
    if not certified:
        return spectral + "; no delay certified by an LMI"
    best = max(certified, key=lambda r: r.value["upper"])
    lo = best.value["lower"]
    where = f"[{lo:.7g}, {best.value['upper']:.7g}] (each end)" if lo is not None else f"h = {best.value['upper']:.7g}"
    return f"{spectral}; certified at {where} by {best.name[len('certified delays ('):-1]} ({best.status.value})"
