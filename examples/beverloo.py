"""Beverloo's law: a silo's discharge rate against the width of its outlet.

Physics: the silo of ``examples/silo.py`` (inelastic disks, e = 0.9, under gravity,
its outflow re-entering at the top through the periodic vertical axis), ``WIDTH``
diameters wide, discharging through outlets of the widths ``OUTLETS`` with the fill
heights that ``N``, ``3N/2`` and ``2N`` disks give.  In two dimensions Beverloo's law says that the
number of disks leaving per unit time is ``W = C sqrt(g / d) ((D - k d) / d)^(3/2)``
(Beverloo, Leniger and van de Velde, Chem. Eng. Sci. 15, 260 (1961), in its 2D form):
the disks fall freely through an arch of size ~ D above the outlet, so their speed is
~ sqrt(g D) and the flux through a width D goes as D^(3/2); ``k d`` is the empty
annulus at the outlet's edges; and the rate does not depend on the fill height (the
walls carry the weight above, Janssen).  Each silo runs with its gate open from the
start; after ``TRANSIENT`` its rate is measured over ``DURATION`` in 10 blocks
(:func:`edmd2d.measurements.discharge`).

The fit: each width's rate is the mean over the three fills, with its error from
their spread; ``W^(2/3)`` is then linear in ``D`` (weighted least squares), which gives
``C`` and ``k`` with their errors, and the chi^2 and residuals say how well the law
holds.  With more than three widths the exponent is fitted too, ``W = C (D - k)^b``
with ``C``, ``k`` and ``b`` together (their errors, and the correlation of ``k`` and
``b``, which is strong: a larger shift mimics a smaller exponent).  A silo that jams
(an arch holds over its outlet, and the flow stops) is reported and left out.

Writes a figure of ``W^(2/3)`` against ``D`` with the fit (``.png`` or ``.svg``), and
prints the table of rates and the fitted constants::

    python examples/beverloo.py [--n 500] [--duration 200] [examples/output/beverloo.png]

(15 silos of 500 to 1000 disks: some 30 minutes on one core, run ``PROCESSES`` at a
time.)
"""

from __future__ import annotations

import math
import sys
from multiprocessing import Pool
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import silo  # noqa: E402  (examples/silo.py: the silo)

from edmd2d import measurements  # noqa: E402

WIDTH, FLOOR, HEADROOM = 36.0, 4.0, 6.0  # the box: the outlet's height, room above
OUTLETS = (3.5, 5.0, 6.5, 8.5, 11.0)  # a factor 3.1; an outlet of 2.5 jams
N = 600  # the fills: N, 3N/2 and 2N disks
TRANSIENT, DURATION, PROCESSES, SEED = 40.0, 200.0, 2, 1


def discharge(case: tuple[float, int]) -> dict:
    """The discharge of one silo (outlet ``D``, ``n`` disks): its rate, error, block
    rates and the fill height (the 95th percentile of the heights in the silo)."""
    outlet, n = case
    # The box just taller than the start's lattice (silo.build's rows 1.05 apart):
    # disks falling back in land on the bed soon, so that few are in flight.
    rows = math.ceil(n / len(np.arange(0.55, WIDTH - 0.54, 1.05)))
    silo.WIDTH, silo.FLOOR, silo.OUTLET = WIDTH, FLOOR, outlet
    silo.HEIGHT = FLOOR + 1.05 * rows + HEADROOM
    silo.N, silo.SEED = n, SEED
    sim = silo.build()
    sim.open_wall(2)
    sim.advance(until=TRANSIENT)
    flow = measurements.discharge(sim, DURATION, blocks=10)
    # The bed: the slow disks in the silo (those falling back onto it are fast).
    speed = np.hypot(*sim.velocities.T)
    bed = (sim.positions[:, 1] > FLOOR) & (speed < 1.0)
    return dict(outlet=outlet, n=n, rate=flow.rate, error=flow.error,
                blocks=flow.block_rates.tolist(),
                fill=float(np.percentile(sim.positions[bed, 1], 95)) - FLOOR,
                jammed=bool(flow.block_rates[-1] == 0.0))


def fit(outlets: np.ndarray, rates: np.ndarray, errors: np.ndarray) -> dict:
    """Beverloo's constants ``C``, ``k`` (with errors) from the weighted straight line
    ``W^(2/3) = C^(2/3) (D - k)`` through the rates ``W`` (errors ``errors``) at the
    widths ``outlets``, its chi^2, and each width's residual in units of its error."""
    y = rates ** (2.0 / 3.0)
    sigma = (2.0 / 3.0) * rates ** (-1.0 / 3.0) * errors
    (slope, intercept), cov = np.polyfit(outlets, y, 1, w=1.0 / sigma, cov="unscaled")
    k = -intercept / slope
    # (k's error by propagation through -intercept / slope, with their covariance)
    grad = np.array([intercept / slope ** 2, -1.0 / slope])
    k_err = float(np.sqrt(grad @ cov @ grad))
    c, c_err = slope ** 1.5, 1.5 * slope ** 0.5 * math.sqrt(cov[0, 0])
    residuals = (y - (slope * outlets + intercept)) / sigma
    return dict(c=float(c), c_err=float(c_err), k=float(k), k_err=k_err,
                chi2=float(np.sum(residuals ** 2)), dof=len(outlets) - 2,
                residuals=residuals.tolist(), slope=float(slope), intercept=float(intercept))


