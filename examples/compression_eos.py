"""The equation of state along a slow compression, through freezing to close packing.

Physics: ``N`` equal disks start at random at packing fraction 0.2 in a periodic box of
the triangular lattice's aspect and grow slowly (the Lubachevsky-Stillinger
compression: the mean diameter grows at ``RATE`` times the thermal speed), with the
temperature held at kT = 1, until the reduced pressure ``Z = PA / NkT`` passes 1e6.
Through the fluid the pressure follows the equilibrium equation of state of hard
disks (Henderson's, and the virial series to tenth order, from
:mod:`edmd2d.theory`): the compression is slow enough for the fluid to stay in
equilibrium.  Near 0.70 the disks freeze (the melting of hard disks, from 0.700 to
0.716: Bernard and Krauth, Phys. Rev. Lett. 107, 155704 (2011)); the global
bond-orientational order ``|Psi_6|`` jumps from the fluid's ``~1/sqrt(N)`` towards 1,
and the pressure follows the crystal's branch, which diverges at close packing as
the free-volume law ``Z = 2 / (1 - phi / phi_cp)`` (``phi_cp = 0.9069``).  Each disk's
Voronoi cell measures how closely it is packed: in the final crystal the median disk
is within a part in a thousand of close packing; vacancies and grain boundaries keep
the whole a little below.

Writes a figure (``.png``): ``Z`` against packing fraction (log scale) with the
theories, and ``|Psi_6|`` along the compression; prints Z against the equation of
state in bins of packing fraction, and the final packing::

    python examples/compression_eos.py [examples/output/compression_eos.png] [--n 400]
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import theory  # noqa: E402
from edmd2d.compress import CLOSE_PACKING  # noqa: E402

N, SEED, RATE, START, MAX_PRESSURE = 1024, 2, 1e-3, 0.2, 1e6
STAGES = (0.4, 0.6, 0.65, 0.68, 0.70, 0.72, 0.74, 0.78)  # where psi_6 is measured


def compress():
    """The compression in stages (psi_6 measured at the end of each), then on to
    jamming: ``(stages, record)`` with the packing fraction, Z and temperature of every
    interval of the whole compression."""
    sim = ed.random_gas(N, START, aspect=2.0 / math.sqrt(3.0), seed=SEED)
    stages, parts = [], []
    for target in STAGES:
        step = ed.compress(sim, target, rate=RATE)
        sim = step.simulation
        parts.append(step)
        stages.append((target, abs(ed.hexatic_order(sim)[0])))
    last = ed.compress(sim, rate=RATE, max_pressure=MAX_PRESSURE, progress=True)
    parts.append(last)
    stages.append((last.packing_fraction, abs(ed.hexatic_order(last.simulation)[0])))
    phi = np.concatenate([p.packing_fractions for p in parts])
    z = np.concatenate([p.reduced_pressures for p in parts])
    return stages, phi, z, last


def main(out):
    stages, phi, z, last = compress()
    local = ed.local_packing_fractions(last.simulation)
    print("  phi      Z (compression)    Henderson   virial(10)")
    edges = np.arange(0.2, 0.7001, 0.05)
    for lo, hi in zip(edges[:-1], edges[1:]):
        m = (phi >= lo) & (phi < hi)
        mean = phi[m].mean()
        err = z[m].std(ddof=1) / math.sqrt(m.sum())
        print(f"  {mean:.3f}   {z[m].mean():8.4f} +- {err:.4f}   "
              f"{float(theory.henderson_z(mean)):8.4f}   {float(theory.virial_z(mean)):8.4f}")
    for target, psi in stages:
        print(f"  |Psi_6| = {psi:.3f} at packing fraction {target:.4f}")
    print(f"final packing fraction {last.packing_fraction:.5f} (close packing "
          f"{CLOSE_PACKING:.5f}); median disk packed at {np.median(local):.5f}")

    fig, (ax, ax_psi) = plt.subplots(2, 1, figsize=(7, 8), sharex=True,
                                     gridspec_kw={"height_ratios": [2, 1]})
    ax.semilogy(phi, z, ".", ms=1, color="k", label=f"compression at rate {RATE:g}")
    fluid = np.linspace(START, 0.72, 200)
    ax.semilogy(fluid, theory.henderson_z(fluid), "C0", label="Henderson (fluid)")
    ax.semilogy(fluid[fluid < 0.6], theory.virial_z(fluid[fluid < 0.6]), "C2--",
                label="virial series, 10 terms")
    solid = np.linspace(0.72, CLOSE_PACKING * (1 - 1e-6), 400)
    ax.semilogy(solid, 2.0 / (1.0 - solid / CLOSE_PACKING), "C3",
                label=r"free volume $2/(1-\phi/\phi_{cp})$")
    ax.axvspan(0.700, 0.716, color="0.9", label="liquid-hexatic coexistence")
    ax.set_ylabel("Z = PA / NkT")
    ax.set_ylim(1.0, 10 * MAX_PRESSURE)
    ax.legend(frameon=False, fontsize=8, loc="upper left")
    ax_psi.plot(*zip(*stages), "o-k")
    ax_psi.axvspan(0.700, 0.716, color="0.9")
    ax_psi.set_xlabel("packing fraction")
    ax_psi.set_ylabel(r"$|\Psi_6|$")
    ax_psi.set_ylim(0, 1)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(f"wrote {out}")
    return stages, phi, z, last


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "compression_eos.png")
