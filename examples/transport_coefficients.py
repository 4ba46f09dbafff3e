"""Transport coefficients of the hard-disk fluid from equilibrium, beside Enskog's theory.

Physics: an elastic gas left alone in a periodic box carries its transport
coefficients in the fluctuations of its fluxes.  ``edmd2d.transport`` sums the
Einstein-Helfand moments of the momentum and energy fluxes exactly over every flight
and collision, and the mean squares of their increments grow at rates given by the
shear viscosity ``eta`` and the thermal conductivity ``lambda``; the mean squared
displacement gives the self-diffusion coefficient ``D``.  Left panel: each
coefficient over Enskog's theory (with the converged Chapman-Enskog values of the
dilute gas) against the packing fraction, at ``N`` disks: the viscosity and the
conductivity follow it within a few per cent, while ``D`` exceeds it more and more
with density (correlated collisions: a disk's momentum comes back to it through the
vortex it sets up).  Middle panel: that vortex is the long-time tail, ``<v_x(0)
v_x(t)> ~ A / t`` with mode coupling's ``A = kT / (8 pi m n (D + nu))``: ``t C(t) /
A`` at packing 0.3 in a box of ``4 N`` disks settles near 1.  Right panel: the tail
makes ``D`` grow with the size of a periodic box, ``dD / d ln N = A`` at a fixed
density (each window several times the time the box's longest wave takes to relax).

The default run, the one ``docs/transport.md`` reports (``N = 400``, ``--duration
32000`` of simulated time at packing 0.3 and as many windows at the others), takes
about half an hour; ``--n 200 --duration 3200`` draws the figure in under a minute.
Writes a figure and prints the tables::

    python examples/transport_coefficients.py [examples/output/transport_coefficients.png]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import theory  # noqa: E402
from edmd2d.transport import transport  # noqa: E402

N, DURATION, SEED = 400, 32000.0, 11
# Packing fractions and their windows: several relaxation times of the slowest flux
# (the heat flux of the dilute gas: lambda / (2 n kT)).
WINDOWS = {0.1: 40.0, 0.2: 20.0, 0.3: 16.0, 0.4: 12.0, 0.5: 10.0}
TAIL_WINDOW = 40.0


def measure(n: int, phi: float, window: float, duration: float, seed: int):
    """The coefficients of ``n`` disks at ``phi``, equilibrated for 20, sampled 40 times
    a window, over ``duration`` rounded to whole windows (at least 12)."""
    sim = ed.make_gas(n, phi, seed=seed)
    sim.advance(until=20.0)
    windows = max(12, round(duration / window))
    return transport(sim, windows * window, dt=window / 40, window=window, blocks=10)


def main(out: Path) -> None:
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig, (left, middle, right) = plt.subplots(1, 3, figsize=(15, 4.2))
    scale = DURATION / WINDOWS[0.3]  # (windows per run)

    print(f"{N} disks; each run {scale:g} windows long; over Enskog's theory:")
    print("packing  window   eta/eta_E        lambda/lambda_E   D/D_E")
    rows = []
    for phi, window in WINDOWS.items():
        c = measure(N, phi, window, scale * window, SEED)
        ratios = [(c.shear_viscosity / theory.enskog_viscosity(phi),
                   c.shear_viscosity_error / theory.enskog_viscosity(phi)),
                  (c.thermal_conductivity / theory.enskog_thermal_conductivity(phi),
                   c.thermal_conductivity_error / theory.enskog_thermal_conductivity(phi)),
                  (c.diffusion[0] / theory.enskog_diffusion(phi),
                   c.diffusion_error[0] / theory.enskog_diffusion(phi))]
        rows.append(ratios)
        print(f"  {phi:4.2f}   {window:5.1f}   " + "   ".join(
            f"{v:.3f} +- {e:.3f}" for v, e in ratios))
    phis = list(WINDOWS)
    for k, label in enumerate(("viscosity", "conductivity", "self-diffusion")):
        left.errorbar(phis, [r[k][0] for r in rows], yerr=[r[k][1] for r in rows],
                      fmt="o-", ms=4, label=label)
    left.axhline(1.0, color="k", lw=1)
    left.set_xlabel("packing fraction")
    left.set_ylabel("measured / Enskog")
    left.set_title(f"{N} disks")
    left.legend()

    phi, big = 0.3, 4 * N
    c = measure(big, phi, TAIL_WINDOW, scale * TAIL_WINDOW / 4, SEED)
    amplitude = theory.long_time_tail(theory.enskog_viscosity(phi), c.diffusion[0],
                                      c.density)
    t = c.vacf_times[1:]
    middle.errorbar(t, t * c.vacf[1:, 0] / amplitude, yerr=t * c.vacf_error[1:, 0] / amplitude,
                    fmt=".", ms=3, label="t C(t) / A")
    middle.axhline(1.0, color="k", lw=1, label="mode coupling")
    middle.set_ylim(0.0, 3.0)
    middle.set_xlabel("time t")
    middle.set_ylabel("t C(t) / A")
    middle.set_title(f"the long-time tail ({big} disks, packing {phi})")
    middle.legend()
    print(f"tail at packing {phi}, {big} disks: A = {amplitude:.4f}; t C(t) / A at t = "
          + ", ".join(f"{t[k]:g}: {t[k] * c.vacf[k + 1, 0] / amplitude:.2f}"
                      for k in range(7, len(t), len(t) // 5)))

    sizes = [max(N // 4, 16), N, 4 * N]
    d, err = [], []
    for n in sizes:
        # (Four times the relaxation time of the box's longest wave, L^2 / (4 pi^2 (D +
        # nu)) ~ n / 50 at packing 0.3; twenty windows at least.)
        window = max(20.0, 0.125 * n)
        c = measure(n, phi, window, max(20.0, scale / 40) * window, SEED + n)
        d.append(c.diffusion[0])
        err.append(c.diffusion_error[0])
    x = np.log(sizes)
    slope = float(np.polyfit(x, d, 1)[0])
    amplitude = theory.long_time_tail(theory.enskog_viscosity(phi), d[-1],
                                      theory.number_density(phi))
    right.errorbar(sizes, d, yerr=err, fmt="o", ms=5, label="measured")
    grid = np.geomspace(sizes[0], sizes[-1], 20)
    right.plot(grid, d[1] + amplitude * np.log(grid / sizes[1]), "k-", lw=1,
               label="slope A (mode coupling)")
    right.set_xscale("log")
    right.set_xticks(sizes, [str(n) for n in sizes])
    right.minorticks_off()
    right.set_xlabel("number of disks N")
    right.set_ylabel("self-diffusion D")
    right.set_title(f"the size of the box (packing {phi})")
    right.legend()
    print(f"D against N at packing {phi}: " + ", ".join(
        f"{n}: {v:.4f} +- {e:.4f}" for n, v, e in zip(sizes, d, err))
        + f"; dD/d ln N = {slope:.4f}, mode coupling {amplitude:.4f}")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "transport_coefficients.png")