def fit_exponent(outlets: np.ndarray, rates: np.ndarray, errors: np.ndarray,
                 start: dict) -> dict:
    """Beverloo's law with its exponent free, ``W = C (D - k)^b``: ``C``, ``k`` and ``b``
    fitted together (weighted least squares, ``scipy.optimize.curve_fit``, from the
    3/2 fit ``start``), with their errors from the errors of the rates, their
    correlation and chi^2."""
    from scipy.optimize import curve_fit

    def law(d, c, k, b):
        return c * np.maximum(d - k, 1e-12) ** b

    p, cov = curve_fit(law, outlets, rates, p0=[start["c"], start["k"], 1.5],
                       sigma=errors, absolute_sigma=True, maxfev=20_000)
    err = np.sqrt(np.diag(cov))
    corr = cov / np.outer(err, err)
    chi2 = float(np.sum(((rates - law(outlets, *p)) / errors) ** 2))
    return dict(c=float(p[0]), k=float(p[1]), b=float(p[2]), c_err=float(err[0]),
                k_err=float(err[1]), b_err=float(err[2]), corr_kb=float(corr[1, 2]),
                chi2=chi2, dof=len(outlets) - 3)


def main(out: Path) -> dict:
    """Run every silo, fit, plot, print; return the rows and the fit."""
    out.parent.mkdir(parents=True, exist_ok=True)
    fills = (N, 3 * N // 2, 2 * N)
    cases = [(d, n) for d in OUTLETS for n in fills]
    if PROCESSES > 1:
        with Pool(PROCESSES) as pool:
            rows = pool.map(discharge, cases)
    else:
        rows = [discharge(case) for case in cases]
    flowing = [r for r in rows if not r["jammed"]]
    print(f"silo {WIDTH:g} wide, e = {silo.RESTITUTION}, g = {silo.GRAVITY}; rates over "
          f"{DURATION:g} time units after {TRANSIENT:g}, 10 blocks")
    print("  outlet  disks  fill height   rate (disks per unit time)")
    for r in rows:
        state = "  jammed" if r["jammed"] else ""
        print(f"  {r['outlet']:6.1f}  {r['n']:5d}  {r['fill']:11.1f}   {r['rate']:.3f} +- "
              f"{r['error']:.3f}{state}")
    # Each width's rate: the mean over its fills, its error from their spread (the
    # fills as replicas: the law has the rate independent of the fill height, and
    # the spread shows more than the block errors, which miss slow changes of the
    # flow's stagnant zones).
    outlets = np.array(sorted({r["outlet"] for r in flowing}))
    if len(outlets) < 3:
        print("  fewer than three outlets flowed: no fit")
        return dict(rows=rows, fit=None)
    per = [[r["rate"] for r in flowing if r["outlet"] == d] for d in outlets]
    if min(len(p) for p in per) < 2:
        print("  an outlet flowed at one fill only: no error from the spread, no fit")
        return dict(rows=rows, fit=None)
    rates = np.array([np.mean(p) for p in per])
    errors = np.array([np.std(p, ddof=1) / math.sqrt(len(p)) for p in per])
    result = fit(outlets, rates, errors)
    print("  outlet  rate over the fills   residual of the fit (errors)")
    for d, w, e, res in zip(outlets, rates, errors, result["residuals"]):
        print(f"  {d:6.1f}  {w:8.3f} +- {e:.3f}   {res:+.2f}")
    print(f"  Beverloo, exponent 3/2: C = {result['c']:.3f} +- {result['c_err']:.3f}, "
          f"k = {result['k']:.2f} +- {result['k_err']:.2f} (chi^2 = {result['chi2']:.1f} "
          f"for {result['dof']} degrees of freedom)")
    free = None
    if len(outlets) > 3:
        free = fit_exponent(outlets, rates, errors, result)
        print(f"  exponent free: b = {free['b']:.2f} +- {free['b_err']:.2f}, k = "
              f"{free['k']:.2f} +- {free['k_err']:.2f} (correlation of k and b "
              f"{free['corr_kb']:+.2f}), C = {free['c']:.3f} +- {free['c_err']:.3f} "
              f"(chi^2 = {free['chi2']:.1f} for {free['dof']} degrees of freedom)")
    fig, ax = plt.subplots(figsize=(5.0, 3.8))
    for n, marker in zip(fills, "os^"):
        sel = [r for r in flowing if r["n"] == n]
        if not sel:
            continue
        ax.errorbar([r["outlet"] for r in sel], [r["rate"] ** (2 / 3) for r in sel],
                    yerr=[(2 / 3) * r["rate"] ** (-1 / 3) * r["error"] for r in sel],
                    fmt=marker, ms=4, capsize=2,
                    label=f"{n} disks (fill ~{np.mean([r['fill'] for r in sel]):.0f} d)")
    d = np.linspace(result["k"], max(OUTLETS) * 1.05, 50)
    ax.plot(d, result["slope"] * d + result["intercept"], "k-", lw=1,
            label=f"Beverloo: C = {result['c']:.2f}, k = {result['k']:.2f}")
    ax.set_xlabel("outlet width D / d")
    ax.set_ylabel("(discharge rate / sqrt(g/d))^(2/3)")
    ax.set_xlim(0.0, None)
    ax.set_ylim(0.0, None)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
    print(f"wrote {out}")
    return dict(rows=rows, fit=result, free=free)


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "beverloo.png")
