"""A granular bed heated from below: inelastic disks under gravity on a hot floor.

Physics: 400 disks (diameter 1, mass 1) with a coefficient of restitution e = 0.9 are
held down by gravity g = 1 in a closed box 100 wide (room for 4 close-packed rows) and
25 tall.  The floor is a heated wall at kT = 4: a disk that hits it leaves with a
velocity drawn from that temperature, whatever it came with.  The side walls and the
lid are inelastic too (wall restitution 0.9).  The floor pumps energy in, the
collisions dissipate it (each one loses the fraction 1 - e^2 of the normal relative
motion's energy), and within some 20 time units the two balance: the bed reaches a
steady, fluidised state, and its granular temperature (the kinetic temperature of
:func:`edmd2d.kinetic_temperature`) fluctuates by about 6 % about a constant value,
some 40 % of the floor's, without drifting.

In the steady state the bed is densest at the floor (packing fraction about 0.5 in
the lowest diameter) and thins out upwards over some 12 diameters.  Its temperature
falls with height, from about 2.6 next to the floor (where disks have just been
heated) to about 1.25 at a height of 8 diameters: disks rising through the bed lose
energy in collisions on their way up.  Higher up, where the gas thins out, the
temperature passes through a minimum and rises a little: a known feature of driven
granular gases, whose heat flux follows the density gradient as well as the
temperature gradient (Brey and Ruiz-Montero, Europhys. Lett. 66, 805 (2004)).  A
deeper bed (``ROWS = 8``) or a hotter floor (``FLOOR_KT = 20``) instead puts the
densest layer a few diameters above the floor, on a hotter, more dilute layer next to
it.  Disks are coloured by speed.

Writes an animation of the first 60 time units (``.gif``, or ``.mp4`` if you name
one) and, beside it, a still (``.png``) with the bed at the end, the temperature
against time, and the density and temperature against height in the steady state;
prints the steady temperature in both halves of the run, the energy balance and the
profiles::

    python examples/heated_bed.py [examples/output/heated_bed.gif]
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

N, ROWS, HEIGHT, RADIUS, SEED = 400, 4.0, 25.0, 0.5, 1  # box width N * 2 RADIUS / ROWS
GRAVITY, FLOOR_KT, RESTITUTION, WALL_RESTITUTION = 1.0, 4.0, 0.9, 0.9
DURATION, SETTLE = 400.0, 50.0  # averages over t > SETTLE
ANIMATE, FPS, TIME_PER_SECOND = 60.0, 15, 5.0  # 12 s of video, 181 frames
BIN = 1.0  # height of the profiles' bins (one diameter)
BLOCK = 30.0  # time of the blocks whose means give the errors


def build() -> ed.Simulation:
    """The disks on a lattice filling the whole box, at the floor's temperature."""
    width = N * 2.0 * RADIUS / ROWS
    packing = N * math.pi * RADIUS**2 / (width * HEIGHT)
    gas = ed.make_gas(N, packing, radius=RADIUS, aspect=width / HEIGHT, periodic=False,
                      temperature=FLOOR_KT, seed=SEED)
    return ed.Simulation(gas.positions, gas.velocities, gas.radii, gas.masses, box=gas.box,
                         restitution=RESTITUTION, wall_restitution=WALL_RESTITUTION,
                         gravity=(0.0, -GRAVITY), wall_temperatures={"bottom": FLOOR_KT},
                         seed=SEED)


