"""A granular shear flow: inelastic disks sheared until heating balances dissipation.

Physics: 1000 disks at packing fraction 0.3 with a coefficient of restitution of 0.8
(each collision loses 36 % of the energy of the normal relative motion), sheared
between Lees-Edwards boundaries.  Nothing but the shear feeds them: the work of the
shear stress, ``-rate A P_xy``, heats the flow, the collisions cool it, and the two
balance in a steady state (left panel: the temperature of the peculiar motion
against time, for three shear rates, each divided by ``rate^2``).  Hard disks have no
time scale of their own, so the flows at different rates are the same flow, seen
faster or slower: from any start the temperature over ``(rate d)^2`` and the
pressure over ``rate^2`` reach the same values (right panel, with their errors over
the steady state; the printed table gives them).  The energy books close to
rounding: the peculiar energy gained equals the work of the shear less the energy
dissipated.

Writes a figure and prints the steady state::

    python examples/granular_shear.py [examples/output/granular_shear.png]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402

N, PACKING, RESTITUTION, SEED = 1000, 0.3, 0.8, 3
RATES = (0.1, 0.3, 1.0)
SETTLE, WINDOW = 40.0, 200.0  # in units of 1 / rate


def peculiar_energy(sim: ed.Simulation) -> float:
    u = sim.peculiar_velocities
    return 0.5 * float(np.sum(sim.masses[:, None] * u * u))


def main(out: Path) -> None:
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    print(f"{N} disks at packing {PACKING}, restitution {RESTITUTION}, from kT = 1")
    print("  rate    T / rate^2          P / rate^2          books (relative)")
    steady = []
    for rate in RATES:
        sim = ed.make_gas(N, PACKING, seed=SEED, shear_rate=rate, restitution=RESTITUTION)
        times, temps = [], []
        for k in range(1, 41):
            sim.advance(until=SETTLE / rate * k / 40)
            times.append(sim.time * rate)
            temps.append(ed.kinetic_temperature(sim) / rate**2)
        left.plot(times, temps, label=f"rate {rate:g}")
        e0, lost0 = peculiar_energy(sim), sim.dissipated_energy()
        m = sim.measure(WINDOW / rate, blocks=10)
        work = -rate * sim.box.area * m.duration * m.pressure_xy
        lost = sim.dissipated_energy() - lost0
        books = (peculiar_energy(sim) - e0 - work + lost) / (work + lost)
        t, t_err = m.temperature / rate**2, m.temperature_error / rate**2
        p, p_err = m.pressure / rate**2, m.pressure_error / rate**2
        steady.append((t, t_err, p, p_err))
        print(f"  {rate:4g}    {t:.4f} +- {t_err:.4f}    {p:.4f} +- {p_err:.4f}    "
              f"{books:.1e}")
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_xlabel("time x rate")
    left.set_ylabel("temperature / rate^2")
    left.set_title("from kT = 1 to the steady state")
    left.legend()
    steady_arr = np.array(steady)
    right.errorbar(RATES, steady_arr[:, 0], yerr=steady_arr[:, 1], fmt="o",
                   label="T / rate^2")
    right.errorbar(RATES, steady_arr[:, 2], yerr=steady_arr[:, 3], fmt="s",
                   label="P / rate^2")
    right.set_xscale("log")
    right.set_xlabel("shear rate")
    right.set_ylim(0.0, 1.3 * float(steady_arr[:, [0, 2]].max()))
    right.set_title("the steady state, at every rate")
    right.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "granular_shear.png")
