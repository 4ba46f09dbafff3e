"""Sedimentation: an elastic gas under gravity settles into the barometric profile.

Physics: 2000 elastic disks (diameter 1, mass 1) start spread evenly over a box 2000
wide (periodic) and 600 tall (walled) and fall under gravity g = 0.02.  While they
settle, an Andersen thermostat at kT = 1 carries off the energy of the fall: each disk
has its velocity redrawn from the Maxwell-Boltzmann distribution about once every 50
time units.  At t = 2000 the thermostat is switched off (the state carries on in a new
:class:`~edmd2d.Simulation` without it) and the gas runs isolated, its energy conserved
exactly.  In equilibrium the density falls off with height as the barometric law
``n(y) = n0 exp(-y / L)``, ``L = kT / (m g)`` (``y`` the height of a disk's centre
above the lowest it can be, one radius above the floor), with ``kT`` measured as the
time-averaged kinetic energy per disk (two degrees of freedom per disk in 2D:
``<KE> / N = kT``).  Here ``L`` is about 50 and the lid 12 decay lengths up.

At the floor the gas is not quite ideal: its density there, n0 = 0.019 disks per unit
area, makes ``B2 n0 = 3 %`` with the second virial coefficient ``B2 = pi d^2 / 2``.
Hydrostatics ``dp/dy = -m g n`` with ``p = n kT (1 + B2 n)`` makes the local decay
length ``L (1 + 2 B2 n)``: the profile is a little stretched near the floor, where the
disks get in each other's way, and barometric further up.  Solved for ``n`` (with the
Lambert W function; ``n0`` follows from ``L (n0 + B2 n0^2) = N / width``), this is the
virial profile of the figure; to first order in ``B2 n0`` it raises the mean height
to ``L (1 + B2 n0 / 2)``.  A straight-line fit of ``ln n`` against ``y`` over the lowest
5 decay lengths finds a decay length 1.5 % above ``kT / (m g)``, as the virial
profile predicts (1.6 %) to within the run's statistical error of 0.1 %; the mean
height is 1.5 % above ``kT / (m g)``, as its first-order value predicts.

Writes a figure (``.png``) with the density against height (log scale) beside the
barometric law and its virial correction, their ratio, and the mean height against
time; prints the fitted decay length against ``kT / (m g)`` and the mean height::

    python examples/sedimentation.py [examples/output/sedimentation.png]
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.special import lambertw  # noqa: E402

import edmd2d as ed  # noqa: E402

N, SEED, RADIUS, GRAVITY, KT = 2000, 4, 0.5, 0.02, 1.0
FLOOR_DENSITY, HEIGHT = 0.02, 12.0  # ideal-gas n0 (sets the width); height in kT/mg
SETTLE, THERMOSTAT_RATE = 2000.0, 0.02  # an Andersen thermostat at KT until t = SETTLE
DURATION, SAMPLE, BLOCKS = 12_000.0, 10.0, 8  # heights every SAMPLE; errors from BLOCKS
FIT_TOP, BINS_PER_LENGTH = 5.0, 5  # fit ln n over 0 < y < 5 L, in bins of L / 5
B2 = math.pi * (2.0 * RADIUS) ** 2 / 2.0  # second virial coefficient of hard disks


def build() -> ed.Simulation:
    """The disks on a lattice spread over the whole box at kT = KT, under gravity, held
    at KT by the thermostat."""
    length = KT / GRAVITY
    width, height = N / (FLOOR_DENSITY * length), HEIGHT * length
    packing = N * math.pi * RADIUS**2 / (width * height)
    gas = ed.make_gas(N, packing, radius=RADIUS, aspect=width / height,
                      periodic=(True, False), temperature=KT, seed=SEED)
    return ed.Simulation(gas.positions, gas.velocities, gas.radii, gas.masses, box=gas.box,
                         gravity=(0.0, -GRAVITY), thermostat=(KT, THERMOSTAT_RATE),
                         seed=SEED)


def floor_density(length: float, per_width: float) -> float:
    """``n0`` of the virial profile: the root of ``L (n0 + B2 n0^2) = N / width``."""
    return (-1.0 + math.sqrt(1.0 + 4.0 * B2 * per_width / length)) / (2.0 * B2)


def virial_profile(y: np.ndarray, length: float, per_width: float) -> np.ndarray:
    """The density at heights ``y`` from hydrostatics with ``p = n kT (1 + B2 n)``,
    ``ln n + 2 B2 n = ln n0 + 2 B2 n0 - y / L`` (for a box many decay lengths tall)."""
    n0 = floor_density(length, per_width)
    arg = 2.0 * B2 * n0 * np.exp(2.0 * B2 * n0 - y / length)
    return lambertw(arg).real / (2.0 * B2)


def decay_length(counts: np.ndarray, centres: np.ndarray) -> float:
    """The decay length of a straight-line fit of ``ln(counts)`` against height, each
    bin weighted by its count (the inverse variance of the log of a Poisson count)."""
    keep = counts > 0
    slope = np.polyfit(centres[keep], np.log(counts[keep]), 1, w=np.sqrt(counts[keep]))[0]
    return -1.0 / slope


def main(out: Path) -> dict:
    """Run, print and plot; return the measured numbers, in units of kT/mg: ``ratio``,
    the fitted decay length, and ``virial_ratio``, the same fit to the virial profile;
    ``mean_height`` and its first-order virial value ``expected_mean``; the errors
    ``ratio_err`` and ``mean_err``."""
    if DURATION <= SETTLE + BLOCKS * SAMPLE:
        raise SystemExit(f"the duration must exceed the settling time {SETTLE:g} by at least "
                         f"{BLOCKS * SAMPLE:g}")
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    width, mass = sim.box.width, float(sim.masses[0])
    times, mean_heights, heights, kinetic = [], [], [], []
    for k in range(1, round(DURATION / SAMPLE) + 1):
        sim.advance(until=k * SAMPLE)
        if sim.thermostat is not None and sim.time >= SETTLE:
            # Settled: the same state carries on without the thermostat, isolated.
            redraws = sim.counts.redraws
            sim = ed.Simulation(sim.positions, sim.velocities, sim.radii, sim.masses,
                                box=sim.box, gravity=sim.gravity, time=sim.time)
            settled_energy = sim.total_energy()
        y = sim.positions[:, 1] - RADIUS
        times.append(sim.time)
        mean_heights.append(y.mean())
        if sim.thermostat is None:
            heights.append(y)
            kinetic.append(sim.kinetic_energy() / N)

    kt = float(np.mean(kinetic))
    length = kt / (mass * GRAVITY)
    per_width = N / width
    n0 = floor_density(length, per_width)
    edges = np.linspace(0.0, FIT_TOP * length, round(FIT_TOP * BINS_PER_LENGTH) + 1)
    centres = 0.5 * (edges[1:] + edges[:-1])
    bin_area = width * (edges[1] - edges[0])

    def counts_of(ys):  # counts in the fit's bins
        return np.histogram(np.concatenate(ys), edges)[0].astype(float)

    counts = counts_of(heights)
    density = counts / len(heights) / bin_area
    fit = decay_length(counts, centres)
    # Errors from independent stretches of the run (each far longer than the ~100 time
    # units over which the kinetic energy and the heights decorrelate): the fit over
    # kT/mg, the density and the mean height in each block.
    parts = list(zip(np.array_split(heights, BLOCKS), np.array_split(kinetic, BLOCKS)))
    ratios = [decay_length(counts_of(h), centres) / (np.mean(k) / (mass * GRAVITY))
              for h, k in parts]
    ratio_err = float(np.std(ratios, ddof=1) / math.sqrt(BLOCKS))
    density_err = np.std([counts_of(h) / len(h) / bin_area for h, _ in parts], axis=0,
                         ddof=1) / math.sqrt(BLOCKS)
    # (The mean height and kT/mg move in opposite directions as the fixed energy shifts
    # between kinetic and potential: their ratio is compared block by block.)
    mean_y = float(np.mean(heights))
    means = [np.mean(h) / (np.mean(k) / (mass * GRAVITY)) for h, k in parts]
    mean_err = float(np.std(means, ddof=1) / math.sqrt(BLOCKS))
    expected_mean = 1.0 + 0.5 * B2 * n0
    # The fit applied to the virial profile, averaged over the same bins.
    fine = np.linspace(0.0, FIT_TOP * length, 20 * len(centres) + 1)
    virial_bins = np.array([virial_profile(fine[(fine >= a) & (fine <= b)], length,
                                           per_width).mean()
                            for a, b in zip(edges[:-1], edges[1:])])
    virial_fit = decay_length(virial_bins * len(heights) * bin_area, centres)

    print(f"{N} disks in a {width:g} x {sim.box.height:g} box (periodic in x), g = "
          f"{GRAVITY:g}; thermostat at kT = {KT:g} until t = {SETTLE:g} ({redraws / N:.0f} "
          f"redraws per disk), then isolated: kT = <KE>/N = {kt:.4f} over "
          f"{SETTLE:g} < t < {sim.time:g}")
    print(f"decay length: fitted {fit:.2f} over 0 < y < {FIT_TOP:g} kT/mg, kT/mg = "
          f"{length:.2f}: ratio {fit / length:.4f} +- {ratio_err:.4f} (the virial profile "
          f"gives {virial_fit / length:.4f})")
    print(f"mean height: {mean_y:.2f} = {mean_y / length:.4f} +- {mean_err:.4f} kT/mg; "
          f"virial, to first order: 1 + B2 n0 / 2 = {expected_mean:.4f} (n0 = {n0:.4f}, "
          f"B2 n0 = {B2 * n0:.3f})")

    fig = plt.figure(figsize=(11.0, 5.6))
    grid = fig.add_gridspec(2, 2, height_ratios=[2.2, 1.0], width_ratios=[1.2, 1.0])
    ax_n = fig.add_subplot(grid[0, 0])
    ax_r = fig.add_subplot(grid[1, 0], sharex=ax_n)
    ax_y = fig.add_subplot(grid[:, 1])
    yy = np.linspace(0.0, FIT_TOP * length, 400)
    ideal = per_width / length * np.exp(-yy / length)
    virial = virial_profile(yy, length, per_width)
    ax_n.errorbar(centres, density, density_err, fmt="o", ms=4, color="k",
                  label="simulation")
    ax_n.semilogy(yy, ideal, "C0--",
                  label=r"barometric $\frac{N}{W L}\,e^{-y/L}$, $L = kT/mg$")
    ax_n.semilogy(yy, virial, "C3", label=r"with $p = nkT\,(1 + B_2 n)$")
    ax_n.set_ylabel("number density $n(y)$")
    ax_n.legend(frameon=False)
    ax_n.tick_params(labelbottom=False)
    ideal_bins = per_width / length * np.exp(-centres / length)
    ax_r.errorbar(centres, density / ideal_bins, density_err / ideal_bins, fmt="o",
                  ms=3, color="k")
    ax_r.axhline(1.0, color="C0", ls="--")
    ax_r.plot(yy, virial / ideal, "C3")
    ax_r.set_xlabel(f"height $y$ above the floor ($L$ = {length:.1f})")
    ax_r.set_ylabel("n / barometric")
    ax_y.plot(times, mean_heights, "k", lw=0.8)
    ax_y.axvspan(0.0, SETTLE, color="0.9", label=f"thermostat at kT = {KT:g}")
    ax_y.axhline(length, color="C0", ls="--", label="$L = kT/mg$")
    ax_y.axhline(expected_mean * length, color="C3", label=r"$L\,(1 + B_2 n_0/2)$")
    ax_y.set_xlabel("time $t$")
    ax_y.set_ylabel(r"mean height $\langle y\rangle$")
    ax_y.set_ylim(0.0, 2.0 * length)
    ax_y.legend(frameon=False, loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)
    print(f"wrote {out}: {sim.counts.collisions} collisions since the thermostat went off, "
          f"energy conserved to {abs(sim.total_energy() / settled_energy - 1):.1e}")
    return {"ratio": fit / length, "ratio_err": ratio_err,
            "virial_ratio": virial_fit / length, "mean_height": mean_y / length,
            "mean_err": mean_err, "expected_mean": expected_mean, "kt": kt}


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "sedimentation.png")
