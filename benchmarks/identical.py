"""Check that two (or more) versions of edmd2d give bit-identical results.

A change to the engine that is meant to keep its physics (a restructuring, a speed-up)
must leave every event and every number exactly as it was.  This script runs the same
systems in each git revision (exported like ``ab.py`` does, each in a fresh process
with its own numba cache) and compares, bit for bit, the event log (time, kind, disks),
the final positions, velocities, unwrapped positions, counts and accumulated impulses:

    python benchmarks/identical.py HEAD~1 HEAD

The systems: 48 small random systems of every box kind (periodic, walled, mixed) with
and without wall segments and a fixed peg, run to t = 3; a 2 000-disk gas with the
lookahead forced on (it is a hint and must change nothing); a walled gas in a polygon
container; and a 10^4-disk periodic gas run for 20 collisions per disk (which includes
a Z-order re-sort of the rows).  Then each physics family, alone and combined, compared
on the engine's whole state row table, its tallies and the physics model's per-disk
state besides the above: gravity (elastic, and inelastic with a wall restitution, where
disks come to rest on the floor; small random walled systems with a fixed peg), restitution
with the TC model (a scalar coefficient, and a table of two species with wall segments),
the thermostat (elastic and inelastic), heated box walls and segments, all of them at
once, and growth (a growing gas, and a compression by ``edmd2d.compress``).
Exit status 1 if any digest differs.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ab import export  # noqa: E402

_CHILD = r"""
import hashlib, json
import numpy as np
import edmd2d as ed

def random_system(rng, n, box, walls):
    pos, rad = [], []
    for _ in range(20000):
        if len(pos) == n:
            break
        r = rng.uniform(0.3, 0.6)
        p = rng.uniform([0.0, 0.0], [box.width, box.height])
        if any(not box.periodic[a] and not (r < p[a] < box.size[a] - r) for a in range(2)):
            continue
        if pos:
            d = np.array(pos) - p
            for a in range(2):
                if box.periodic[a]:
                    d[:, a] -= box.size[a] * np.round(d[:, a] / box.size[a])
            if (np.hypot(*d.T) < np.array(rad) + r).any():
                continue
        ok = True
        for w in walls:
            a, b = np.array(w.start), np.array(w.end)
            u = b - a
            s = np.clip((p - a) @ u / (u @ u), 0.0, 1.0)
            if np.hypot(*(p - a - s * u)) < r:
                ok = False
        if ok:
            pos.append(p)
            rad.append(r)
    pos = np.array(pos)
    return pos, rng.normal(size=(len(pos), 2)), np.array(rad), rng.uniform(0.5, 2.0, len(pos))

def digest(sim):
    h = hashlib.sha256()
    for ev in sim._recorded_events():
        if ev[1] not in ("rest", "wake"):  # (streamed by later versions only)
            h.update(repr(ev).encode())
    # (The counts by name: a count added later, 0 here, must not change the digest.)
    c = sim.counts
    counts = [c.collisions, c.wall_collisions, c.cell_crossings, c.events, c.stale]
    for arr in (sim.positions, sim.velocities, sim.unwrapped_positions, np.array(counts)):
        h.update(np.ascontiguousarray(arr).tobytes())
    acc = sim._accumulators()
    for key in ("virial", "virial_xx", "virial_yy", "box_impulse", "segment_impulse"):
        h.update(np.asarray(acc[key], np.float64).tobytes())
    h.update(repr(sim.time).encode())
    return h.hexdigest()

out = {}
kinds = [(True, True), (False, False), (True, False), (False, True)]
for seed in range(48):
    rng = np.random.default_rng(seed)
    box = ed.Box(rng.uniform(2.5, 7.0), rng.uniform(2.5, 7.0), periodic=kinds[seed % 4])
    w, hgt = box.width, box.height
    walls = [[], [ed.Wall((0.5 * w, 0.25 * hgt), (0.5 * w, 0.75 * hgt))],
             ed.Wall.polygon([(0.2 * w, 0.2 * hgt), (0.45 * w, 0.25 * hgt),
                              (0.3 * w, 0.45 * hgt)])][seed % 3]
    pos, vel, rad, mass = random_system(rng, int(rng.integers(2, 10)), box, walls)
    if seed % 5 == 0 and len(pos) > 2:
        mass[0] = np.inf
        vel[0] = 0.0
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls)
    sim._record_events(100_000)
    sim.advance(until=3.0)
    out[f"small-{seed}"] = digest(sim)

