"""The region of attraction of paper 003's closed loop (3), (11) from the comparison system, and against a simulated grid.

From the comparison system of :mod:`.comparison`, D⁺‖V‖ ≤ φ(‖V‖) with φ(r) = −αr + (3/β)max(0, g(r)),
g(r) = k0r + 2k0r² + 6k0r³ − a_m/4:

* r0, the positive root of g: on ‖V‖ ≤ r0 the saturation is inactive (‖u_lin‖₂ ≤ a_m there), the
  loop is (10) and V̇ = AV;
* ρ*, the smallest root of ψ(r) = −αr + (3/β)g(r) above r0: φ < 0 on (0, ρ*) (φ = −αr on (0, r0],
  ψ(r0) = −αr0 < 0 and ψ has no root in [r0, ρ*)), so {‖V‖ < ρ*} is positively invariant and
  ‖V‖ → 0, hence σ → 0, σ̇ → 0 and ω = D(σ)σ̇ → 0: the limits (5).  r0 and ρ* are algebraic numbers
  (roots of cubics with the run's rational coefficients), the sign conditions decided by exact root
  isolation: status ``exact``.
* In the initial data (the text's |σ(t0)|, ‖ω(t0)‖): ‖V‖² = Q₁₁|σ|² + 2Q₁₂σ·σ̇ + Q₂₂|σ̇|² (Q of
  :mod:`.comparison`) with |σ̇| = ¼(1 + |σ|²)‖ω‖, so every initial state with
  Q₁₁s² + 2|Q₁₂|s·y + Q₂₂y² < ρ*², s = |σ(t0)|, y = ¼(1 + s²)‖ω(t0)‖, is attracted.  The row's
  status is computed from the comparison system's steps (:func:`.comparison.majorant_steps`,
  :func:`.norm_steps.chain_status`): ``exact`` only if every identity and norm step is.

``lkverify constants somov.region`` simulates the closed loop (3), (11) on a grid of (|σ0|, ‖ω0‖)
(four direction pairs each, :mod:`.grid`) and compares: the region's set must lie inside the
converged one (status ``simulated``), and the ratio of their areas in the (|σ0|, ‖ω0‖) rectangle is
reported (``estimated``).  At the catalogued instance the region is |σ0| < 0.078 (Φ0 < 18°)
at ω0 = 0 — the majorant is crude — while every sampled state with |σ0| ≤ 1 and ‖ω0‖ ≤ 0.25 rad/s
converges (area ratio ≈ 0.006); faster initial spins carry the body through Φ = 2π, where the MRP of
this law (no switching to the shadow set) runs off to infinity.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import sympy

from lkverify import Report, Result, Status
from lkverify.catalogue.signal_theorem import SignalTheorem

from .comparison import channel_form, majorant, majorant_steps
from .equations import PAPER, closed_loop
from .grid import ATOL, CONVERGED, NOT_CONVERGED, RTOL, run_grid, run_points
from .norm_steps import chain_status, inequality_step

__all__ = ["CertifiedRegion", "certified_region", "check_radius", "region", "RegionConstants", "W_RANGE"]


@dataclasses.dataclass(frozen=True)
class CertifiedRegion:
    """r0, ρ* (exact algebraic numbers) and the initial-data form (Q₁₁, |Q₁₂|, Q₂₂)."""

    r0: sympy.Expr
    rho: sympy.Expr
    Q: tuple

    def contains(self, s, w):
        """The certified predicate on (|σ0|, ‖ω0‖) (numpy, floats: for grids and figures)."""
        q11, q12, q22 = (float(x) for x in self.Q)
        y = (1 + np.asarray(s) ** 2) * np.asarray(w) / 4
        return q11 * s ** 2 + 2 * q12 * s * y + q22 * y ** 2 < float(self.rho) ** 2

    @property
    def s_max(self):
        """|σ0| bound at ω0 = 0: ρ*/√Q₁₁."""
        return self.rho / sympy.sqrt(self.Q[0])

    @property
    def w_max(self):
        """‖ω0‖ bound at σ0 = 0: 4ρ*/√Q₂₂."""
        return 4 * self.rho / sympy.sqrt(self.Q[2])

    def w_boundary(self, s):
        """The largest certified ‖ω0‖ at |σ0| = s (0 beyond s_max)."""
        q11, q12, q22 = (float(x) for x in self.Q)
        rho2 = float(self.rho) ** 2
        s = np.asarray(s, float)
        disc = (q12 * s) ** 2 - q22 * (q11 * s ** 2 - rho2)
        y = np.where(disc > 0, (-q12 * s + np.sqrt(np.maximum(disc, 0))) / q22, 0.0)
        return np.maximum(y, 0) * 4 / (1 + s ** 2)


def _smallest_root_above(poly, r, lo):
    roots = [x for x in sympy.Poly(poly, r).real_roots() if x > lo]
    return min(roots, key=lambda x: sympy.N(x, 30)) if roots else None


def certified_region(v) -> CertifiedRegion:
    """r0, ρ* and Q at resolved values (exact)."""
    r, g, psi = majorant(v)
    r0 = _smallest_root_above(g, r, 0)
    rho = _smallest_root_above(psi, r, r0)
    Q = channel_form(v)
    return CertifiedRegion(r0, rho, (Q[0, 0], abs(Q[0, 1]), Q[1, 1]))


def check_radius(v, rho) -> Result:
    """Is {‖V‖ < ρ} a region of the comparison system, φ < 0 on (0, ρ)?  Exact; a too large ρ is refuted.

    φ = −αr on (0, r0]; on [r0, ρ) φ = ψ, which is negative there iff ψ has no root in [r0, ρ) —
    i.e. ρ ≤ ρ*.  A refutation names an exact rational r < ρ with φ(r) ≥ 0.
    """
    r, g, psi = majorant(v)
    reg = certified_region(v)
    rho = sympy.sympify(rho)
    if (rho - reg.rho).is_nonpositive:
        return Result("region", f"region ||V|| < {sympy.sstr(rho)}", Status.EXACT, {"rho_star": float(reg.rho)},
                      f"ρ = {sympy.sstr(rho)} ≤ ρ* = {float(reg.rho):.6g}: φ < 0 on (0, ρ) (exact)")
    # a rational w in [ρ*, ρ) just above ρ*: ψ changes sign at its simple root ρ*, so ψ(w) ≥ 0 there
    w = None
    for digits in range(4, 40, 4):
        cand = sympy.Rational(int(sympy.ceiling(reg.rho * 10 ** digits)), 10 ** digits)
        if cand < rho and psi.subs(r, cand) >= 0:
            w = cand
            break
    if w is None:
        return Result("region", f"region ||V|| < {sympy.sstr(rho)}", Status.UNDECIDED, {"rho_star": float(reg.rho)},
                      f"ρ = {sympy.sstr(rho)} > ρ* = {float(reg.rho):.6g} but no rational witness in [ρ*, ρ) was found")
    val = (-sympy.sympify(v["alpha"]) * w + 3 * sympy.Max(0, g.subs(r, w)) / sympy.sympify(v["beta"]))
    return Result("region", f"region ||V|| < {sympy.sstr(rho)}", Status.FAILED,
                  {"rho_star": float(reg.rho), "witness": str(w), "phi": str(val)},
                  f"refuted: φ({sympy.sstr(w)}) = {sympy.sstr(val)} ≥ 0 with {sympy.sstr(w)} < ρ = {sympy.sstr(rho)} "
                  f"(ρ* = {float(reg.rho):.6g}; exact)")


def initial_data_step(Q) -> Result:
    """‖V‖² = Q₁₁|σ|² + 2Q₁₂σ·σ̇ + Q₂₂|σ̇|² ≤ Q₁₁s² + 2|Q₁₂|s·y + Q₂₂y² from |σ·σ̇| ≤ s·y (Cauchy–Schwarz)."""
    q11, q12, q22 = (sympy.sympify(x) for x in Q)
    s, y = sympy.symbols("s y", nonnegative=True)
    t = sympy.Symbol("t", real=True)
    h = s * y - sympy.sign(q12) * t
    return inequality_step("||V(t0)||^2 <= Q11 s^2 + 2|Q12| s y + Q22 y^2",
                           q11 * s ** 2 + 2 * abs(q12) * s * y + q22 * y ** 2 - (q11 * s ** 2 + 2 * q12 * t + q22 * y ** 2),
                           [(2 * abs(q12), [h], 1)], hyps=[h],
                           text="t = σ·σ̇ with |t| ≤ s·|σ̇| (Cauchy–Schwarz) and |σ̇| = ¼(1 + s²)‖ω‖ = y (‖B(σ)ω‖ = "
                                "(1 + σ²)‖ω‖)")


def _region_rows(v) -> list:
    r, g, psi = majorant(v)
    reg = certified_region(v)
    ok = reg.r0 is not None and reg.rho is not None
    Qm = channel_form(v)
    init = initial_data_step((Qm[0, 0], Qm[0, 1], Qm[1, 1]))
    comp, missing = chain_status(majorant_steps(v) + [init])
    rests = ("the comparison system D⁺‖V‖ ≤ φ(‖V‖) is exact (somov.comparison: identities and checked norm "
             "steps), and so is the bound on ‖V(t0)‖ above"
             if not missing else f"the comparison system is not proved (somov.comparison: {', '.join(missing)})")
    rows = [Result("constant", "r0 (saturation inactive)", Status.EXACT, {"value": float(reg.r0), "exact": str(reg.r0)},
                   f"g(r) = {sympy.sstr(g)} has the single positive root r0 = {float(reg.r0):.6g}: on ‖V‖ ≤ r0 the "
                   f"bound on ‖p‖ is 0, i.e. ‖D(v − a)‖₂ ≤ a_m and SC is inactive (the root exact; the bound on ‖p‖ "
                   f"is the checked norm chain of somov.comparison)"),
            Result("region", "rho* (comparison system)", Status.EXACT if ok else Status.FAILED,
                   {"value": float(reg.rho) if reg.rho is not None else None, "exact": str(reg.rho)},
                   f"ψ(r) = −αr + (3/β)g(r) = {sympy.sstr(sympy.expand(psi))}: ψ(r0) = −αr0 < 0 and its first root "
                   f"above r0 is ρ* = {float(reg.rho):.6g} (ψ(r0) = −αr0 since g(r0) = 0; every real root of ψ isolated exactly): "
                   f"φ < 0 on (0, ρ*) (exact)")]
    smax, wmax = reg.s_max, reg.w_max
    status = Status.EXACT if ok and not missing else (Status.FAILED if comp is Status.FAILED or not ok else Status.UNDECIDED)
    rows.append(init)
    rows.append(Result("region", "initial data in the region", status,
                       {"s_max": float(smax), "Phi_max_deg": float(4 * sympy.atan(smax) * 180 / sympy.pi),
                        "w_max": float(wmax), "Q": [str(x) for x in reg.Q], "not_proved": missing},
                       f"attracted if Q₁₁s² + 2|Q₁₂|s·y + Q₂₂y² < ρ*², s = |σ(t0)|, y = ¼(1+s²)‖ω(t0)‖, "
                       f"(Q₁₁, |Q₁₂|, Q₂₂) = ({', '.join(sympy.sstr(x) for x in reg.Q)}): at ω0 = 0 |σ0| < "
                       f"{float(smax):.4g} (Φ0 < {float(4 * sympy.atan(smax) * 180 / sympy.pi):.3g}°), at σ0 = 0 "
                       f"‖ω0‖ < {float(wmax):.4g} rad/s (a_m = {v['a_m']}); ρ* exact and {rests}: "
                       f"{'the region is exact' if status is Status.EXACT else 'the region is not established'}"))
    return rows


#: the sampled rectangle of ‖ω0‖, in multiples of the certified ‖ω0‖ bound at σ0 = 0
W_RANGE = 10.0
#: points on the certified boundary (just inside it) simulated as well
N_BOUNDARY = 16


class RegionConstants:
    """``lkverify constants somov.region``: the region against a simulated grid (goals, run, plot)."""

    goals = ["default"]

    def __init__(self, n_s=15, n_w=15, t_end=300.0, rtol=RTOL, atol=ATOL, n_boundary=N_BOUNDARY):
        self.n_s, self.n_w, self.t_end, self.n_boundary = n_s, n_w, t_end, n_boundary
        self.rtol, self.atol = rtol, atol

    def run(self, item_name, values, shown, *, budget=150.0, progress=None, goal=None):
        rows = _region_rows(values)
        reg = certified_region(values)
        s = np.linspace(0.0, 1.0, self.n_s)
        w = np.linspace(0.0, W_RANGE * float(reg.w_max), self.n_w)
        if progress:
            progress(f"{item_name}: {self.n_s}×{self.n_w} initial states × 4 directions to t = {self.t_end:g}")
        grid = run_grid(values, s, w, t_end=self.t_end, rtol=self.rtol, atol=self.atol)
        rows += grid_rows(reg, grid)
        sb = np.linspace(0.0, 0.999 * float(reg.s_max), self.n_boundary)
        wb = 0.999 * reg.w_boundary(sb)
        cls = run_points(values, sb, wb, t_end=self.t_end, rtol=self.rtol, atol=self.atol)
        rows.append(boundary_row(cls, float(reg.s_max), self.t_end))
        bad = [r.name for r in rows if not r.status.holds]
        verdict = "every check holds" if not bad else f"failed: {', '.join(bad)}"
        return Report(item_name, dict(shown), tuple(rows), verdict), {"grid": grid, "region": reg, "values": values,
                                                                     "boundary": (sb, wb)}

    def plot(self, extra, path, *, values=None):
        from matplotlib.figure import Figure

        grid, reg = extra["grid"], extra["region"]
        fig = Figure(figsize=(7.5, 5.0), layout="constrained")
        ax = fig.subplots()
        S, Wg = np.meshgrid(grid.s, grid.w, indexing="ij")
        ax.scatter(S[grid.converged], Wg[grid.converged], s=14, c="tab:green", label="converged (all 4 directions)")
        ax.scatter(S[~grid.converged], Wg[~grid.converged], s=18, marker="x", c="tab:red", label="not converged")
        ss = np.linspace(0, float(reg.s_max), 400)
        ax.fill_between(ss, 0, reg.w_boundary(ss), color="tab:blue", alpha=0.35, label="region (comparison system, checked steps)")
        ax.set_xlabel(r"$|\sigma(t_0)|$")
        ax.set_ylabel(r"$\|\omega(t_0)\|$ (rad/s)")
        v = extra["values"]
        ax.set_title(f"Paper 003: region of attraction of (3), (11); α = {v['alpha']}, β = {v['beta']}, "
                     f"a_m = {v['a_m']}; runs to t = {grid.t_end:g}", fontsize=9)
        b = extra.get("boundary")
        if b is not None:
            ax.plot(b[0], b[1], ".", ms=4, c="navy", label="simulated on the region's boundary")
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
        ax.grid(alpha=0.3)
        from lkverify.report.files import save_figure

        save_figure(fig, path, dpi=120)


_trapezoid = getattr(np, "trapezoid", None) or getattr(np, "trapz")


def _simulated_status(classes) -> Status:
    """failed if a run did not converge, undecided if one ran out of steps, else simulated."""
    if (classes == NOT_CONVERGED).any():
        return Status.FAILED
    return Status.SIMULATED if (classes == CONVERGED).all() else Status.UNDECIDED


def _runs_text(grid) -> str:
    return (f"{grid.directions} direction pairs each, DOPRI5 rtol = {grid.rtol:g}, atol = {grid.atol:g} "
            f"to t = {grid.t_end:g}")


def grid_rows(reg, grid) -> list:
    """Containment of the certified set in the converged grid points, and the area ratio."""
    S, Wg = np.meshgrid(grid.s, grid.w, indexing="ij")
    inside = reg.contains(S, Wg)
    missed = inside & (grid.classes == NOT_CONVERGED)
    open_ = inside & grid.undecided
    ds, dw = grid.s[1] - grid.s[0], grid.w[1] - grid.w[0]
    fine_s = np.linspace(0, grid.s[-1], 801)
    cert_area = float(_trapezoid(np.minimum(reg.w_boundary(fine_s), grid.w[-1]), fine_s))
    ws, ww = np.full(grid.s.size, ds), np.full(grid.w.size, dw)  # trapezoid weights: half cells at the edges
    ws[[0, -1]] /= 2
    ww[[0, -1]] /= 2
    sim_area = float(np.sum(grid.converged * np.outer(ws, ww)))
    total = float(grid.s[-1] * grid.w[-1])
    ratio = cert_area / sim_area if sim_area else float("nan")
    status = _simulated_status(grid.classes[inside])
    detail = {Status.SIMULATED: f"{int(inside.sum())} of the {inside.size} grid points lie in the region and every "
                                f"one of them converged ({_runs_text(grid)})",
              Status.FAILED: f"{int(missed.sum())} grid points in the region did NOT converge ({_runs_text(grid)})",
              Status.UNDECIDED: f"{int(open_.sum())} grid points in the region ran out of steps before t = "
                                f"{grid.t_end:g}, none failed ({_runs_text(grid)})"}[status]
    rows = [Result("simulation", "region inside the converged grid", status,
                   {"grid_points_certified": int(inside.sum()), "missed": int(missed.sum()),
                    "undecided": int(open_.sum()), "rtol": grid.rtol, "atol": grid.atol}, detail),
            Result("simulation", "area ratio region/converged", Status.ESTIMATED,
                   {"ratio": ratio, "certified_area": cert_area, "converged_area": sim_area, "rectangle": total,
                    "converged_fraction": float(grid.converged.mean()), "undecided_points": int(grid.undecided.sum())},
                   f"in |σ0| ∈ [0, 1], ‖ω0‖ ∈ [0, {grid.w[-1]:.3g}]: region area {cert_area:.3g}, converged "
                   f"{sim_area:.3g} ({100 * grid.converged.mean():.0f} % of the grid points): ratio {ratio:.3g}")]
    return rows


def boundary_row(classes, s_max: float, t_end: float) -> Result:
    """The runs from just inside the region's boundary (classes of :func:`.grid.run_points`) must converge."""
    n = int(classes.size)
    conv, failed = int((classes == CONVERGED).sum()), int((classes == NOT_CONVERGED).sum())
    return Result("simulation", "region boundary converges", _simulated_status(classes),
                  {"points": n, "not_converged": n - conv, "failed": failed},
                  f"{conv} of {n} initial data just inside the region's boundary (|σ0| from 0 to "
                  f"{0.999 * s_max:.3g}, 4 direction pairs each) converge by t = {t_end:g}"
                  f"{f', {failed} do not' if failed else ''}{f', {n - conv - failed} ran out of steps' if n - conv - failed else ''}")


