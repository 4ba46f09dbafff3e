"""Side-by-side comparisons: edmd2d against the reference engine, billiards and pymunk.

Every comparison starts both codes from the *same* equilibrated state (built with
``make_gas`` and run by edmd2d for a few collisions per disk), and times edmd2d on that
same state with the same budget, so that each ratio compares like with like.

reference
    ``edmd2d.reference.ReferenceSimulation``, the brute-force oracle (every pair and
    every periodic image at every event: O(N^2) per event), in the same periodic box
    as the scaling suite.  Disk-disk collisions per second.
billiards
    python-billiards (event driven, exact, an O(N) update per event in Python with
    numpy), in a walled box: it has no periodic boundaries, so the box walls are four
    ``InfiniteWall`` obstacles and edmd2d runs the same walled box.  Collisions per
    second.
pymunk
    Chipmunk2D through pymunk: a time-stepped rigid-body engine, so "collisions per
    second" is not defined and physical time simulated per wall-clock second is
    compared instead, in the same walled box.  Equal accuracy is taken to mean that the
    time step resolves the mean free flight: ``dt = tau / k`` with ``tau`` the mean
    time between two collisions of a disk (measured by edmd2d on the same state) and
    ``k`` steps per free flight (10 = the headline; 100 where listed).  Disks: circles
    with elasticity 1, friction 0 and infinite moment of inertia (no rotation), no
    gravity or damping; the walls are static segments, thick enough that nothing
    tunnels; ``collision_slop`` (the overlap pymunk tolerates on purpose, 0.1 length
    units by default) is set to 0.001 diameter; the default bounding-box-tree index
    (faster than the spatial hash here).  Being time stepped, pymunk lets disks overlap:
    at sampled times (outside the timed part) we count the pairs closer than 0.99
    diameter and record the deepest overlap and the drift of the kinetic energy.

A peer that is not installed is skipped with a message (``pip install -e ".[bench]"``
installs both).
"""

from __future__ import annotations

import math
import time

import numpy as np
from timing import run_for, stats, time_advance

import edmd2d as ed
from edmd2d.reference import ReferenceSimulation

EQUILIBRATE_PER_DISK = 5


def equilibrated(n: int, packing: float, *, periodic: bool, seed: int):
    """A gas after ``EQUILIBRATE_PER_DISK`` collisions per disk, and its state."""
    sim = ed.make_gas(n, packing, periodic=periodic, seed=seed)
    sim.advance(collisions=EQUILIBRATE_PER_DISK * n)
    state = {
        "positions": sim.positions,
        "velocities": sim.velocities,
        "radii": sim.radii,
        "masses": sim.masses,
        "box": sim.box,
    }
    return sim, state


def _edmd_rates(state: dict, seconds: float, repeats: int = 3) -> dict:
    """edmd2d collision rate and physical time per second from ``state``."""
    sim = ed.Simulation(**state)
    n = len(sim)
    probe = time_advance(sim, 2 * n)  # untimed: sizes the timed runs
    per_run = max(1000, int(probe["collisions"] / probe["seconds"] * seconds / repeats))
    runs = [time_advance(sim, per_run) for _ in range(repeats)]
    coll = sum(r["collisions"] for r in runs)
    phys = sum(r["physical_time"] for r in runs)
    return {
        "collisions_per_s": stats(r["collisions"] / r["seconds"] for r in runs),
        "physical_time_per_s": stats(r["physical_time"] / r["seconds"] for r in runs),
        # mean time between two collisions of one disk: each collision involves two
        "mean_free_time": n * phys / (2.0 * coll),
        "collisions_per_unit_time": coll / phys,
    }


def _missing(name: str) -> dict | None:
    try:
        __import__(name)
    except ImportError:
        return {"skipped": f"{name} is not installed (pip install -e \".[bench]\")"}
    return None


# ---------------------------------------------------------------------- reference
def vs_reference(n: int, packing: float, *, seconds: float, seed: int) -> dict:
    """Collisions per second of the brute-force reference and of edmd2d, periodic box."""
    _, state = equilibrated(n, packing, periodic=True, seed=seed)
    ref = ReferenceSimulation(**state)

    def one_collision() -> int:
        ref.advance(collisions=1)
        return 1

    done, elapsed = run_for(one_collision, seconds)
    ref_rate = done / elapsed
    edmd = _edmd_rates(state, min(seconds, 1.0))
    return {
        "n": n,
        "packing": packing,
        "box": "periodic",
        "reference_collisions": done,
        "reference_seconds": elapsed,
        "reference_collisions_per_s": ref_rate,
        "edmd2d_collisions_per_s": edmd["collisions_per_s"],
        "ratio": edmd["collisions_per_s"]["median"] / ref_rate,
    }


# ---------------------------------------------------------------------- billiards
def vs_billiards(n: int, packing: float, *, seconds: float, seed: int) -> dict:
    """Collisions per second of python-billiards and of edmd2d, walled box."""
    skip = _missing("billiards")
    if skip:
        return skip
    import billiards

    _, state = equilibrated(n, packing, periodic=False, seed=seed)
    edmd = _edmd_rates(state, min(seconds, 1.0))
    w, h = state["box"].width, state["box"].height
    # The box walls, counter-clockwise, so the inside is on the left of each.
    corners = [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)]
    walls = [billiards.InfiniteWall(corners[k], corners[(k + 1) % 4], inside="left")
             for k in range(4)]
    table = billiards.Billiard(obstacles=walls)
    t0 = time.perf_counter()
    for p, v, r, m in zip(state["positions"], state["velocities"], state["radii"],
                          state["masses"]):
        table.add_ball(p, v, radius=float(r), mass=float(m))
    setup_s = time.perf_counter() - t0
    # Evolve in slices of about 20 disk-disk collisions (from edmd2d's rate on this state).
    dt = 20.0 / edmd["collisions_per_unit_time"]

    def one_slice() -> int:
        events = table.evolve(table.time + dt)
        return sum(1 for e in events if isinstance(e[2], (int, np.integer)))

    try:
        done, elapsed = run_for(one_slice, seconds)
    except AssertionError as exc:  # billiards asserts its own invariants
        return {"n": n, "packing": packing, "error": f"billiards failed: {exc!r}"}
    rate = done / elapsed
    return {
        "n": n,
        "packing": packing,
        "box": "walled",
        "billiards_setup_s": setup_s,
        "billiards_collisions": done,
        "billiards_seconds": elapsed,
        "billiards_collisions_per_s": rate,
        "edmd2d_collisions_per_s": edmd["collisions_per_s"],
        "ratio": edmd["collisions_per_s"]["median"] / rate if rate > 0 else math.inf,
    }


