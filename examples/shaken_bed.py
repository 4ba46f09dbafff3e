"""A granular bed on a shaken floor, and the temperature of a dilute one against kinetic
theory.

Physics: the floor is a wall segment across a box periodic along x that moves as
``A sin(omega t)`` (:class:`edmd2d.Oscillation`); disks (diameter 1, mass 1) fall on it
under gravity g = 1, collide inelastically with each other (restitution e) and
elastically with the floor, which gives them the energy their collisions dissipate.

First a dense bed: 300 disks with e = 0.9, 40 wide, on a floor shaken with amplitude
0.4 at omega = 6 (peak acceleration 14 g).  Within a few time units the bed is
fluidised, and it stays so: a dense, cool layer (packing fraction 0.5, granular
temperature about 1) floats some 6 diameters above the floor on a hot, dilute one
(temperature 5 at the floor), the granular Leidenfrost state (Eshuis, van der Weele,
van der Meer and Lohse, Phys. Rev. Lett. 95, 258001 (2005)).  The animation shows
it, coloured by speed.

Then the dilute, nearly elastic regime of V. Kumaran (J. Fluid Mech. 364, 163 (1998)):
four disks per unit length of floor, ``epsilon = (1 - e^2) N sigma / L = 0.04``, and
three floor speeds.  To leading order the velocities are Maxwellian at one
temperature, the density is barometric, and the floor's power balances the
collisions' losses at ``kT = (2 sqrt(2) / pi) m (A omega)^2 / epsilon``
(:func:`edmd2d.theory.vibrated_bed_temperature`).  The measured temperatures grow as
``(A omega)^2`` and lie within a few % of that line (0.996, 0.970 and 1.001 of it,
each from one run of 200 disks with a scatter of 2 %; the first correction, of order
``epsilon^(1/2)``, is some 4 % at this ``epsilon``: docs/moving-walls.md measures it).

Writes an animation of the dense bed (``.gif``, or ``.mp4`` if you name one) and,
beside it, a still (``.png``) with the bed, its density and temperature against height,
and the dilute bed's temperature against the floor's speed; prints the numbers::

    python examples/shaken_bed.py [examples/output/shaken_bed.gif]
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import theory, viz  # noqa: E402

N, WIDTH, HEIGHT, SEED = 300, 40.0, 40.0, 1
AMPLITUDE, OMEGA, RESTITUTION = 0.4, 6.0, 0.9
DURATION, SETTLE = 120.0, 20.0  # the dense bed; profiles over t > SETTLE
FPS, TIME_PER_SECOND = 15, 4.0
# The dilute bed: disks per unit length, epsilon, floor amplitude, the leading-order
# temperatures whose floor speeds are run, width of its box, relaxation times run.
PER_LENGTH, EPSILON, DILUTE_AMPLITUDE = 4.0, 0.04, 0.5
TARGETS, DILUTE_WIDTH, RELAXATIONS = (70.0, 140.0, 280.0), 50.0, 20.0


def floor_bed(n, width, height, amplitude, omega, restitution, temperature, seed,
              rows_gap=1.2):
    """``n`` disks in rows above a floor across a box periodic along x, shaken as
    ``amplitude sin(omega t)``, with velocities at ``temperature``."""
    floor = 2.0 * amplitude + 0.1
    rng = np.random.default_rng(seed)
    per_row = int(width // rows_gap)
    x = (np.arange(n) % per_row) * (width / per_row) + 0.5 + rng.uniform(0.0, 0.1, n)
    y = floor + amplitude + 1.0 + rows_gap * (np.arange(n) // per_row)
    if y.max() + 0.5 >= height:
        raise ValueError(f"{n} disks do not fit in rows below the lid at {height}")
    vel = rng.normal(size=(n, 2)) * math.sqrt(temperature)
    return ed.Simulation(np.column_stack([x, y]), vel, 0.5,
                         box=ed.Box(width, height, periodic=(True, False)),
                         walls=[ed.Wall((0.0, floor), (width, floor))],
                         wall_motions={0: ed.Oscillation(amplitude, omega)},
                         gravity=(0.0, -1.0), restitution=restitution, resting=False,
                         seed=seed)


def dilute_temperature(target, seed):
    """The dilute bed whose leading-order temperature is ``target``: (its floor
    speed ``A omega``, that temperature, the measured one averaged over the last
    ``RELAXATIONS - 3`` relaxation times)."""
    e = math.sqrt(1.0 - EPSILON / PER_LENGTH)
    speed = math.sqrt(target * EPSILON * math.pi / (2.0 * math.sqrt(2.0)))
    omega = speed / DILUTE_AMPLITUDE
    kt = theory.vibrated_bed_temperature(DILUTE_AMPLITUDE, omega, e, PER_LENGTH)
    sim = floor_bed(round(PER_LENGTH * DILUTE_WIDTH), DILUTE_WIDTH, 16.0 * kt,
                    DILUTE_AMPLITUDE, omega, e, kt, seed, rows_gap=2.0)
    tau = 2.0 * math.sqrt(kt / math.pi) / EPSILON  # relaxation of the energy balance
    sim.advance(until=3.0 * tau)
    temps = []
    for k in range(1, round((RELAXATIONS - 3.0) * 50) + 1):
        sim.advance(until=(3.0 + k / 50.0) * tau)
        temps.append(ed.kinetic_temperature(sim))
    return speed, kt, float(np.mean(temps))


def main(out: Path) -> dict:
    """Animate the dense bed, measure its profiles and the dilute bed's temperatures,
    print and plot; return the numbers (``heights``, ``packing``, ``temperature`` of
    the dense bed; ``speeds``, ``theory`` and ``measured`` of the dilute one)."""
    if DURATION <= SETTLE:
        raise SystemExit(f"the duration must exceed the settling time {SETTLE:g}")
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = floor_bed(N, WIDTH, HEIGHT, AMPLITUDE, OMEGA, RESTITUTION, 1.0, SEED)
    speed_scale = 2.0 * AMPLITUDE * OMEGA
    anim = viz.animate(sim, SETTLE, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by="speed", vmin=0.0, vmax=speed_scale, colorbar=True,
                       figsize=(6.0, 6.0))
    anim.ax.figure.axes[-1].set_ylabel("speed")
    viz.save(anim, out, dpi=70, progress=viz.TextProgress())
    plt.close(anim.ax.figure)
    floor = sim.walls[0].start[1] + 0.5  # the centres' lowest height, floor at rest
    prof = ed.measurements.profiles(sim, DURATION - sim.time, samples=200, blocks=10,
                                    bins=20, span=(floor - AMPLITUDE, floor + 20.0))
    heights = prof.centres - floor
    print(f"dense bed: {N} disks, e = {RESTITUTION:g}, floor A = {AMPLITUDE:g}, "
          f"omega = {OMEGA:g} (peak acceleration {AMPLITUDE * OMEGA**2:g} g), "
          f"{sim.counts.collisions} collisions up to t = {sim.time:g}")
    print(f"  granular temperature {ed.kinetic_temperature(sim):.2f} at the end; the "
          f"floor has done work {sim.wall_work()[0]:.0f}, collisions dissipated "
          f"{sim.dissipated_energy():.0f}")
    print("  height  packing  temperature")
    for z, eta, kt in zip(heights[::2], prof.packing_fraction[::2], prof.temperature[::2]):
        print(f"  {z:6.2f}   {eta:.3f}   {kt:6.2f}")

    speeds, expected, measured = [], [], []
    for target in TARGETS:
        speed, kt, found = dilute_temperature(target, SEED)
        speeds.append(speed)
        expected.append(kt)
        measured.append(found)
        print(f"dilute bed, epsilon = {EPSILON:g}: floor speed A omega = {speed:.3f}, "
              f"kT = {found:.1f} against {kt:.1f} (leading order), ratio "
              f"{found / kt:.3f}")

    fig = plt.figure(figsize=(12.0, 4.2))
    grid = fig.add_gridspec(1, 4, width_ratios=[1.2, 0.8, 0.8, 1.1])
    ax_box = fig.add_subplot(grid[0])
    viz.draw(sim, ax=ax_box, color_by="speed", vmin=0.0, vmax=speed_scale,
             show_time=True)
    ax_n = fig.add_subplot(grid[1])
    ax_n.plot(prof.packing_fraction, heights, "C0o-", ms=3)
    ax_n.set_xlabel("packing fraction")
    ax_n.set_ylabel("height above the floor")
    ax_t = fig.add_subplot(grid[2], sharey=ax_n)
    ax_t.errorbar(prof.temperature, heights, xerr=prof.temperature_error, fmt="C3o-",
                  ms=3)
    ax_t.set_xlabel("granular temperature")
    ax_k = fig.add_subplot(grid[3])
    u2 = np.square(speeds)
    line = np.linspace(0.0, 1.1 * u2.max(), 50)
    slope = expected[0] / u2[0]
    ax_k.plot(line, slope * line, "k--", label="kinetic theory, leading order")
    ax_k.plot(u2, measured, "C3o", label="measured")
    ax_k.set_xlabel(r"floor's speed squared $(A\omega)^2$")
    ax_k.set_ylabel("granular temperature $kT$")
    ax_k.set_title(rf"dilute bed, $\epsilon = {EPSILON:g}$", fontsize="medium")
    ax_k.legend(frameon=False, fontsize="small")
    fig.tight_layout()
    still = out.with_suffix(".png")
    fig.savefig(still, dpi=80)
    plt.close(fig)
    print(f"wrote {out} and {still}")
    return {"heights": heights, "packing": prof.packing_fraction,
            "temperature": prof.temperature, "speeds": speeds, "theory": expected,
            "measured": measured}


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "shaken_bed.gif")
