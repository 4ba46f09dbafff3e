"""The equation of state of hard disks, Z(eta), measured against the literature curves.

Physics: a fluid of hard disks has no energy scale, so its pressure is ``P = n kT Z(eta)``
with a compressibility factor that depends on the packing fraction only.  It is measured
here exactly from the collision virial, ``Z = 1 + sum J |r_ij| / (2 t N kT)``, and
independently from the collision rate (which fixes the contact value g(sigma), and
``Z = 1 + 2 eta g(sigma)``), from the dilute gas to the dense fluid near freezing
(eta ~ 0.70), and compared with Henderson's formula, the Santos-Lopez de Haro-Yuste
equation and the virial series to B_10.

    python examples/equation_of_state.py [examples/output/equation_of_state.png]
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

N, SEED, COLLISIONS = 1000, 1, 1_000_000
ETAS = (0.05, 0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.68)


def measure_point(eta):
    sim = ed.make_gas(N, eta, seed=SEED)
    sim.advance(collisions=200 * N // 2)  # melt the lattice start
    g = theory.contact_value(theory.henderson_z(eta), eta)
    rate = theory.enskog_collision_rate(theory.number_density(eta), 1.0, g)
    m = sim.measure(duration=2.0 * COLLISIONS / (N * rate), blocks=10)
    # The collision rate's contact value, turned into Z = 1 + 2 eta g(sigma).
    n = m.n / m.area
    g_rate = m.collision_rate / (2 * n * math.sqrt(math.pi * m.temperature))
    z_rate = 1 + 2 * eta * g_rate
    z_rate_err = 2 * eta * m.collision_rate_error / (2 * n * math.sqrt(math.pi * m.temperature))
    return m.compressibility_factor, m.compressibility_factor_error, z_rate, z_rate_err


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    rows = []
    print(" eta     Z (virial)           Z (collision rate)    Henderson  SHY")
    for eta in ETAS:
        z, z_err, z_rate, z_rate_err = measure_point(eta)
        rows.append((eta, z, z_err, z_rate, z_rate_err))
        print(f" {eta:4.2f}  {z:8.4f} +- {z_err:.4f}   {z_rate:8.4f} +- {z_rate_err:.4f}"
              f"   {theory.henderson_z(eta):8.4f}  {theory.santos_z(eta):8.4f}")
    rows = np.array(rows)

    eta = np.linspace(0.0, 0.72, 200)
    fig, (ax, ax_dev) = plt.subplots(2, 1, figsize=(6.0, 6.5), sharex=True,
                                     gridspec_kw={"height_ratios": [2, 1]})
    ax.plot(eta, theory.henderson_z(eta), "k-", lw=1, label="Henderson (1975)")
    ax.plot(eta, theory.santos_z(eta), "b--", lw=1, label="Santos et al. (1995)")
    ax.plot(eta, theory.virial_z(eta), "g:", lw=1.5, label="virial series to $B_{10}$")
    ax.errorbar(rows[:, 0], rows[:, 1], rows[:, 2], fmt="o", color="C3", ms=4,
                label=f"edmd2d, virial (N={N})")
    ax.errorbar(rows[:, 0], rows[:, 3], rows[:, 4], fmt="x", color="C1", ms=6,
                label="edmd2d, from collision rate")
    ax.set_ylabel(r"$Z = PA/NkT$")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.set_title("Hard disks: equation of state")
    hend = theory.henderson_z(rows[:, 0])
    ax_dev.axhline(0.0, color="k", lw=1)
    ax_dev.plot(eta, theory.santos_z(eta) / theory.henderson_z(eta) - 1, "b--", lw=1)
    ax_dev.plot(eta, theory.virial_z(eta) / theory.henderson_z(eta) - 1, "g:", lw=1.5)
    ax_dev.errorbar(rows[:, 0], rows[:, 1] / hend - 1, rows[:, 2] / hend, fmt="o",
                    color="C3", ms=4)
    ax_dev.set_ylim(-0.06, 0.02)
    ax_dev.set_xlabel(r"packing fraction $\eta$")
    ax_dev.set_ylabel("Z / Henderson - 1")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "equation_of_state.png")
