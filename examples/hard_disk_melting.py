"""The melting of hard disks: the Mayer-Wood loop of the liquid-hexatic transition.

Physics: hard disks melt in two steps, with a first-order transition between the
liquid and the hexatic phase, whose coexistence spans packing fractions 0.700 to 0.716
(Bernard and Krauth, Phys. Rev. Lett. 107, 155704 (2011); Engel et al., Phys. Rev. E
87, 042134 (2013)).  In a finite periodic system the coexisting phases pay for their
interface, and the equation of state, the pressure ``beta P d^2`` against the packing
fraction, shows a loop (a Mayer-Wood loop) where the two phases coexist: the pressure
rises to a maximum near 0.702, falls to a minimum near 0.714 and rises again.  Its
height shrinks with the number of disks (0.016 at 256^2, 0.006 at 1024^2 in
``beta P d^2``: published data below), while its area, the interface free energy per
disk, shrinks as ``N^-1/2``.

Each point of the sweep (:func:`edmd2d.ensemble.sweep`) is one simulation: ``N`` equal
disks in a periodic box of the triangular lattice's aspect (1 : sqrt(3)/2), started as
a liquid (placed at random at 0.45 and compressed quickly, :func:`edmd2d.compress`) or
as a crystal (a lattice), run for ``EQUILIBRATE`` collisions per disk and then
measured over ``MEASURE`` collisions per disk in ``BLOCKS`` windows: ``Z`` (virial
pressure, :func:`edmd2d.measure`) and the global orientational order ``|Psi_6|``
(:func:`edmd2d.hexatic_order`) of each window.  The pressure of the first and the
second half of the windows is compared (their difference, the drift, with its error);
the state is checkpointed after every window, so an interrupted sweep continues each
point where it stopped.  ``beta P d^2 = Z rho d^2 = Z 4 eta / pi``.

Slow density fluctuations dominate the error near the transition: at 64^2 disks and
0.70 a window of 3500 collisions per disk has ``Z`` to about 0.02, and the whole
measurement of 7e4 collisions per disk (about 200 s of one core) to 0.01 (1e-3).

Writes a figure (``.png``): the measured loop with error bars beside the published
equations of state (Bernard and Krauth 2011 at 256^2 and 1024^2; Li et al., J. Chem.
Phys. 157, 234111 (2022) at 128^2 in the same box shape, from the data distributed
with that paper), the order ``|Psi_6|`` against packing fraction, and a snapshot inside
the coexistence region coloured by the phase of each disk's local ``psi_6`` (hexatic
domains share one colour); writes the table of the sweep (``results.csv`` in the
sweep's directory) and prints it::

    python examples/hard_disk_melting.py [OUT.png] [--quick | --full] [--n 4096]
        [--scheduler serial|tcp://...] [--workers 2] [--sweep DIR]

``--quick`` (the default): 64^2 disks, six packing fractions, liquid starts, 5e4
collisions per disk each; about 12 minutes on two cores.  ``--full``: 64^2 and 128^2
disks, 0.690 to 0.724 in steps of 0.002, liquid and crystal starts, 2e4 + 7e4
collisions per disk (128^2: hours of one core per point; run it in the background, it
resumes from its checkpoints when started again).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np

import edmd2d as ed

# Published equations of state, beta P d^2 (d the diameter) at packing fraction eta,
# from the data files distributed with Li et al. (2022) (github.com/jellyfysh/
# HistoricDisks, DigitizedData: "original data provided by the authors").
BERNARD_KRAUTH_2011 = {  # event-chain Monte Carlo, square boxes: {N: {eta: beta P d^2}}
    1024 ** 2: {0.698: 9.16931, 0.700: 9.18545, 0.702: 9.18800, 0.704: 9.18692,
                0.706: 9.18553, 0.708: 9.18502, 0.710: 9.18425, 0.712: 9.18354,
                0.714: 9.18218, 0.716: 9.18336, 0.718: 9.19495, 0.720: 9.22765},
    256 ** 2: {0.698: 9.17080, 0.700: 9.18846, 0.702: 9.19240, 0.704: 9.18870,
               0.706: 9.18584, 0.708: 9.18178, 0.710: 9.17904, 0.712: 9.17687,
               0.714: 9.17582, 0.716: 9.17791, 0.718: 9.18577, 0.720: 9.2266},
}
LI_2022_128 = {  # massively parallel Monte Carlo, 128^2 disks, box 1 : sqrt(3)/2
    0.698: (9.17441, 0.00057), 0.704: (9.18700, 0.00091), 0.708: (9.17512, 0.00088),
    0.712: (9.16590, 0.00094), 0.716: (9.1560, 0.0018)}

NS = (64 ** 2,)
ETAS = (0.692, 0.698, 0.702, 0.708, 0.714, 0.720)
STARTS = ("liquid",)
EQUILIBRATE, MEASURE, BLOCKS, REPLICAS, SEED = 1.5e4, 3.5e4, 10, 1, 2011
FULL = dict(NS=(64 ** 2, 128 ** 2), ETAS=tuple(np.round(np.arange(0.690, 0.7241, 0.002), 3)),
            STARTS=("liquid", "crystal"), EQUILIBRATE=2e4, MEASURE=7e4)
ASPECT = 2.0 / math.sqrt(3.0)  # width / height: a triangular lattice of N = k^2 fits


def start(n: int, eta: float, kind: str, rng) -> ed.Simulation:
    """A liquid (random at 0.45, compressed quickly) or a crystal (a lattice)."""
    if kind == "crystal":
        return ed.make_gas(n, eta, aspect=ASPECT, seed=rng)
    gas = ed.random_gas(n, 0.45, aspect=ASPECT, seed=rng)
    return ed.compress(gas, eta, rate=1e-2).simulation


def melting_point(parameters: dict, seed, workdir: Path) -> dict:
    """One point of the sweep: build, equilibrate, measure in windows (see the module
    notes), checkpointing after every window and continuing from the checkpoint."""
    n, eta = int(parameters["n"]), float(parameters["packing_fraction"])
    windows_eq = int(round(parameters["equilibrate"] / parameters["measure"]
                           * parameters["blocks"]))
    windows = windows_eq + int(parameters["blocks"])
    path = workdir / "state.edmd2d"
    if path.exists():
        sim = ed.checkpoint.load(path)
        record = ed.checkpoint.read_metadata(path)
    else:
        sim = start(n, eta, parameters["start"], np.random.default_rng(seed))
        probe = ed.measure(sim, 10.0, blocks=1)  # the collision rate, for the windows
        per_window = parameters["measure"] / parameters["blocks"]  # collisions per disk
        record = {"window": per_window / (probe.collisions / (n * probe.duration)),
                  "z": [], "psi6": [], "collisions": []}
        ed.checkpoint.save(sim, path, metadata=record)
    while len(record["z"]) < windows:
        m = ed.measure(sim, record["window"], blocks=1)
        record["z"].append(m.compressibility_factor)
        record["psi6"].append(abs(ed.hexatic_order(sim)[0]))
        record["collisions"].append(sim.counts.collisions / n)
        ed.checkpoint.save(sim, path, metadata=record)
    z = np.array(record["z"][windows_eq:])
    half = len(z) // 2
    scale = 4.0 * eta / math.pi  # beta P d^2 = Z rho d^2
    z_err = float(z.std(ddof=1) / math.sqrt(len(z)))
    drift = float(z[half:].mean() - z[:half].mean())
    drift_err = float(math.hypot(z[half:].std(ddof=1) / math.sqrt(len(z) - half),
                                 z[:half].std(ddof=1) / math.sqrt(half)))
    psi = np.array(record["psi6"][windows_eq:])
    return {"Z": float(z.mean()), "Z_error": z_err,
            "pressure": float(z.mean() * scale), "pressure_error": z_err * scale,
            "psi6": float(psi.mean()), "psi6_error": float(psi.std(ddof=1)
                                                           / math.sqrt(len(psi))),
            "drift": drift, "drift_error": drift_err,
            "collisions_per_disk": float(record["collisions"][-1])}


def run_sweep(directory: Path, scheduler, workers):
    points = [{"n": n, "packing_fraction": float(eta), "start": kind,
               "equilibrate": EQUILIBRATE, "measure": MEASURE, "blocks": BLOCKS}
              for n in NS for eta in ETAS for kind in STARTS]
    from edmd2d import ensemble  # (dask.distributed: pip install -e ".[ensemble]")

    return ensemble.sweep(melting_point, points, output=directory, replicas=REPLICAS,
                          seed=SEED, scheduler=scheduler, workers=workers, progress=True)


def table(result) -> list[dict]:
    rows = []
    for task in result.tasks:
        if task["status"] != "ok":
            print(f"  {task['task']} failed: {task['error']['type']}: "
                  f"{task['error']['message']}")
            continue
        rows.append({**task["parameters"], **task["values"], "task": task["task"],
                     "seconds": task["seconds"]})
    return rows


def main(out: Path, directory: Path, scheduler=None, workers=None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    result = run_sweep(directory, scheduler, workers)
    rows = table(result)
    print(f"  {'N':>6} {'eta':>6} {'start':>8} {'beta P d^2':>18} {'|Psi_6|':>7} "
          f"{'drift of Z':>16} {'coll/disk':>9} {'s':>6}")
    for r in rows:
        print(f"  {r['n']:6d} {r['packing_fraction']:6.3f} {r['start']:>8} "
              f"{r['pressure']:9.4f} +- {r['pressure_error']:.4f} {r['psi6']:7.3f} "
              f"{r['drift']:+8.4f} +- {r['drift_error']:.4f} "
              f"{r['collisions_per_disk']:9.0f} {r['seconds']:6.0f}")

    fig, (ax, ax_psi, ax_snap) = plt.subplots(1, 3, figsize=(16, 5.2),
                                              gridspec_kw={"width_ratios": [1.3, 1, 1]})
    for (n, data), style in zip(BERNARD_KRAUTH_2011.items(), ("C7-", "C7--")):
        ax.plot(list(data), list(data.values()), style, lw=1,
                label=f"Bernard & Krauth 2011, N = {int(math.isqrt(n))}$^2$")
    eta_li, p_li = zip(*LI_2022_128.items())
    ax.errorbar(eta_li, [p for p, _ in p_li], [e for _, e in p_li], fmt="s", ms=4,
                color="C2", mfc="none", label="Li et al. 2022, N = 128$^2$")
    for k, n in enumerate(sorted({r["n"] for r in rows})):
        for kind, marker in (("liquid", "o"), ("crystal", "^")):
            sel = sorted((r for r in rows if r["n"] == n and r["start"] == kind),
                         key=lambda r: r["packing_fraction"])
            if not sel:
                continue
            ax.errorbar([r["packing_fraction"] for r in sel], [r["pressure"] for r in sel],
                        [r["pressure_error"] for r in sel], fmt=marker + "-", ms=5,
                        color=_color(k, kind), capsize=2,
                        label=f"edmd2d, N = {int(math.isqrt(n))}$^2$, {kind} start")
            ax_psi.errorbar([r["packing_fraction"] for r in sel], [r["psi6"] for r in sel],
                            [r["psi6_error"] for r in sel], fmt=marker + "-", ms=5,
                            color=_color(k, kind), capsize=2)
    for a in (ax, ax_psi):
        a.axvspan(0.700, 0.716, color="0.92", zorder=0)
        a.set_xlabel(r"packing fraction $\eta$")
    ax.set_ylabel(r"$\beta P d^2$")
    ax.legend(frameon=False, fontsize=7)
    ax_psi.set_ylabel(r"$|\Psi_6|$")
    ax_psi.set_ylim(0, 1)
    snapshot(ax_snap, result, rows)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    (directory / "summary.json").write_text(json.dumps(rows, indent=1))
    print(f"wrote {out} and {directory / 'results.csv'}")
    return rows


def _color(k: int, kind: str) -> str:
    """A colour per system size ``k`` and start."""
    return f"C{(4 * k + (1 if kind == 'liquid' else 3)) % 10}"


def snapshot(ax, result, rows):
    """The final state of the point nearest the middle of the coexistence region (the
    largest N), each disk coloured by the phase of its local psi_6."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection

    if not rows:
        return
    n = max(r["n"] for r in rows)
    pick = min((r for r in rows if r["n"] == n),
               key=lambda r: abs(r["packing_fraction"] - 0.708))
    sim = ed.checkpoint.load(result.output / "tasks" / pick["task"] / "state.edmd2d")
    _, local = ed.hexatic_order(sim)
    phase = (np.angle(local) / (2 * np.pi)) % 1.0
    color = plt.get_cmap("hsv")(phase)
    color[:, 3] = np.clip(np.abs(local), 0.15, 1.0)  # disordered disks fade
    ax.add_collection(EllipseCollection(2 * sim.radii, 2 * sim.radii, 0, units="xy",
                                        offsets=sim.positions,
                                        offset_transform=ax.transData,
                                        facecolors=color, edgecolors="none"))
    ax.set_xlim(0, sim.box.width)
    ax.set_ylim(0, sim.box.height)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(f"N = {sim.n}, $\\eta$ = {pick['packing_fraction']:.3f}: "
                 r"phase of local $\psi_6$", fontsize=9)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = Path(__file__).parent / "output" / "hard_disk_melting.png"
    parser.add_argument("out", nargs="?", type=Path, default=default,
                        help=f"the figure to write (default {default})")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true", help="64^2 disks, 6 points (default)")
    mode.add_argument("--full", action="store_true", help="64^2 and 128^2, 18 points, "
                      "liquid and crystal starts (hours; resumable)")
    parser.add_argument("--n", type=int, default=None, help="one system size instead")
    parser.add_argument("--etas", default=None,
                        help="comma-separated packing fractions instead (e.g. 0.708,0.714)")
    parser.add_argument("--starts", default=None,
                        help="comma-separated starts instead: liquid, crystal")
    parser.add_argument("--collisions", type=float, default=None,
                        help="collisions per disk measured per point (equilibration: "
                        "3/7 of it)")
    parser.add_argument("--scheduler", default=None,
                        help="'serial', or a Dask scheduler address (default: a local "
                        "cluster of one worker per core)")
    parser.add_argument("--workers", type=int, default=None, help="local Dask workers")
    parser.add_argument("--sweep", type=Path, default=None,
                        help="the sweep's directory (default next to the figure)")
    args = parser.parse_args()
    if args.full:
        globals().update(FULL)
    if args.n is not None:
        if args.n < 16:
            parser.error(f"--n must be at least 16, got {args.n}")
        NS = (args.n,)
    if args.etas is not None:
        ETAS = tuple(float(e) for e in args.etas.split(","))
        if not all(0.0 < e < 0.9 for e in ETAS):
            parser.error(f"--etas must lie in (0, 0.9), got {args.etas}")
    if args.starts is not None:
        STARTS = tuple(args.starts.split(","))
        if not set(STARTS) <= {"liquid", "crystal"}:
            parser.error(f"--starts takes liquid and crystal, got {args.starts}")
    if args.collisions is not None:
        if args.collisions <= 0:
            parser.error(f"--collisions must be positive, got {args.collisions}")
        MEASURE, EQUILIBRATE = args.collisions, args.collisions * 3 / 7
    sweep_dir = args.sweep or args.out.with_suffix("").parent / (args.out.stem + "-sweep")
    main(args.out, sweep_dir, args.scheduler, args.workers)
