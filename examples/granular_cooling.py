"""A granular gas: inelastic disks cool down and gather into clusters.

Physics: 4000 disks at packing fraction 0.25 in a periodic box collide with a
coefficient of restitution e = 0.7, so every collision loses the fraction 1 - e^2 of the
normal relative motion's energy.  Nothing feeds energy back, and the gas cools.  At
first it stays uniform and cools close to what kinetic theory predicts for a uniform
gas, T = T0 exp(-(1 - e^2) C / 2) against the collisions per disk C, which with the
collision rate omega ~ sqrt(T) is Haff's law T = T0 / (1 + t / t_H)^2 (here within 10 %
of both up to C = 7; derivations and limits in docs/restitution.md).  But this uniform
state is unstable: where the gas is a little denser, disks collide more often, lose
energy faster, the pressure there drops and more disks flow in.  The motion becomes
correlated (neighbouring disks move alike, which shows as patches of one colour) and the
gas falls apart into dense, slow clusters separated by dilute, hot gaps; the temperature
then falls more slowly than the two laws, which assume a uniform gas (Goldhirsch and
Zanetti, Phys. Rev. Lett. 70, 1619 (1993)).  Disks are coloured by their speed over
the current root-mean-square speed, so the colours stay meaningful while the whole gas
slows down (by a factor of about 25 in this run).

Writes an animation (``.gif``, or ``.mp4`` if you name one) and, beside it, a still
(``.png``) with the last frame and the temperature against both laws, and prints the
temperature against the laws at a few times::

    python examples/granular_cooling.py [examples/output/granular_cooling.gif]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import theory, viz  # noqa: E402

N, PACKING, RESTITUTION, SEED = 4000, 0.25, 0.7, 5
DURATION, FPS, TIME_PER_SECOND = 300.0, 10, 30.0  # 10 s of video, 101 frames
PRINT_AT = (0.0, 3.0, 6.0, 12.0, 30.0, 60.0, 150.0, 300.0)  # times of the printed table


def relative_speed(sim: ed.Simulation) -> np.ndarray:
    """Each disk's speed over the root-mean-square speed of the gas now."""
    v = np.hypot(*sim.velocities.T)
    return v / np.sqrt(np.mean(v * v))


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    gas = ed.make_gas(N, PACKING, seed=SEED)  # elastic, kT = 1, on a lattice
    gas.advance(collisions=5 * N)  # melt the lattice start elastically
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, gas.masses, box=gas.box,
                        restitution=RESTITUTION)
    t0, temp0 = sim.time, ed.kinetic_temperature(sim)
    # Haff's time t_H = 4 / ((1 - e^2) omega0) from the Enskog collision rate at T0.
    eps = 1.0 - RESTITUTION**2
    g_contact = theory.contact_value(theory.henderson_z(PACKING), PACKING)
    omega0 = theory.enskog_collision_rate(theory.number_density(PACKING), 1.0, g_contact,
                                          temperature=temp0)
    t_haff = 4.0 / (eps * omega0)

    times, per_disk, temps = [], [], []
    bar = viz.TextProgress()

    def record(i, n):  # after each frame: time, collisions per disk, temperature
        bar(i, n)
        times.append(sim.time - t0)
        per_disk.append(2.0 * sim.counts.collisions / N)
        temps.append(ed.kinetic_temperature(sim) / temp0)

    anim = viz.animate(sim, DURATION, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by=relative_speed, vmin=0.0, vmax=2.5, colorbar=True,
                       figsize=(5.4, 4.6))
    anim.ax.figure.axes[-1].set_ylabel("speed / rms speed")
    viz.save(anim, out, dpi=64, progress=record)
    plt.close(anim.ax.figure)

    t, c, temp = np.array(times), np.array(per_disk), np.array(temps)
    exp_law = np.exp(-eps * c / 2.0)
    haff = 1.0 / (1.0 + t / t_haff) ** 2
    print(f"N = {N}, packing fraction {PACKING}, e = {RESTITUTION}: Enskog omega0 = "
          f"{omega0:.3f}, t_H = {t_haff:.2f}")
    print("     t   collisions/disk   T/T0       exp law    Haff")
    for tp in (tp for tp in PRINT_AT if tp <= t[-1]):
        k = int(np.argmin(np.abs(t - tp)))
        print(f"{t[k]:6.1f}   {c[k]:10.1f}       {temp[k]:.3e}  {exp_law[k]:.3e}  "
              f"{haff[k]:.3e}")

    fig, (ax_box, ax_t) = plt.subplots(1, 2, figsize=(10.0, 4.6),
                                       gridspec_kw={"width_ratios": [1, 1.15]})
    viz.draw(sim, ax=ax_box, color_by=relative_speed, vmin=0.0, vmax=2.5, show_time=True)
    ax_t.loglog(t[1:], temp[1:], "k", lw=2, label="simulation")
    ax_t.loglog(t[1:], exp_law[1:], "C0--",
                label=r"$\exp(-(1-e^2)\,C/2)$, $C$ measured")
    ax_t.loglog(t[1:], haff[1:], "C3:", lw=2, label=r"Haff: $1/(1+t/t_H)^2$")
    ax_t.set_xlabel("time $t$")
    ax_t.set_ylabel("granular temperature $T/T_0$")
    ax_t.legend(frameon=False, fontsize="small")
    fig.tight_layout()
    still = out.with_suffix(".png")
    fig.savefig(still, dpi=80)
    plt.close(fig)
    print(f"wrote {out} and {still}: {sim.counts.collisions} collisions, "
          f"{sim.dissipated_energy() / (sim.kinetic_energy() + sim.dissipated_energy()):.1%}"
          " of the kinetic energy dissipated")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "granular_cooling.gif")
