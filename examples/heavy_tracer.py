"""A heavy tracer, twenty times wider than the disks of its bath.

Physics: one disk of radius 10 (mass 400: the bath's areal density) in a periodic
bath of 2 x 10^4 disks of radius 0.5 at packing fraction 0.3 and kT = 1.  It is hit
from every side along its long rim, some 50 times per unit time, and wanders: the
script prints its mean kinetic energy beside equipartition's ``M <V^2> / 2 = kT (1 -
M / M_all)`` (2D, the total momentum fixed), with an error from ten blocks of the
run, and draws its mean squared displacement, which turns from ballistic (``2 kT t^2
/ M``) to diffusive (``4 D t``).

Such a tracer used to slow every disk of the bath: the grid's cells held the largest
disk, so every small disk scanned cells twenty diameters wide.  The wide grid (the
default, ``grid="auto"``) lists the tracer in the small cells near it instead; the
script times a stretch of the run on both grids and prints the two speeds.

Writes a figure: the tracer's path over the bath, and its mean squared displacement
against time with the ballistic line::

    python examples/heavy_tracer.py [examples/output/heavy_tracer.png]
"""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

SEED = 1
N = 20_000  # disks in all, the tracer first
PACKING = 0.3
R_TRACER, R_BATH = 10.0, 0.5
KT = 1.0
EQUILIBRATE = 20.0
DURATION = 2000.0  # of the sampled run
SAMPLE = 0.5  # time between samples of the tracer
BLOCKS = 10
TIMED = 20  # collisions per disk timed on each grid


def build(grid: str = "auto") -> ed.Simulation:
    """The bath and the tracer (disk 0, mass by area), from a disordered start."""
    radii = np.full(N, R_BATH)
    radii[0] = R_TRACER
    masses = (radii / R_BATH) ** 2
    gas = ed.random_gas(N, PACKING, radii=radii, masses=masses, temperature=KT, seed=SEED)
    if grid == "auto":
        return gas
    return ed.Simulation(gas.positions, gas.velocities, gas.radii, gas.masses,
                         box=gas.box, grid=grid)


def speeds() -> dict[str, float]:
    """Collisions per second of ``TIMED`` collisions per disk on each grid."""
    out = {}
    for grid in ("auto", "uniform"):
        sim = build(grid)
        sim.advance(collisions=N)  # (compiled, the start relaxed)
        start = time.process_time()
        sim.advance(collisions=TIMED * N)
        out[grid] = TIMED * N / (time.process_time() - start)
    return out


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    mass = float(sim.masses[0])
    sim.advance(until=EQUILIBRATE)
    times = sim.time + SAMPLE * np.arange(int(round(DURATION / SAMPLE)) + 1)
    path = np.empty((len(times), 2))
    speed2 = np.empty(len(times))
    for k, t in enumerate(times):
        sim.advance(until=float(t))
        path[k] = sim.unwrapped_positions[0]
        speed2[k] = float(np.sum(sim.velocities[0] ** 2))
    blocks = np.array_split(0.5 * mass * speed2, BLOCKS)
    energy = float(np.mean(0.5 * mass * speed2))
    error = float(np.std([b.mean() for b in blocks], ddof=1) / np.sqrt(BLOCKS))
    # (The total momentum is held at zero, so the tracer shares the bath's: each of its
    # velocity components has the variance kT (1 - M / M_all) / M.)
    expected = KT * (1.0 - mass / float(sim.masses.sum()))
    print(f"tracer: M <V^2> / 2 = {energy:.3f} +- {error:.3f} (equipartition with the "
          f"total momentum fixed: kT (1 - M / M_all) = {expected:.3f})")
    lags = np.unique(np.round(np.geomspace(1, len(times) // 4, 30)).astype(int))
    msd = np.array([np.mean(np.sum((path[lag:] - path[:-lag]) ** 2, axis=1))
                    for lag in lags])
    tau = lags * SAMPLE
    late = tau >= tau[-1] / 4
    diffusion = float(np.polyfit(tau[late], msd[late], 1)[0] / 4.0)
    print(f"tracer: diffusion coefficient {diffusion:.4g} (slope of the mean squared "
          f"displacement over the last three quarters of its lags)")
    rates = speeds()
    print(f"speed: {rates['auto'] / 1e6:.3f} M collisions/s on the wide grid, "
          f"{rates['uniform'] / 1e6:.3f} M on the uniform grid "
          f"({rates['auto'] / rates['uniform']:.1f} times faster)")

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 5))
    viz.draw(sim, left, color_by=None, color="0.8", linewidth=0.0)
    wrapped = path - sim.box.size * np.floor(path / sim.box.size)
    jumps = np.flatnonzero(np.any(np.abs(np.diff(wrapped, axis=0)) > 0.5 * sim.box.size,
                                  axis=1)) + 1
    for piece in np.split(wrapped, jumps):
        left.plot(piece[:, 0], piece[:, 1], color="C3", lw=1.2)
    left.set_title(f"the tracer's path over t = {DURATION:g}")
    right.loglog(tau, msd, "o", ms=4, label="measured")
    right.loglog(tau, 2.0 * KT / mass * tau ** 2, "--", color="0.4",
                 label=r"ballistic $2kT t^2/M$")
    right.loglog(tau, 4.0 * diffusion * tau, ":", color="C1",
                 label=f"diffusive $4Dt$, D = {diffusion:.3g}")
    right.set_xlabel("time")
    right.set_ylabel("mean squared displacement")
    right.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", nargs="?", type=Path,
                        default=Path(__file__).parent / "output" / "heavy_tracer.png")
    parser.add_argument("--n", type=int, default=N, help="disks in all")
    parser.add_argument("--duration", type=float, default=DURATION,
                        help="length of the sampled run")
    args = parser.parse_args()
    N, DURATION = args.n, args.duration
    main(args.out)
