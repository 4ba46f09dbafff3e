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
Phys. 157, 234111 (2022) at 870 disks and at 128^2 in the same box shape, from the data
distributed with that paper), the order ``|Psi_6|`` against packing fraction, the
height and the fall of the loop against ``N`` beside the published ones, the
pressure of each window near the loop's minimum, the whole equation of state (given
the command line's fluid sweep), and a snapshot inside the
coexistence region coloured by the phase of each disk's local ``psi_6`` (hexatic
domains share one colour); writes the table of the sweep (``results.csv`` in the
sweep's directory) and prints it with the loop heights and falls::

    python examples/hard_disk_melting.py [OUT.png] [--quick | --full] [--n 4096]
        [--etas 0.704,0.712] [--starts liquid,crystal] [--collisions 7e4]
        [--scheduler serial|tcp://...] [--workers 2] [--sweep DIR]
    python examples/hard_disk_melting.py OUT.png --plot SWEEP [SWEEP ...]

``--quick`` (the default): 64^2 disks, six packing fractions, liquid starts, 5e4
collisions per disk each; about 7 minutes on two cores.  ``--full``: 64^2 and 128^2
disks, 0.690 to 0.724 in steps of 0.002, liquid and crystal starts, 2e4 + 7e4
collisions per disk, 72 points (on one core of the machine these notes were measured
on, a point of 1e5 collisions per disk takes 4 minutes at 64^2 and 15 at 128^2, so
about 10 core-hours in all; run it in the background, it resumes from its
checkpoints when started again).  ``--plot`` runs
nothing: it draws the figure from the finished points of one or more sweeps (several
system sizes, or a sweep still running) and writes their combined points to
``OUT.csv`` (the loop heights and falls are printed).  A run continued in a sweep of
more windows (its ``state.edmd2d`` copied into the new sweep's task directory before
it starts) is counted once, as its longer run (``drop_continued``).

The runs at one ``(N, eta)`` (starts, replicas, several sweeps) are combined as a
weighted mean whose error is widened by the scatter of the runs when they disagree
(``combine``).  Two numbers measure the loop against ``N``: its height, the
highest combined pressure at ``eta <= 0.710`` less the lowest one after it at ``eta
<= 0.718``, as the published heights are read off the published curves, which noise
inflates (``loop_height``); and the fall of the pressure from 0.704 to 0.716, two
fixed points inside the loop of every published size from 870 disks up, which it
does not (``fall``).
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
# HistoricDisks, DigitizedData: "original data provided by the authors"), in the loop
# region.
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
LI_2022_870 = {  # event-chain Monte Carlo, 870 disks, box 29 : 30 sqrt(3)/2
    0.690: 8.969476, 0.692: 9.036875, 0.694: 9.08915, 0.696: 9.12293, 0.698: 9.13490,
    0.700: 9.12956, 0.702: 9.11236, 0.704: 9.09028, 0.706: 9.06621, 0.708: 9.04532,
    0.710: 9.0272, 0.712: 9.0122, 0.714: 9.0158, 0.716: 9.0450, 0.718: 9.0818}
LI_2022_224 = {  # event-chain Monte Carlo, 224 disks, square box
    0.690: 8.83348, 0.692: 8.84651, 0.694: 8.83344, 0.696: 8.7966, 0.698: 8.74504,
    0.700: 8.6876, 0.702: 8.6436, 0.704: 8.6262, 0.706: 8.6175, 0.708: 8.6305,
    0.710: 8.6721, 0.712: 8.7378, 0.714: 8.7984, 0.716: 8.8869, 0.718: 8.9570}
ENGEL_2013_512 = {  # Engel et al. (2013), massively parallel Monte Carlo, 512^2, square
    0.698: 9.16994, 0.700: 9.18610, 0.702: 9.19002, 0.704: 9.18816, 0.706: 9.186067,
    0.708: 9.18424, 0.710: 9.182809, 0.712: 9.18116, 0.714: 9.179945, 0.716: 9.18212,
    0.718: 9.19302, 0.720: 9.2269}
# The curves from which the loop height against N is drawn, with their source.
PUBLISHED_LOOPS = {
    224: (LI_2022_224, "Li et al. 2022"),
    870: (LI_2022_870, "Li et al. 2022"),
    128 ** 2: ({eta: p for eta, (p, _) in LI_2022_128.items()}, "Li et al. 2022"),
    256 ** 2: (BERNARD_KRAUTH_2011[256 ** 2], "Bernard & Krauth 2011"),
    512 ** 2: (ENGEL_2013_512, "Engel et al. 2013"),
    1024 ** 2: (BERNARD_KRAUTH_2011[1024 ** 2], "Bernard & Krauth 2011"),
}
# Where the loop is looked for: its maximum at eta <= MAX_BELOW (all published maxima
# lie at 0.692-0.704), its minimum after the maximum at eta <= MIN_BELOW (beyond it the
# pressure of the hexatic branch rises steeply at every size).
MAX_BELOW, MIN_BELOW = 0.710, 0.718
# The fall of the pressure between two fixed packing fractions, inside the loop of
# every published size from 870 disks up (Li et al.'s 128^2 points include both):
# unlike the loop's height, it needs no search for extremes, so noise does not bias it.
FALL = (0.704, 0.716)

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
    windows_eq = _windows_eq(parameters)
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
    return summarize(record, windows_eq, eta)


def _statistics(x) -> tuple[float, float, float, float]:
    """The mean of the windows ``x``, its standard error, and the drift: the mean of
    the second half of the windows less the first half's, with its error."""
    x = np.asarray(x, dtype=float)
    half = len(x) // 2
    drift_error = math.hypot(x[half:].std(ddof=1) / math.sqrt(len(x) - half),
                             x[:half].std(ddof=1) / math.sqrt(half))
    return (float(x.mean()), float(x.std(ddof=1) / math.sqrt(len(x))),
            float(x[half:].mean() - x[:half].mean()), float(drift_error))


def rho_d2(eta: float) -> float:
    """``rho d^2 = 4 eta / pi`` for equal disks of diameter ``d``: ``beta P d^2 = Z
    rho d^2``."""
    return 4.0 * eta / math.pi


def summarize(record: dict, windows_eq: int, eta: float) -> dict:
    """What a point returns, from the windows of its checkpoint's record after the
    first ``windows_eq``: ``Z``, ``beta P d^2 = Z 4 eta / pi``, ``|Psi_6|``, the drifts
    of ``Z`` and of ``|Psi_6|``, each with its error, and the collisions per disk."""
    z, z_err, drift, drift_err = _statistics(record["z"][windows_eq:])
    psi, psi_err, psi_drift, psi_drift_err = _statistics(record["psi6"][windows_eq:])
    scale = rho_d2(eta)
    return {"Z": z, "Z_error": z_err, "pressure": z * scale, "pressure_error": z_err * scale,
            "psi6": psi, "psi6_error": psi_err, "drift": drift, "drift_error": drift_err,
            "psi6_drift": psi_drift, "psi6_drift_error": psi_drift_err,
            "collisions_per_disk": float(record["collisions"][-1])}


def _windows_eq(parameters: dict) -> int:
    """The number of equilibration windows of a point."""
    return int(round(parameters["equilibrate"] / parameters["measure"]
                     * parameters["blocks"]))


def run_sweep(directory: Path, scheduler, workers):
    points = [{"n": n, "packing_fraction": float(eta), "start": kind,
               "equilibrate": EQUILIBRATE, "measure": MEASURE, "blocks": BLOCKS}
              for n in NS for eta in ETAS for kind in STARTS]
    from edmd2d import ensemble  # (dask.distributed: pip install -e ".[ensemble]")

    return ensemble.sweep(melting_point, points, output=directory, replicas=REPLICAS,
                          seed=SEED, scheduler=scheduler, workers=workers, progress=True)


def table(result) -> list[dict]:
    """The finished points of a sweep, one dict each (its parameters, values, task id
    and directory); failed ones are printed and left out."""
    rows = []
    for task in result.tasks:
        if task["status"] != "ok":
            print(f"  {task['task']} failed: {task['error']['type']}: "
                  f"{task['error']['message']}")
            continue
        state = result.output / "tasks" / task["task"] / "state.edmd2d"
        row = {**task["parameters"], **task["values"], "task": task["task"],
               "seconds": task["seconds"], "state": str(state)}
        if "start" in row and "psi6_drift" not in row and state.exists():
            # a result without the drift of |Psi_6|: all values again from the
            # windows its checkpoint keeps
            row.update(summarize(ed.checkpoint.read_metadata(state),
                                 _windows_eq(row), row["packing_fraction"]))
        rows.append(row)
    return rows


def _mean(values, errors) -> tuple[float, float]:
    """The inverse-variance weighted mean and its error, scaled up by ``sqrt(chi^2 /
    (k - 1))`` when the ``k`` values scatter more than their errors say (the Particle
    Data Group's scale factor), so that runs which have not yet agreed widen the
    error instead of hiding in it."""
    values = np.asarray(values, dtype=float)
    errors = np.asarray(errors, dtype=float)
    if not (np.isfinite(errors).all() and (errors > 0).all() and np.isfinite(values).all()):
        raise ValueError(f"values and errors must be finite, errors positive: {values}, "
                         f"{errors}")
    w = 1.0 / errors ** 2
    mean = float((w * values).sum() / w.sum())
    error = float(1.0 / math.sqrt(w.sum()))
    if len(values) > 1:
        chi2 = float((w * (values - mean) ** 2).sum())
        error *= max(1.0, math.sqrt(chi2 / (len(values) - 1)))
    return mean, error


def combine(rows) -> dict:
    """The runs at each ``(N, eta)`` (starts and replicas) as one pressure.

    Returns ``{N: [point, ...]}`` sorted by ``eta``, each point a dict: ``eta``,
    ``pressure`` and ``error`` (:func:`_mean` of the runs), ``runs`` and ``psi6``
    (the runs' mean ``|Psi_6|``).
    """
    groups: dict = {}
    for r in rows:
        groups.setdefault((r["n"], round(r["packing_fraction"], 6)), []).append(r)
    out: dict = {}
    for (n, eta), runs in sorted(groups.items()):
        p, e = _mean([r["pressure"] for r in runs], [r["pressure_error"] for r in runs])
        out.setdefault(n, []).append({
            "eta": eta, "pressure": p, "error": e, "runs": len(runs),
            "psi6": float(np.mean([r["psi6"] for r in runs]))})
    return out


def _extremes(eta, p):
    """The indices of the loop's maximum, the highest pressure at ``eta <=
    MAX_BELOW``, and of its minimum, the lowest one after it at ``eta <= MIN_BELOW``,
    and whether that minimum is the last point there (the loop may go on lower);
    ``None`` without a point at ``eta <= MAX_BELOW``."""
    eta, p = np.asarray(eta), np.asarray(p)
    top = np.flatnonzero(eta <= MAX_BELOW + 1e-9)
    if len(top) == 0:
        return None
    i = int(top[np.argmax(p[top])])
    after = np.flatnonzero((eta >= eta[i]) & (eta <= MIN_BELOW + 1e-9))
    j = int(after[np.argmin(p[after])])
    return i, j, bool(j == after[-1])


def loop_height(points, samples: int = 4000, seed: int = 0):
    """The height of the loop, from :func:`combine`'s points of one system size: the
    highest pressure less the lowest one after it (:func:`_extremes`), as the
    published heights are read off the published curves.

    Its ``error`` is that of the difference of the two points.  It is also biased
    upwards by the noise, the largest of several noisy values near a flat maximum
    lying above the maximum and the smallest below the minimum.  ``bias`` is what a
    parametric bootstrap sees of that (the mean height of ``samples`` curves
    redrawn from normal distributions of the points' means and errors, less the
    height): an estimate that falls short of the true bias when several points
    share an extreme, so read the height as ``height - bias`` or lower, within
    ``error``.  ``None`` without a point at ``eta <= MAX_BELOW``.
    """
    eta = np.array([q["eta"] for q in points])
    p = np.array([q["pressure"] for q in points])
    err = np.array([q["error"] for q in points])
    found = _extremes(eta, p)
    if found is None:
        return None
    i, j, bounded = found
    rng = np.random.default_rng(seed)
    draws = p + err * rng.standard_normal((samples, len(p)))
    heights = []
    for d in draws:
        k, m, _ = _extremes(eta, d)
        heights.append(d[k] - d[m])
    height = float(p[i] - p[j])
    return {"height": height, "error": float(math.hypot(err[i], err[j])),
            "bias": float(np.mean(heights) - height), "eta_max": float(eta[i]),
            "eta_min": float(eta[j]), "bounded": bounded}


def fall(points, between=FALL):
    """``(p(a) - p(b), error)`` between the packing fractions ``between = (a, b)``,
    from :func:`combine`'s points (``None`` if either is missing)."""
    at = {round(q["eta"], 6): q for q in points}
    a, b = (at.get(round(e, 6)) for e in between)
    if a is None or b is None:
        return None
    return a["pressure"] - b["pressure"], math.hypot(a["error"], b["error"])


def published_loops() -> list[dict]:
    """The loop height and the fall between ``FALL`` of each published curve
    (their errors, 1e-4 to 2e-3, are far below ours, so they are taken as exact):
    dicts of ``n``, ``height``, ``bounded``, ``fall`` (``None`` where the curve
    lacks a point) and ``source``."""
    out = []
    for n, (curve, source) in PUBLISHED_LOOPS.items():
        eta = np.array(sorted(curve))
        p = np.array([curve[e] for e in eta])
        i, j, bounded = _extremes(eta, p)
        a, b = (curve.get(e) for e in FALL)
        out.append({"n": n, "height": float(p[i] - p[j]), "bounded": bounded,
                    "fall": None if a is None or b is None else a - b,
                    "source": source})
    return out


def report(rows) -> dict:
    """Prints the runs, the loop heights and falls, and the published ones; returns
    ``{N: {"points": ..., "loop": ..., "fall": ...}}``."""
    print(f"  {'N':>6} {'eta':>6} {'start':>8} {'beta P d^2':>18} {'|Psi_6|':>7} "
          f"{'drift of Z':>16} {'drift of |Psi_6|':>16} {'coll/disk':>9} {'s':>6}")
    for r in sorted(rows, key=lambda r: (r["n"], r["packing_fraction"], r["start"])):
        psi_drift = (f"{r['psi6_drift']:+8.4f} +- {r['psi6_drift_error']:.4f}"
                     if "psi6_drift" in r else f"{'':>16}")
        print(f"  {r['n']:6d} {r['packing_fraction']:6.3f} {r['start']:>8} "
              f"{r['pressure']:9.4f} +- {r['pressure_error']:.4f} {r['psi6']:7.3f} "
              f"{r['drift']:+8.4f} +- {r['drift_error']:.4f} {psi_drift} "
              f"{r['collisions_per_disk']:9.0f} {r['seconds']:6.0f}")
    a, b = FALL
    summary = {}
    for n, points in combine(rows).items():
        loop = loop_height(points) if len(points) >= 3 else None
        drop = fall(points)
        summary[n] = {"points": points, "loop": loop, "fall": drop}
        if loop is not None:
            print(f"  N = {n}: loop height {loop['height']:.4f} +- {loop['error']:.4f} "
                  f"(maximum at {loop['eta_max']:.3f}, minimum at {loop['eta_min']:.3f}"
                  f"{' or beyond' if loop['bounded'] else ''}; noise bias "
                  f"{loop['bias']:+.4f} or more)")
        if drop is not None:
            print(f"  N = {n}: fall from {a} to {b}: {drop[0]:.4f} +- {drop[1]:.4f}")
        if n in PUBLISHED_LOOPS:
            curve, source = PUBLISHED_LOOPS[n]
            common = [q for q in points if round(q["eta"], 3) in curve]
            if common:
                pulls = [(q["pressure"] - curve[round(q["eta"], 3)]) / q["error"]
                         for q in common]
                summary[n]["pulls"] = pulls
                print(f"  N = {n} against {source} at the same N: chi^2 = "
                      f"{sum(x * x for x in pulls):.1f} for {len(pulls)} points (pulls "
                      + ", ".join(f"{x:+.1f}" for x in pulls) + ")")
    for q in published_loops():
        fall_text = "" if q["fall"] is None else f", fall from {a} to {b}: {q['fall']:.4f}"
        print(f"  published, N = {q['n']}: loop height {q['height']:.4f}"
              f"{' or more' if q['bounded'] else ''}{fall_text} ({q['source']})")
    return summary


def figure(rows, out: Path, fluid=()) -> dict:
    """The figure of the module notes from the rows of one or more sweeps (and, with
    ``fluid``, the rows of an equation-of-state sweep of the command line,
    ``edmd2d sweep examples/eos_full.toml``, for the whole equation of state);
    returns :func:`report`'s summary."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    summary = report(rows)
    fig, axes = plt.subplots(2, 3, figsize=(18, 10.5))
    (ax, ax_psi, ax_h), (ax_t, ax_eos, ax_snap) = axes
    for (n, data), style in zip(BERNARD_KRAUTH_2011.items(), ("C7-", "C7--")):
        ax.plot(list(data), list(data.values()), style, lw=1,
                label=f"Bernard & Krauth 2011, N = {int(math.isqrt(n))}$^2$")
    ax.plot(list(LI_2022_870), list(LI_2022_870.values()), "C7:", lw=1,
            label="Li et al. 2022, N = 870")
    eta_li, p_li = zip(*LI_2022_128.items())
    ax.errorbar(eta_li, [p for p, _ in p_li], [e for _, e in p_li], fmt="s", ms=4,
                color="C2", mfc="none", label="Li et al. 2022, N = 128$^2$")
    sizes = sorted({r["n"] for r in rows})
    for k, n in enumerate(sizes):
        for kind, marker in (("liquid", "o"), ("crystal", "^")):
            sel = sorted((r for r in rows if r["n"] == n and r["start"] == kind),
                         key=lambda r: r["packing_fraction"])
            if not sel:
                continue
            ax.errorbar([r["packing_fraction"] for r in sel], [r["pressure"] for r in sel],
                        [r["pressure_error"] for r in sel], fmt=marker, ms=4,
                        color=_color(k), mfc="none" if kind == "crystal" else None,
                        capsize=2, alpha=0.6)
            ax_psi.errorbar([r["packing_fraction"] for r in sel], [r["psi6"] for r in sel],
                            [r["psi6_error"] for r in sel], fmt=marker, ms=4,
                            color=_color(k), mfc="none" if kind == "crystal" else None,
                            capsize=2, label=f"N = {_size(n)}, {kind} start")
        points = summary[n]["points"]
        ax.errorbar([q["eta"] for q in points], [q["pressure"] for q in points],
                    [q["error"] for q in points], fmt="-", lw=1.5, color=_color(k), capsize=3,
                    label=f"edmd2d, N = {_size(n)} (o liquid, ^ crystal start; line: "
                    "combined)")
    for a in (ax, ax_psi):
        a.axvspan(0.700, 0.716, color="0.92", zorder=0)
        a.set_xlabel(r"packing fraction $\eta$")
    ax.set_xlim(0.688, 0.730)
    ax.set_ylim(8.94, 9.42)
    ax.set_ylabel(r"$\beta P d^2$")
    ax.legend(frameon=False, fontsize=7, loc="upper left")
    ax_psi.set_ylabel(r"$|\Psi_6|$")
    ax_psi.set_ylim(0, 1)
    ax_psi.legend(frameon=False, fontsize=7)

    for q in published_loops():
        ax_h.plot(q["n"], q["height"], "s", color="C7", mfc="none" if q["bounded"] else "C7",
                  ms=6)
        ax_h.annotate(q["source"].replace(" et al.", "").replace(" & ", "-"),
                      (q["n"], q["height"]), fontsize=6, xytext=(5, 3),
                      textcoords="offset points")
        if q["fall"] is not None and q["fall"] > 0:
            ax_h.plot(q["n"], q["fall"], "D", color="C7", mfc="none", ms=5)
    for k, n in enumerate(sizes):
        loop, drop = summary[n]["loop"], summary[n]["fall"]
        if loop is not None:
            ax_h.errorbar(n, loop["height"], loop["error"], fmt="s", color=_color(k),
                          capsize=3, ms=6, mfc="none",
                          label=f"edmd2d, N = {_size(n)}: loop height")
        if drop is not None:
            ax_h.errorbar(n * 1.08, drop[0], drop[1], fmt="D", color=_color(k), capsize=3,
                          ms=5, label=f"edmd2d, N = {_size(n)}: fall {FALL[0]} to {FALL[1]}")
    ax_h.axhline(0.0, color="0.8", lw=0.8)
    ax_h.set_xscale("log")
    ax_h.set_xlabel("N")
    ax_h.set_ylabel(r"in $\beta P d^2$")
    ax_h.set_title("squares: loop height (highest less lowest point; grey open: the "
                   "curve ends at its minimum)\ndiamonds: the fall from "
                   f"{FALL[0]} to {FALL[1]}; grey: published", fontsize=8)
    if any(summary[n]["loop"] is not None or summary[n]["fall"] is not None
           for n in sizes):
        ax_h.legend(frameon=False, fontsize=7)
    series(ax_t, rows)
    equation_of_state(ax_eos, summary, fluid)
    snapshot(ax_snap, rows)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return summary


def main(out: Path, directory: Path, scheduler=None, workers=None):
    """Runs (or resumes) the sweep, prints its table and loop heights, and draws the
    figure; returns the rows."""
    result = run_sweep(directory, scheduler, workers)
    rows = table(result)
    if not rows:
        print(f"no point finished; nothing to draw (the sweep is in {directory})")
        return rows
    figure(rows, out)
    (directory / "summary.json").write_text(json.dumps(rows, indent=1))
    print(f"wrote {out} and {directory / 'results.csv'}")
    return rows


def plot(out: Path, directories) -> list[dict]:
    """The figure of finished sweeps (of any sizes, or a sweep still running: its
    finished points, and an equation-of-state sweep of the command line for the
    whole equation of state), without running anything, and the combined points in
    ``OUT.csv``; returns the rows of this example's points."""
    from edmd2d import ensemble

    rows, fluid = [], []
    for directory in dict.fromkeys(Path(d).resolve() for d in directories):
        for row in table(ensemble.load(directory)):
            if "start" in row:
                rows.append(row)
            elif {"Z", "Z_error", "packing_fraction", "n"} <= row.keys():
                fluid.append(row)  # an equation-of-state sweep of the command line
            else:
                print(f"  {directory}: {row['task']} is neither a point of this example "
                      "nor of an equation-of-state sweep; left out")
    if not rows:
        raise SystemExit(f"no finished point of this example in "
                         f"{', '.join(map(str, directories))}")
    rows = drop_continued(rows)
    summary = figure(rows, out, fluid)
    csv = out.with_suffix(".csv")
    with csv.open("w") as f:
        f.write("n,packing_fraction,pressure,pressure_error,runs,psi6\n")
        for n, entry in summary.items():
            for q in entry["points"]:
                f.write(f"{n},{q['eta']:.3f},{q['pressure']:.5f},{q['error']:.5f},"
                        f"{q['runs']},{q['psi6']:.4f}\n")
    print(f"wrote {out} and {csv}")
    return rows


def drop_continued(rows) -> list[dict]:
    """The rows without those of runs that another row continued: a run whose
    checkpoint was carried into a sweep of more windows (to run it longer) appears in
    both sweeps, its windows in the shorter one the first windows of the longer one;
    only the longer is kept, so that no window is counted twice."""
    windows = {}
    for r in rows:
        state = Path(r["state"])
        windows[r["state"]] = (ed.checkpoint.read_metadata(state)["z"]
                               if state.exists() else None)
    kept = []
    for r in rows:
        mine = windows[r["state"]]
        continued = mine is not None and any(
            o is not r and o["n"] == r["n"] and o["start"] == r["start"]
            and o["packing_fraction"] == r["packing_fraction"]
            and windows[o["state"]] is not None
            and len(windows[o["state"]]) > len(mine)
            and windows[o["state"]][:len(mine)] == mine for o in rows)
        if continued:
            print(f"  {r['task']} ({r['state']}) was continued in another sweep: "
                  "its longer run is kept")
        else:
            kept.append(r)
    return kept


def _color(k: int) -> str:
    """A colour per system size ``k``."""
    return ("C0", "C1", "C3", "C4", "C5")[k % 5]


def _size(n: int) -> str:
    """``64$^2$`` for a square number of disks, else the number."""
    k = math.isqrt(n)
    return f"{k}$^2$" if k * k == n else str(n)


def series(ax, rows, low: float = 0.710, high: float = 0.718):
    """The pressure of every window against the collisions per disk so far, for the
    runs at ``low <= eta <= high`` of one size, the longest run of each packing
    fraction and start: how the starts approach each other (dotted: the end of each
    run's equilibration).  The size is the one with runs from both starts there,
    then the longest runs, then the most disks."""
    near = [r for r in rows if low - 1e-9 <= r["packing_fraction"] <= high + 1e-9
            and Path(r["state"]).exists()]
    if not near:
        ax.set_axis_off()
        return

    def rank(n):
        runs = [r for r in near if r["n"] == n]
        return (len({r["start"] for r in runs}),
                max(r["collisions_per_disk"] for r in runs), n)

    n = max({r["n"] for r in near}, key=rank)
    longest: dict = {}
    for r in near:
        key = (r["packing_fraction"], r["start"])
        if r["n"] == n and (key not in longest or r["collisions_per_disk"]
                            > longest[key]["collisions_per_disk"]):
            longest[key] = r
    etas = sorted({eta for eta, _ in longest})
    for _, r in sorted(longest.items(), key=lambda item: (item[0][1], item[0][0])):
        record = ed.checkpoint.read_metadata(r["state"])
        p = np.array(record["z"]) * rho_d2(r["packing_fraction"])
        color = f"C{etas.index(r['packing_fraction'])}"
        ax.plot(record["collisions"], p, "-" if r["start"] == "liquid" else "--",
                color=color, marker="o" if r["start"] == "liquid" else "^", ms=3, lw=1,
                label=f"$\\eta$ = {r['packing_fraction']:.3f}, {r['start']} start")
        ax.axvline(record["collisions"][_windows_eq(r) - 1], color=color, ls=":", lw=1)
    ax.set_xlabel("collisions per disk")
    ax.set_ylabel(r"$\beta P d^2$ of each window")
    ax.set_title(f"N = {_size(n)}: the windows of the runs near the minimum", fontsize=9)
    ax.legend(frameon=False, fontsize=7)


def equation_of_state(ax, summary, fluid):
    """``Z`` from the dilute gas to the solid: the fluid sweep's points (mean of its
    replicas) and this example's combined points, against Henderson's equation of
    state and the free-volume cell theory of the solid, ``Z = 1 / (1 - sqrt(eta /
    eta_cp))``."""
    if not fluid:
        ax.set_axis_off()
        return
    from edmd2d import theory

    for k, n in enumerate(sorted({r["n"] for r in fluid})):
        by_eta: dict = {}
        for r in fluid:
            if r["n"] == n:
                by_eta.setdefault(round(r["packing_fraction"], 6), []).append(r)
        eta = np.array(sorted(by_eta))
        z = [_mean([r["Z"] for r in by_eta[e]], [r["Z_error"] for r in by_eta[e]])
             for e in eta]
        ax.errorbar(eta, [v for v, _ in z], [e for _, e in z], fmt="ov^s"[k % 4], ms=4,
                    color="k", mfc="none" if k else "k",
                    label=f"edmd2d fluid sweep, N = {n}")
    for k, (n, entry) in enumerate(sorted(summary.items())):
        q = entry["points"]
        ax.errorbar([p["eta"] for p in q], [p["pressure"] / rho_d2(p["eta"]) for p in q],
                    [p["error"] / rho_d2(p["eta"]) for p in q], fmt="o", ms=3,
                    color=_color(k), label=f"edmd2d melting sweep, N = {_size(n)}")
    x = np.linspace(0.01, 0.73, 300)
    ax.plot(x, theory.henderson_z(x), "C7-", lw=1, label="Henderson (fluid)")
    x = np.linspace(0.69, 0.75, 50)
    ax.plot(x, 1.0 / (1.0 - np.sqrt(x / theory.ETA_CLOSE_PACKED)), "C7--", lw=1,
            label=r"free volume $1/(1-\sqrt{\eta/\eta_{cp}})$ (solid)")
    ax.set_xlabel(r"packing fraction $\eta$")
    ax.set_ylabel(r"$Z = \beta P / \rho$")
    ax.set_xlim(0, 0.74)
    ax.set_ylim(0, 12)
    ax.legend(frameon=False, fontsize=7, loc="upper left")
    ax.set_title("the whole equation of state", fontsize=9)


def snapshot(ax, rows):
    """The final state of the point nearest the middle of the coexistence region (the
    largest N, a liquid start if there is one), each disk coloured by the phase of its
    local psi_6."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection

    rows = [r for r in rows if Path(r["state"]).exists()]
    if not rows:
        ax.set_axis_off()
        return
    n = max(r["n"] for r in rows)
    pick = min((r for r in rows if r["n"] == n),
               key=lambda r: (abs(r["packing_fraction"] - 0.708), r["start"] != "liquid"))
    sim = ed.checkpoint.load(pick["state"])
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
    ax.set_title(f"N = {_size(sim.n)}, $\\eta$ = {pick['packing_fraction']:.3f}, "
                 f"{pick['start']} start: phase of local $\\psi_6$", fontsize=9)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = Path(__file__).parent / "output" / "hard_disk_melting.png"
    parser.add_argument("out", nargs="?", type=Path, default=default,
                        help=f"the figure to write (default {default})")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true", help="64^2 disks, 6 points (default)")
    mode.add_argument("--full", action="store_true", help="64^2 and 128^2, 18 packing "
                      "fractions, liquid and crystal starts (~10 core-hours; resumable)")
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
    mode.add_argument("--plot", type=Path, nargs="+", metavar="SWEEP", default=None,
                      help="run nothing: draw the figure and write the table (OUT.csv) "
                      "from the finished points of these sweeps (several sizes, or a "
                      "sweep still running)")
    args = parser.parse_args()
    if args.plot is not None:
        given = [name for name in ("n", "etas", "starts", "collisions", "scheduler",
                                   "workers", "sweep") if getattr(args, name) is not None]
        if given:
            parser.error(f"--plot runs nothing: --{given[0]} cannot be given with it")
        for directory in args.plot:
            if directory.suffix in (".png", ".pdf", ".svg"):
                parser.error(f"--plot: {directory} looks like the figure; give it "
                             "first (OUT.png --plot SWEEP ...)")
            if not (directory / "results.json").exists():
                parser.error(f"--plot: {directory} holds no sweep (no results.json)")
        plot(args.out, args.plot)
        raise SystemExit(0)
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