sim = ed.make_gas(2000, 0.5, seed=3)
sim._qs[8] = 1  # the queue's LOOKAHEAD flag: forced on for a small system
sim._record_events(200_000)
sim.advance(collisions=40_000)
out["lookahead-2000"] = digest(sim)

box = ed.Box(30.0, 30.0, periodic=False)
walls = ed.Wall.polygon([(1.0, 1.0), (29.0, 2.0), (28.0, 29.0), (2.0, 28.0)])
g = ed.make_gas(120, 0.3, periodic=False, seed=4)
pos = g.positions + [0.5 * (30.0 - g.box.width), 0.5 * (30.0 - g.box.height)]
sim = ed.Simulation(pos, g.velocities, g.radii, box=box, walls=walls)
sim._record_events(200_000)
sim.advance(collisions=30_000)
out["polygon-120"] = digest(sim)

sim = ed.make_gas(10_000, 0.5, seed=1)
sim._record_events(300_000)
sim.advance(collisions=200_000)
out["gas-10000"] = digest(sim)

def physics_digest(sim):
    # Besides digest(): the whole state rows (with the supports under gravity), every
    # tally, and the model's per-disk state and random stream.
    h = hashlib.sha256(digest(sim).encode())
    # (The first five counts and 14 accumulators; one added later enters only where
    # it is not 0.  The off-diagonal virial, acc[15], is summed at every collision
    # where it exists, so it is left out, to compare with revisions before it.)
    counts = np.asarray(sim._counts)
    acc = np.asarray(sim._acc)
    wacc = np.asarray(sim._wacc)
    # (Likewise the segments' first seven tallies; the work of moving ones, column 7
    # and acc[16], enters only where it is not 0.)
    extra = [a for a in (counts[5:], acc[14:15], acc[16:], wacc[:, 7:]) if a.any()]
    for arr in (sim._S, acc[:14], wacc[:, :7], counts[:5], *extra):
        h.update(np.ascontiguousarray(arr).tobytes())
    m = sim._model
    if m is not None:
        for arr in (m.t_last, m.streak, m.thermo, m.cursor, m.buffer):
            h.update(np.ascontiguousarray(arr).tobytes())
    return h.hexdigest()

def run_physics(name, sim, **advance):
    # (An inelastic collapse under gravity, a disk at rest on a disk, stops the run with
    # the state as it was before that event: a result to compare like any other.)
    sim._record_events(200_000)
    try:
        sim.advance(**advance)
        stop = ""
    except RuntimeError as exc:
        stop = str(exc)
    out[name] = hashlib.sha256((physics_digest(sim) + stop).encode()).hexdigest()

# Inelastic disks under gravity come to rest where the engine has that (on by default
# there): these systems compare the runs without it, which must not change.
NO_REST = {"resting": False} if "resting" in getattr(ed, "physics", ed).__dict__.get(
    "KEYWORDS", {}) else {}

def walled(**kw):
    return ed.make_gas(300, 0.3, periodic=False, **kw)

run_physics("gravity", walled(gravity=(0.0, -1.0), seed=5), collisions=20_000)
run_physics("gravity-tilted", ed.make_gas(300, 0.3, periodic=(True, False),
            gravity=(0.3, -2.0), seed=6), collisions=20_000)
run_physics("gravity-inelastic", walled(gravity=(0.0, -1.0), restitution=0.8,
            wall_restitution=0.7, seed=7, **NO_REST), collisions=20_000)
run_physics("restitution-tc", ed.make_gas(500, 0.4, restitution=0.9, tc=1e-3, seed=8),
            collisions=20_000)
g = ed.make_gas(300, 0.3, periodic=False, seed=9)
w, hgt = g.box.width, g.box.height
seg = [ed.Wall((0.5 * w, 0.3 * hgt), (0.5 * w, 0.7 * hgt))]
keep = [k for k in range(len(g)) if abs(g.positions[k, 0] - 0.5 * w) > 1.0]
table = np.array([[0.95, 0.8], [0.8, 0.6]])
run_physics("restitution-table", ed.Simulation(
    g.positions[keep], g.velocities[keep], g.radii[keep], box=g.box, walls=seg,
    species=np.arange(len(keep)) % 2, restitution=table, wall_restitution=0.9, tc=1e-4),
    collisions=20_000)