def _hypotheses(v) -> list:
    return [Result("hypothesis", f"{name} > 0", Status.EXACT if sympy.sympify(v[name]) > 0 else Status.FAILED,
                   str(v[name]), f"{name} = {v[name]}") for name in ("alpha", "beta", "a_m")]


def _derivations(v) -> list:
    return majorant_steps(v) + _region_rows(v)


def argument(v):
    """The links after the comparison system: the comparison lemma on (0, ρ*), the initial data, the limits (5)."""
    from lkverify.certify.steps import Comparison, Follows

    steps = majorant_steps(v)
    comp, missing = chain_status(steps)
    by_name = {x.name: x.status for x in steps}
    r, g, psi = majorant(v)
    reg = certified_region(v)
    phi_r = -sympy.sympify(v["alpha"]) * r + 3 * sympy.Max(0, g) / sympy.sympify(v["beta"])
    rows = {x.name: x for x in _region_rows(v)}
    init = rows["initial data in the region"]
    limits = [(n, by_name.get(n, Status.UNDECIDED)) for n in
              ("|sigma| <= ||V||", "|sigmadot| <= sqrt(k0) ||V||", "|D sigmadot|^2 = 16|sigmadot|^2/(1+|sigma|^2)^2")]
    links = [
        Comparison(phi_r, r, reg.rho, rests_on=(("D⁺‖V‖ ≤ φ(‖V‖) (the checked majorant steps)", comp),),
                   name="comparison lemma: ‖V‖ < ρ* invariant, ‖V‖ → 0"),
        Follows("initial data in the region ⇒ ‖V(t0)‖ < ρ*", ((init.name, init.status),),
                "Q₁₁s² + 2|Q₁₂|s·y + Q₂₂y² < ρ*² bounds ‖V(t0)‖² (the initial-data step)"),
        Follows("limits (5): σ → 0, σ̇ → 0, ω → 0", (*limits, ("‖V‖", None)),
                "|σ| ≤ ‖V‖, |σ̇| ≤ √k0‖V‖ and ‖ω‖ = 4|σ̇|/(1 + σ²) ≤ 4|σ̇| squeeze them with ‖V‖ → 0"),
    ]
    return links, {}


region = SignalTheorem(
    "region", system=closed_loop, hypotheses=[_hypotheses], derivations=[_derivations], argument=argument,
    paper=PAPER, relevant=("alpha", "beta", "a_m"), constants=RegionConstants(),
    derivations_link="comparison system D⁺‖V‖ ≤ φ(‖V‖): identities and norm steps; r0, ρ*, initial data",
    conclusion="every initial state with Q₁₁s² + 2|Q₁₂|s·y + Q₂₂y² < ρ*² is attracted: σ, σ̇, ω → 0",
    title="Region of attraction of (3), (11) from the comparison system: the comparison lemma on (0, ρ*) "
          "(exact), against a simulated grid")