def halves(t: np.ndarray, temp: np.ndarray):
    """Mean and standard error of the temperature in each half of the steady window.

    The errors come from the scatter of the means of blocks ``BLOCK`` long over the
    whole window (the temperature decorrelates within a few time units, with an echo
    of the bed's bouncing at ~5), scaled to the length of a half."""
    mid = 0.5 * (t[0] + t[-1])
    per_block = max(1, round(BLOCK / (t[1] - t[0])))
    blocks = temp[: len(temp) // per_block * per_block].reshape(-1, per_block).mean(axis=1)
    scatter = float(np.std(blocks, ddof=1))
    return [(float(part.mean()), scatter / math.sqrt(len(part) / per_block))
            for part in (temp[t < mid], temp[t >= mid])]


def main(out: Path) -> dict:
    """Run, animate, print and plot; return the measured numbers (the steady
    temperature in each half, ``first`` and ``second``, with their errors and the rms
    ``fluctuation``; the profiles ``heights``, ``packing`` and ``temperature``; the
    floor's ``heat`` and the ``dissipation`` per unit time)."""
    if DURATION < SETTLE + 2.0 * BLOCK:
        raise SystemExit(f"the duration must be at least {SETTLE + 2 * BLOCK:g}: the settling "
                         f"time {SETTLE:g} and two blocks of {BLOCK:g} for the errors")
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    dt = TIME_PER_SECOND / FPS
    times, temps, heights, energies = [], [], [], []
    ledger = {}  # heat, dissipation and energy when the steady window opens
    bar = viz.TextProgress()

    def record(i=0, n=None):  # after each frame: temperature, and the profiles' samples
        if n is not None:
            bar(i, n)
        times.append(sim.time)
        temps.append(ed.kinetic_temperature(sim))
        if sim.time >= SETTLE:
            if not ledger:
                ledger.update(t=sim.time, heat=sim.wall_heat()[2],
                              lost=sim.dissipated_energy(), energy=sim.total_energy())
            v = sim.velocities
            heights.append(sim.positions[:, 1] - RADIUS)  # above the lowest possible
            energies.append(0.5 * sim.masses * np.einsum("ij,ij->i", v, v))

    speed_scale = 2.0 * math.sqrt(FLOOR_KT)  # twice the floor's rms speed per axis
    anim = viz.animate(sim, min(ANIMATE, DURATION), fps=FPS,
                       time_per_second=TIME_PER_SECOND, color_by="speed", vmin=0.0,
                       vmax=speed_scale, colorbar=True, figsize=(8.0, 2.6))
    anim.ax.figure.axes[-1].set_ylabel("speed")
    viz.save(anim, out, dpi=80, progress=record)
    plt.close(anim.ax.figure)
    for k in range(len(times), round(DURATION / dt) + 1):  # the rest, at the same interval
        sim.advance(until=k * dt)
        record()

    t, temp = np.array(times), np.array(temps)
    steady = t >= SETTLE
    (t1, e1), (t2, e2) = halves(t[steady], temp[steady])
    spread = float(temp[steady].std())
    span = sim.time - ledger["t"]
    heat = (sim.wall_heat()[2] - ledger["heat"]) / span
    lost = (sim.dissipated_energy() - ledger["lost"]) / span
    stored = sim.total_energy() - ledger["energy"]

    y, ke = np.concatenate(heights), np.concatenate(energies)
    top = BIN * math.ceil(np.quantile(y, 0.995) / BIN)
    edges = np.arange(0.0, top + 0.5 * BIN, BIN)
    mid = 0.5 * (edges[1:] + edges[:-1])
    counts, _ = np.histogram(y, edges)
    packing = counts / len(heights) / (sim.box.width * BIN) * math.pi * RADIUS**2
    sums, _ = np.histogram(y, edges, weights=ke)
    with np.errstate(invalid="ignore", divide="ignore"):
        local_t = np.where(counts >= 200, sums / counts, np.nan)  # 2 degrees of freedom
    coolest = int(np.nanargmin(local_t))

    print(f"{N} disks, box {sim.box.width:.1f} x {sim.box.height:g}, g = {GRAVITY:g}, "
          f"e = {RESTITUTION:g} (walls {WALL_RESTITUTION:g}), floor kT = {FLOOR_KT:g}, "
          f"tc = {sim.tc:.2g}")
    print(f"granular temperature for t > {SETTLE:g}: {t1:.3f} +- {e1:.3f} in the first "
          f"half, {t2:.3f} +- {e2:.3f} in the second (change {t2 - t1:+.3f}); "
          f"fluctuation (rms) {spread:.3f}")
    print(f"energy per unit time: the floor gives {heat:.2f}, collisions dissipate "
          f"{lost:.2f} (the bed's energy changed by {stored:+.1f} over {span:g})")
    print(" height  packing  temperature")
    for k in range(0, len(mid), 2):
        print(f"{mid[k]:6.2f}   {packing[k]:.4f}   {local_t[k]:6.2f}")
    print(f"half the disks sit below height {np.median(y):.2f}; the temperature falls from "
          f"{local_t[0]:.2f} at the floor to {local_t[coolest]:.2f} at height "
          f"{mid[coolest]:.2f}")

    fig = plt.figure(figsize=(12.0, 7.6))
    grid = fig.add_gridspec(2, 3, height_ratios=[1.0, 1.05])
    ax_box = fig.add_subplot(grid[0, :])
    viz.draw(sim, ax=ax_box, color_by="speed", vmin=0.0, vmax=speed_scale, show_time=True)
    ax_t = fig.add_subplot(grid[1, 0])
    ax_t.plot(t, temp, "k", lw=0.8)
    ax_t.axvline(SETTLE, color="0.5", ls=":")
    half = 0.5 * (t[steady][0] + t[-1])
    ax_t.hlines([t1, t2], [SETTLE, half], [half, t[-1]], colors="C3", lw=2,
                label="mean of each half")
    ax_t.set_xlabel("time $t$")
    ax_t.set_ylabel("granular temperature $T$")
    ax_t.set_ylim(0.0, None)
    ax_t.legend(frameon=False, fontsize="small", loc="upper right")
    ax_n = fig.add_subplot(grid[1, 1])
    ax_n.plot(packing, mid, "C0o-", ms=3)
    ax_n.set_xlabel("packing fraction")
    ax_n.set_ylabel("height above the floor")
    ax_n.set_xlim(0.0, None)
    ax_temp = fig.add_subplot(grid[1, 2], sharey=ax_n)
    ax_temp.plot(local_t, mid, "C3o-", ms=3)
    ax_temp.axvline(FLOOR_KT, color="0.5", ls="--", label="floor")
    ax_temp.set_xlabel(r"temperature $\langle m v^2\rangle / 2$")
    ax_temp.set_xlim(0.0, 1.1 * FLOOR_KT)
    ax_temp.legend(frameon=False, fontsize="small")
    ax_n.set_ylim(0.0, top)
    fig.tight_layout()
    still = out.with_suffix(".png")
    fig.savefig(still, dpi=80)
    plt.close(fig)
    print(f"wrote {out} and {still}: {sim.counts.collisions} collisions up to "
          f"t = {sim.time:g}")
    return {"first": (t1, e1), "second": (t2, e2), "fluctuation": spread,
            "heights": mid, "packing": packing, "temperature": local_t,
            "heat": heat, "dissipation": lost}


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "heated_bed.gif")
