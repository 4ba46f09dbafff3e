"""Relaxation of a hard-disk gas from equal speeds to the Maxwell-Boltzmann distribution.

Physics: 2000 disks in a periodic box start with one and the same speed (random, pairwise
opposite directions, so the total momentum is zero).  Elastic collisions conserve the
energy exactly but share it out unevenly, and within a few collisions per disk the
speeds follow the 2D Maxwell-Boltzmann law ``f(v) = (m v / kT) exp(-m v^2 / 2kT)``.  The
moment ratio ``<v^4> / <v^2>^2`` goes from 1 (equal speeds) to 2 (2D Maxwellian), and a
Kolmogorov-Smirnov test of the energies ``m v^2 / 2kT`` against the unit exponential
stops rejecting.

    python examples/maxwell_boltzmann.py [examples/output/maxwell_boltzmann.png]
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import theory  # noqa: E402

N, PACKING, SEED = 2000, 0.25, 3
SNAPSHOTS = (0.0, 1.0, 2.0, 5.0, 10.0)  # collisions per disk


def equal_speeds(sim, rng):
    n = len(sim)
    angle = rng.uniform(0.0, 2 * math.pi, n // 2)
    half = np.column_stack([np.cos(angle), np.sin(angle)])
    vel = np.empty((n, 2))
    vel[0::2], vel[1::2] = half, -half
    # Same kinetic energy as kT = 1 with 2N - 2 degrees of freedom.
    sim.set_velocities(vel * math.sqrt((2 * n - 2) / n))


def moment_ratio(vel):
    v2 = np.einsum("ij,ij->i", vel, vel)
    return float(np.mean(v2**2) / np.mean(v2) ** 2)


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(SEED)
    sim = ed.make_gas(N, PACKING, seed=SEED)
    equal_speeds(sim, rng)
    kt = ed.kinetic_temperature(sim)

    fig, (ax_hist, ax_ratio) = plt.subplots(1, 2, figsize=(10.0, 4.2))
    v = np.linspace(0, 4, 300)
    ax_hist.plot(v, theory.maxwell_boltzmann_speed_pdf(v, kt), "k-", lw=2,
                 label="2D Maxwell-Boltzmann")
    times, ratios = [], []
    for k, per_disk in enumerate(SNAPSHOTS):
        target = int(per_disk * N / 2)  # each collision involves two disks
        if target > sim.counts.collisions:
            sim.advance(collisions=target - sim.counts.collisions)
        vc, f = ed.speed_distribution(sim, bins=40, v_max=4.0)
        p = ed.maxwell_boltzmann_test(sim).pvalue
        ax_hist.step(vc, f, where="mid", color=f"C{k}",
                     label=f"{per_disk:g} coll./disk, KS p={p:.1e}")
        print(f"{per_disk:4g} collisions per disk: <v^4>/<v^2>^2 = "
              f"{moment_ratio(sim.velocities):.3f}, KS p-value {p:.3g}")
    sim2 = ed.make_gas(N, PACKING, seed=SEED)
    equal_speeds(sim2, np.random.default_rng(SEED))
    for _ in range(151):  # 0 ... 15 collisions per disk
        times.append(sim2.counts.collisions * 2 / N)
        ratios.append(moment_ratio(sim2.velocities))
        sim2.advance(collisions=N // 20)
    ax_hist.set_xlabel("speed v")
    ax_hist.set_ylabel("probability density")
    ax_hist.set_ylim(0, 2.5)
    ax_hist.legend(fontsize=7)
    ax_ratio.plot(times, ratios, "o-", ms=3)
    ax_ratio.axhline(2.0, color="k", ls="--", label="Maxwell-Boltzmann (2D): 2")
    ax_ratio.axhline(1.0, color="gray", ls=":", label="equal speeds: 1")
    ax_ratio.set_xlabel("collisions per disk")
    ax_ratio.set_ylabel(r"$\langle v^4\rangle / \langle v^2\rangle^2$")
    ax_ratio.legend(fontsize=8)
    fig.suptitle(f"{N} hard disks, packing fraction {PACKING}: relaxation to equilibrium")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "maxwell_boltzmann.png")
