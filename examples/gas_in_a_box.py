"""A gas in a box: from equal speeds to the Maxwell-Boltzmann distribution.

Physics: 400 hard disks in a walled box all start with the same speed (random
directions), i.e. far from equilibrium.  Each elastic collision conserves energy and
momentum but redistributes speed between the pair, and within a few collision times the
speeds settle on the two-dimensional Maxwell-Boltzmann distribution
``P(v) = (m v / kT) exp(-m v^2 / 2kT)`` with ``kT`` fixed by the (exactly conserved)
kinetic energy -- Boltzmann's relaxation to equilibrium, watched disk by disk.  Disks
are coloured by speed: at first all alike, then spread over the whole colour scale.

Writes an animation (``.gif``, or ``.mp4`` if you name one) and, beside it, a still
with the speed histogram (``.png``)::

    python examples/gas_in_a_box.py [examples/output/gas_in_a_box.gif]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

N, PACKING, SEED = 400, 0.3, 7
DURATION, FPS, TIME_PER_SECOND = 16.0, 20, 2.0  # 8 s of video, 161 frames
RELAXED_AFTER = 4.0  # collect the histogram from here on


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = ed.make_gas(N, PACKING, periodic=False, temperature=1.0, seed=SEED)
    # Same kinetic energy (kT = 1 over 2N degrees of freedom), but every speed equal.
    v = sim.velocities
    sim.set_velocities(v / np.hypot(*v.T)[:, None] * np.sqrt(2.0))
    kT = sim.kinetic_energy() / N  # 2D: E = N kT

    speeds = []
    bar = viz.TextProgress()

    def record(i, n):  # called after each frame is drawn: sample the speeds
        bar(i, n)
        if sim.time >= RELAXED_AFTER:
            speeds.append(np.hypot(*sim.velocities.T))

    anim = viz.animate(sim, DURATION, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by="speed", vmax=3.0, colorbar=True, figsize=(5.0, 4.2))
    viz.save(anim, out, dpi=80, progress=record)
    plt.close(anim.ax.figure)

    fig, (ax_box, ax_hist) = plt.subplots(1, 2, figsize=(9.0, 4.2),
                                          gridspec_kw={"width_ratios": [1, 1.1]})
    viz.draw(sim, ax=ax_box, color_by="speed", vmax=3.0, show_time=True)
    samples = np.concatenate(speeds)
    ax_hist.hist(samples, bins=40, range=(0, 4), density=True, color="0.7",
                 label=f"simulation, t > {RELAXED_AFTER:g}")
    vv = np.linspace(0, 4, 200)
    ax_hist.plot(vv, vv / kT * np.exp(-vv**2 / (2 * kT)), "C3",
                 label=r"Maxwell-Boltzmann $v\,e^{-v^2/2kT}/kT$")
    ax_hist.axvline(np.sqrt(2 * kT), color="k", ls="--", label="all speeds at t = 0")
    ax_hist.set_xlabel("speed $v$")
    ax_hist.set_ylabel("probability density")
    ax_hist.legend(frameon=False, fontsize="small")
    fig.tight_layout()
    still = out.with_suffix(".png")
    fig.savefig(still, dpi=80)
    plt.close(fig)
    print(f"wrote {out} and {still}: {sim.counts.collisions} collisions up to t = {sim.time:g}, "
          f"energy conserved to {abs(sim.kinetic_energy() / N / kT - 1):.1e}")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "gas_in_a_box.gif")