run_physics("thermostat", ed.make_gas(400, 0.35, thermostat=(1.5, 0.05), seed=10),
            collisions=20_000)
run_physics("thermostat-inelastic", ed.make_gas(400, 0.35, thermostat=(1.0, 0.1),
            restitution=0.9, seed=11), collisions=20_000)
run_physics("heated-walls", walled(wall_temperatures={"left": 2.0, "right": 0.5},
            seed=12), collisions=20_000)
g = walled(seed=13)
keep = [k for k in range(len(g)) if abs(g.positions[k, 0] - 0.5 * w) > 1.0]
run_physics("heated-segment", ed.Simulation(
    g.positions[keep], g.velocities[keep], g.radii[keep], box=g.box, walls=seg,
    wall_temperatures={0: 1.5, "bottom": 2.0}, seed=14), collisions=20_000)
run_physics("everything", walled(gravity=(0.0, -0.5), restitution=0.9,
            wall_restitution=0.8, wall_temperatures={"bottom": 3.0},
            thermostat=(1.0, 0.02), seed=15, **NO_REST), collisions=20_000)
for seed in range(12):
    rng = np.random.default_rng(100 + seed)
    box = ed.Box(rng.uniform(3.0, 7.0), rng.uniform(3.0, 7.0), periodic=(seed % 2 == 0, False))
    pos, vel, rad, mass = random_system(rng, int(rng.integers(3, 10)), box, [])
    mass[0] = np.inf  # a fixed peg: a parabola against a point
    vel[0] = 0.0
    e = 1.0 if seed % 3 == 0 else 0.85
    run_physics(f"gravity-small-{seed}", ed.Simulation(
        pos, vel, rad, mass, box=box, gravity=(0.2 * (seed % 4 - 1.5), -1.0),
        restitution=e, wall_restitution=e, **(NO_REST if e < 1.0 else {})), until=20.0)
g = ed.make_gas(400, 0.3, seed=16)
run_physics("growth", ed.Simulation(g.positions, g.velocities, g.radii, box=g.box,
            growth=2e-3), collisions=20_000)
g = walled(seed=17)
keep = [k for k in range(len(g)) if abs(g.positions[k, 0] - 0.5 * w) > 1.0]
run_physics("growth-walled", ed.Simulation(
    g.positions[keep], g.velocities[keep], g.radii[keep], box=g.box, walls=seg,
    growth=1e-3), collisions=20_000)
res = ed.compress(ed.make_gas(200, 0.3, seed=18), 0.6, rate=0.01)
h = hashlib.sha256()
for arr in (res.times, res.packing_fractions, res.reduced_pressures, res.temperatures,
            res.collisions, res.simulation.positions, res.simulation.velocities,
            res.simulation.radii):
    h.update(np.ascontiguousarray(arr).tobytes())
out["compress"] = h.hexdigest()
print(json.dumps(out))
"""


def digests(tree: Path) -> dict:
    """Digest of each system's results, run by the edmd2d tree ``tree``."""
    env = dict(os.environ, PYTHONPATH=str(tree / "src"), NUMBA_CACHE_DIR=str(tree / "nc"))
    proc = subprocess.run([sys.executable, "-c", _CHILD], env=env, check=False, capture_output=True,
                          text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"the systems failed to run in {tree}:\n{proc.stderr[-3000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("revisions", nargs="+", help="git revisions to compare (two or more)")
    args = ap.parse_args(argv)
    if len(args.revisions) < 2:
        ap.error("give at least two revisions")
    with tempfile.TemporaryDirectory() as tmp:
        results = {rev: digests(export(rev, Path(tmp))) for rev in args.revisions}
    first, *others = args.revisions
    bad = 0
    for name in results[first]:
        values = {rev: results[rev].get(name) for rev in args.revisions}
        same = len(set(values.values())) == 1
        bad += not same
        print(f"{name:>20}  {'identical' if same else 'DIFFERENT'}  {values[first][:16]}")
    print(f"{len(results[first]) - bad} of {len(results[first])} systems bit-identical "
          f"across {', '.join(args.revisions)}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
