"""A sheared hard-disk fluid: its velocity profile, and its viscosity against Enskog's theory.

Physics: 2000 disks in a box with Lees-Edwards boundaries, whose images above slide
to the right and those below to the left.  No wall pushes the fluid; the shear enters
through the sliding boundary alone, and the disks settle into a linear flow
``u(y) = rate (y - H/2)`` across the whole box (left panel: the mean x velocity in 20
slabs, with its error bars, on the line of slope ``rate``).  The fluid carries the
momentum of the flow from the top to the bottom: the off-diagonal pressure ``P_xy =
-eta rate``, summed exactly at every collision and over every flight, gives the
viscosity ``eta``.  A weak thermostat (a hundredth of the collision rate) takes out
the heat of the shear.  Right panel: ``eta`` in units of ``sqrt(m kT) / d`` against
the packing fraction, beside Enskog's theory (Gass 1971) with the converged
Chapman-Enskog correction of the dilute gas: within a few per cent up to packing 0.5,
below the fluid near freezing, where collisions are correlated (docs/shear.md has
the table).  Third panel: the viscosity at packing 0.3 against the reduced shear rate
``rate d sqrt(m / kT)``, which the shear heating limits: the Newtonian plateau, flat
within its errors (in 2D the viscosity creeps up as the rate falls, the long-time
tail, too little to see here).  Faster flows would need a stronger thermostat, whose
redraws carry momentum away (0.45 instead of 0.51 with one at a tenth of the
collision rate).

Writes a figure and prints the viscosities::

    python examples/sheared_fluid.py [examples/output/sheared_fluid.png]
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import measurements, theory  # noqa: E402

N, PROFILE_PACKING, SEED = 2000, 0.4, 1
PACKINGS = (0.05, 0.2, 0.3, 0.4, 0.5, 0.6)
RATES = (0.005, 0.01, 0.02, 0.05, 0.1)  # shear rates at 0.3, over the collision rate
COLLISIONS_PER_DISK = 2000  # each viscosity's window


def collision_rate(phi: float) -> float:
    """Enskog's collision rate per disk at kT = 1 (unit diameters and masses)."""
    g = theory.contact_value(theory.henderson_z(phi), phi)
    return float(theory.enskog_collision_rate(theory.number_density(phi), 1.0, g))


def sheared(phi: float, rate: float | None = None) -> ed.Simulation:
    """The fluid sheared at ``rate`` (default 0.02 of its collision rate), with a
    thermostat at 0.01 of the collision rate, past its start."""
    nu = collision_rate(phi)
    rate = 0.02 * nu if rate is None else rate
    sim = ed.make_gas(N, phi, seed=SEED, shear_rate=rate, thermostat=(1.0, 0.01 * nu))
    sim.advance(until=300.0 / nu)
    return sim


def reduced_viscosity(sim: ed.Simulation, phi: float) -> tuple[float, float, float]:
    """The viscosity and its error in units of ``sqrt(m kT) / d`` at the measured
    temperature, and that temperature."""
    m = sim.measure(COLLISIONS_PER_DISK / collision_rate(phi), blocks=10)
    scale = math.sqrt(m.temperature)
    return m.viscosity / scale, m.viscosity_error / scale, m.temperature


def main(out: Path) -> None:
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig, (left, right, third) = plt.subplots(1, 3, figsize=(15, 4.2))

    sim = sheared(PROFILE_PACKING)
    rate = sim.families["shear"].rate
    prof = measurements.profiles(sim, 200.0 / collision_rate(PROFILE_PACKING))
    height = sim.box.height
    left.errorbar(prof.centres, prof.velocity[:, 0], yerr=prof.velocity_error[:, 0],
                  fmt="o", ms=4, label="measured")
    y = np.array([0.0, height])
    left.plot(y, rate * (y - height / 2), "k--", lw=1, label=f"slope {rate:.3g}")
    left.set_xlabel("height y")
    left.set_ylabel("mean velocity along x")
    left.set_title(f"flow across the box (packing {PROFILE_PACKING})")
    left.legend()

    print(f"{N} disks, shear at 0.02 and thermostat at 0.01 of the collision rate")
    print("packing   eta (sqrt(m kT)/d)     Enskog   ratio")
    measured, errors = [], []
    for phi in PACKINGS:
        eta, err, _ = reduced_viscosity(sheared(phi), phi)
        measured.append(eta)
        errors.append(err)
        enskog = float(theory.enskog_viscosity(phi))
        print(f"  {phi:4.2f}    {measured[-1]:.4f} +- {errors[-1]:.4f}    {enskog:.4f}   "
              f"{measured[-1] / enskog:.3f}")
    phis = np.linspace(0.01, 0.65, 100)
    right.plot(phis, theory.enskog_viscosity(phis), "k-", lw=1, label="Enskog")
    right.plot(phis, theory.enskog_viscosity(phis, sonine=False), "k:", lw=1,
               label="Enskog, first Sonine (Gass)")
    right.errorbar(PACKINGS, measured, yerr=errors, fmt="o", ms=5, label="measured")
    right.set_yscale("log")
    right.set_xlabel("packing fraction")
    right.set_ylabel("viscosity  eta d / sqrt(m kT)")
    right.legend()

    print("packing 0.3: rate d sqrt(m/kT)   eta (sqrt(m kT)/d)")
    reduced, by_rate, by_rate_err = [], [], []
    for fraction in RATES:
        rate = fraction * collision_rate(0.3)
        eta, err, kt = reduced_viscosity(sheared(0.3, rate), 0.3)
        reduced.append(rate / math.sqrt(kt))
        by_rate.append(eta)
        by_rate_err.append(err)
        print(f"            {reduced[-1]:8.4f}          {eta:.4f} +- {err:.4f}")
    third.errorbar(reduced, by_rate, yerr=by_rate_err, fmt="o", ms=5, label="measured")
    third.axhline(float(theory.enskog_viscosity(0.3)), color="k", lw=1, label="Enskog")
    third.set_xscale("log")
    third.set_xlabel("shear rate  rate d sqrt(m / kT)")
    third.set_ylabel("viscosity  eta d / sqrt(m kT)")
    third.set_title("packing 0.3")
    third.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "sheared_fluid.png")
