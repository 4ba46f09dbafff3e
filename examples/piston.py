"""A gas compressed by a piston: slowly, along the hard-disk adiabat; fast, hotter.

Physics: ``N`` elastic disks in a box periodic along x, between the floor and a wall
segment across the box that comes down at a constant speed (``ed.Translation``) until
the free area (the centres' room) is an eighth of its start.  Hard disks have no
potential energy, so all the piston's work (``sim.wall_work()``) goes into the
kinetic energy.  Compressed slowly, the gas follows its adiabat, ``d ln T / d ln eta =
Z(eta)`` (``theory.adiabatic_temperature``, with Kolafa and Rottner's equation of
state): hotter than an ideal gas's ``T A = const`` as the disks crowd (a little
below the bulk adiabat when dense: the walls' share of a small box, which halves when
the box's side doubles; see docs/moving-walls.md).  A piston as
fast as the disks' thermal speed leaves a hot layer behind it and does more work than
the adiabat's: the gas ends hotter.

Writes a figure: the slow run's gas at the end, under the piston; the temperature
against the compression for both runs, with the two adiabats::

    python examples/piston.py [examples/output/piston.png]
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import theory, viz  # noqa: E402

SEED = 1
N = 400
R = 0.5
ETA_START = 0.05
RATIO = 8.0  # free area at the start over free area at the end
SPEEDS = (0.01, 1.0)  # slow (1 % of the thermal speed) and fast
SAMPLES = 40


def compress(speed: float) -> tuple[ed.Simulation, np.ndarray, np.ndarray]:
    """Run the compression at ``speed``: the simulation at the end, and the packing
    fraction of the free area and the temperature at ``SAMPLES + 1`` times."""
    width = math.sqrt(N * math.pi * R * R / ETA_START)
    h0 = width + 2 * R
    h1 = (h0 - 2 * R) / RATIO + 2 * R
    gas = ed.random_gas(N, ETA_START, seed=SEED)  # (square and periodic: rescaled)
    pos = gas.positions * (width / gas.box.width) + [0.0, R]
    sim = ed.Simulation(pos, gas.velocities, R,
                        box=ed.Box(width, h0 + 1.0, periodic=(True, False)),
                        walls=[ed.Wall((0.0, h0), (width, h0))],
                        wall_motions={0: ed.Translation((0.0, -speed), h0 - h1)})
    times = np.linspace(0.0, (h0 - h1) / speed, SAMPLES + 1)
    eta, temperature = [], []
    for t in times:
        sim.advance(until=float(t))
        top = sim.wall_positions[0, 0, 1]
        eta.append(N * math.pi * R * R / (width * (top - 2 * R)))
        temperature.append(sim.kinetic_energy() / N)
    return sim, np.array(eta), np.array(temperature)


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    runs = {speed: compress(speed) for speed in SPEEDS}
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 5),
                                      gridspec_kw={"width_ratios": [1, 1.3]})
    slow = runs[SPEEDS[0]][0]
    viz.draw(slow, left, color_by="speed")
    left.set_title(f"after the slow compression (t = {slow.time:.0f})")
    eta0 = runs[SPEEDS[0]][1][0]
    grid = np.linspace(eta0, runs[SPEEDS[0]][1][-1], 60)
    right.plot(grid / eta0, [theory.adiabatic_temperature(eta0, e) for e in grid], "-",
               color="0.3", label="hard-disk adiabat")
    right.plot(grid / eta0, grid / eta0, "--", color="0.6", label="ideal gas, T A = const")
    for (speed, (sim, eta, temperature)), marker in zip(runs.items(), "os"):
        rise = temperature / temperature[0]
        expected = theory.adiabatic_temperature(eta[0], eta[-1])
        print(f"piston at {speed:g}: T rises {rise[-1]:.3f} times (adiabat "
              f"{expected:.3f}, ideal gas {eta[-1] / eta[0]:.3f}); work "
              f"{sim.wall_work()[0]:.2f}, kinetic energy gained "
              f"{sim.kinetic_energy() - temperature[0] * N:.2f}")
        right.plot(eta / eta[0], rise, marker, ms=4, label=f"piston at {speed:g}")
    right.set_xscale("log")
    right.set_yscale("log")
    for axis in (right.xaxis, right.yaxis):
        axis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    right.set_xlabel(r"compression $\eta / \eta_0$")
    right.set_ylabel(r"$T / T_0$")
    right.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "piston.png")