# ---------------------------------------------------------------------- pymunk
def _pymunk_space(state: dict, slop_fraction: float = 1e-3):
    import pymunk

    space = pymunk.Space()
    space.gravity = (0.0, 0.0)
    dmax = 2.0 * float(np.max(state["radii"]))
    space.collision_slop = slop_fraction * dmax
    bodies = []
    for p, v, r, m in zip(state["positions"], state["velocities"], state["radii"],
                          state["masses"]):
        body = pymunk.Body(float(m), math.inf)
        body.position = (float(p[0]), float(p[1]))
        body.velocity = (float(v[0]), float(v[1]))
        shape = pymunk.Circle(body, float(r))
        shape.elasticity = 1.0
        shape.friction = 0.0
        space.add(body, shape)
        bodies.append(body)
    # Thick static segments whose inner surfaces are the box sides.
    w, h, t = state["box"].width, state["box"].height, dmax
    ends = [(-t, -t), (w + t, -t), (w + t, h + t), (-t, h + t)]
    for k in range(4):
        seg = pymunk.Segment(space.static_body, ends[k], ends[(k + 1) % 4], t)
        seg.elasticity = 1.0
        seg.friction = 0.0
        space.add(seg)
    return space, bodies


def _pymunk_sample(bodies, masses, diameter: float, box) -> dict:
    from scipy.spatial import cKDTree

    pos = np.array([tuple(b.position) for b in bodies])
    vel = np.array([tuple(b.velocity) for b in bodies])
    pairs = np.array(sorted(cKDTree(pos).query_pairs(diameter)), dtype=np.int64)
    dist = np.zeros(0)
    if len(pairs):
        dist = np.linalg.norm(pos[pairs[:, 0]] - pos[pairs[:, 1]], axis=1)
    depth = float(1.0 - dist.min() / diameter) if len(dist) else 0.0
    outside = int(np.sum((pos[:, 0] < 0) | (pos[:, 0] > box.width)
                         | (pos[:, 1] < 0) | (pos[:, 1] > box.height)))
    return {
        "overlapping_pairs": int(np.sum(dist < 0.99 * diameter)),
        "touching_or_overlapping_pairs": len(dist),
        "deepest_overlap": max(depth, 0.0),
        "outside_box": outside,
        "kinetic_energy": float(0.5 * np.sum(masses[:, None] * vel**2)),
    }


def vs_pymunk(n: int, packing: float, *, steps_per_free_time: int, seconds: float,
              seed: int, samples: int = 10) -> dict:
    """Physical time per wall-clock second of pymunk and of edmd2d, walled box."""
    skip = _missing("pymunk")
    if skip:
        return skip
    _, state = equilibrated(n, packing, periodic=False, seed=seed)
    edmd = _edmd_rates(state, min(seconds, 1.0))
    tau = edmd["mean_free_time"]
    dt = tau / steps_per_free_time
    space, bodies = _pymunk_space(state)
    masses = np.asarray(state["masses"], dtype=float)
    diameter = 2.0 * float(np.max(state["radii"]))
    ke0 = _pymunk_sample(bodies, masses, diameter, state["box"])["kinetic_energy"]
    batch = 10
    steps, timed, sampled = 0, 0.0, []
    while timed < seconds:
        t0 = time.perf_counter()
        for _ in range(batch):
            space.step(dt)
        timed += time.perf_counter() - t0
        steps += batch
        if timed >= seconds * (len(sampled) + 1) / samples:  # untimed
            sampled.append(_pymunk_sample(bodies, masses, diameter, state["box"]))
    pairs = [s["overlapping_pairs"] for s in sampled]
    phys_rate = steps * dt / timed
    return {
        "n": n,
        "packing": packing,
        "box": "walled",
        "mean_free_time": tau,
        "steps_per_free_time": steps_per_free_time,
        "dt": dt,
        "pymunk_steps": steps,
        "pymunk_seconds": timed,
        "pymunk_physical_time_per_s": phys_rate,
        "pymunk_steps_per_s": steps / timed,
        "overlapping_pairs_mean": float(np.mean(pairs)),
        "overlapping_pairs_max": int(np.max(pairs)),
        "overlapping_pairs_per_disk": float(np.mean(pairs)) / n,
        "pairs_closer_than_diameter_mean": float(np.mean(
            [s["touching_or_overlapping_pairs"] for s in sampled])),
        "deepest_overlap": max(s["deepest_overlap"] for s in sampled),
        "outside_box_max": max(s["outside_box"] for s in sampled),
        "kinetic_energy_drift": sampled[-1]["kinetic_energy"] / ke0 - 1.0,
        "samples": len(sampled),
        "edmd2d_physical_time_per_s": edmd["physical_time_per_s"],
        "ratio": edmd["physical_time_per_s"]["median"] / phys_rate,
    }
