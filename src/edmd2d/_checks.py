"""The checks of disks against their box, its walls and gravity that a simulation's
constructor and its ``set_*`` methods share: each raises a ``ValueError`` that names
the offending disks."""

from __future__ import annotations

import numpy as np

from ._sums import dot
from ._validate import as_float_array, indices_where

# Relative tolerance for "touching is fine, overlapping is not" in the input checks:
# lattices built by arithmetic touch to within rounding, and the engine copes with a
# rounding-sized overlap (an approaching overlapped pair collides at once).
OVERLAP_TOL = 1e-9


def check_in_box(box, pos: np.ndarray, rad: np.ndarray) -> np.ndarray:
    """``pos``, every centre inside ``box`` and every disk clear of its walls; on a
    periodic axis a centre at ``x = width`` becomes 0 (in place)."""
    for axis, length in enumerate((box.width, box.height)):
        name = "xy"[axis]
        coord = pos[:, axis]
        outside = (coord < 0) | (coord > length)
        if outside.any():
            raise ValueError(
                f"positions: disks {indices_where(outside)} lie outside the box "
                f"(0 <= {name} <= {length})"
            )
        if box.periodic[axis]:
            coord[coord == length] = 0.0
        else:
            lo = coord < rad * (1 - OVERLAP_TOL)
            hi = coord > length - rad * (1 - OVERLAP_TOL)
            if (lo | hi).any():
                raise ValueError(
                    f"positions: disks {indices_where(lo | hi)} overlap the box wall "
                    f"on the {name} axis (need radius <= {name} <= {length} - radius)"
                )
    return pos


def check_room(box, vel: np.ndarray, rad: np.ndarray) -> None:
    """A disk as wide as the box between two walls cannot move across it: it would
    bounce from wall to wall with no time in between, without end."""
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            continue
        stuck = (2.0 * rad >= length * (1 - OVERLAP_TOL)) & (vel[:, axis] != 0.0)
        if stuck.any():
            name = "xy"[axis]
            raise ValueError(
                f"velocities: disks {indices_where(stuck)} fill the box between its "
                f"walls on the {name} axis (diameter >= {length}) and cannot move "
                f"along {name}; their {name}-velocity must be 0"
            )


def check_periodic_room(box, rad: np.ndarray) -> None:
    """A periodic axis is at least one largest diameter long."""
    dmax = 2.0 * float(rad.max())
    for axis, length in (("width", box.width), ("height", box.height)):
        periodic = box.periodic[0 if axis == "width" else 1]
        if periodic and length < dmax:
            raise ValueError(
                f"box {axis} {length} is smaller than the largest disk diameter {dmax}: "
                "on a periodic axis a disk would overlap its own image"
            )


def as_cell_size(cell_size, rad: np.ndarray) -> float | None:
    """``cell_size`` (``None``: the default) as a float, at least the largest diameter."""
    if cell_size is None:
        return None
    dmax = 2.0 * float(rad.max())
    cell_size = float(as_float_array("cell_size", cell_size, ()))
    if not cell_size >= dmax:
        raise ValueError(
            f"cell_size must be at least the largest diameter {dmax}, got {cell_size}"
        )
    return cell_size


def check_grid(grid, rad: np.ndarray, cell_size) -> None:
    """``grid`` is one of "auto", "uniform" and "wide", and "wide" has wide disks to
    list (radii of two sizes at least) and nothing that keeps them out."""
    if not isinstance(grid, str) or grid not in ("auto", "uniform", "wide"):
        raise ValueError(f"grid must be 'auto', 'uniform' or 'wide', got {grid!r}")
    if grid != "wide":
        return
    if cell_size is not None:
        raise ValueError("grid='wide' does not combine with cell_size")
    if float(rad.max()) == float(rad.min()):
        raise ValueError("grid='wide' needs disks of more than one size (the wider ones "
                         "are listed in the cells near them)")


def check_walls_in_box(box, walls) -> None:
    """Every end point of every wall segment lies in the box."""
    w, h = box.width, box.height
    for k, wall in enumerate(walls):
        for pt in (wall.start, wall.end):
            if not (0 <= pt[0] <= w and 0 <= pt[1] <= h):
                raise ValueError(
                    f"walls[{k}] has an end point {pt} outside the box [0, {w}] x [0, {h}]"
                )


def resting(box, walls, gravity, pos: np.ndarray, vel: np.ndarray, rad: np.ndarray,
            mass: np.ndarray, model, what: str = "positions") -> np.ndarray:
    """Under gravity, the box walls each movable disk rests on (bits ``1 << side``,
    see ``layout.S_SUPPORT``): it touches the wall, with zero normal velocity, and
    gravity presses it into the wall.  An inelastic model with ``tc > 0`` holds such
    a disk on the wall (as it would put a disk to rest whose bounces shrink); any
    other model would make it bounce without end at one instant (a resting contact
    is not a motion of free flights and impulses): refused."""
    bits = np.zeros(len(pos), np.int32)
    g = gravity
    if g is None:
        return bits
    movable = np.isfinite(mass)
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis] or g[axis] == 0.0:
            continue
        if g[axis] < 0.0:
            touching = pos[:, axis] - rad <= OVERLAP_TOL * rad
        else:
            touching = length - rad - pos[:, axis] <= OVERLAP_TOL * rad
        still = movable & touching & (vel[:, axis] == 0.0)
        if still.any() and (model is None or model.hold == 0.0):
            name = "xy"[axis]
            wall = f"{name}=0" if g[axis] < 0.0 else f"{name}={length}"
            raise ValueError(
                f"{what}: disks {indices_where(still)} rest on the box wall at "
                f"{wall} with zero {name}-velocity while gravity presses them into "
                "it, which would take unboundedly many bounces at one instant: "
                "lift them by a small gap, give them a velocity, or make them "
                "inelastic (restitution < 1 with tc > 0 lets walls hold them)"
            )
        side = 2 * axis + (0 if g[axis] < 0.0 else 1)
        bits[still] |= 1 << side
    if model is None:
        _check_not_resting_on_obstacles(walls, pos, vel, rad, movable, g, what)
    return bits


def _check_not_resting_on_obstacles(walls, pos, vel, rad, movable, g, what) -> None:
    """Elastic disks under gravity: none may start at rest (no velocity along the
    contact normal) on a wall segment or an immovable disk that gravity presses it
    into; it would bounce without end at one instant.  (Only disks with a zero
    velocity component can, so only they are checked.)"""
    still = np.flatnonzero(movable & ((vel[:, 0] == 0.0) | (vel[:, 1] == 0.0)))
    if len(still) == 0:
        return
    pegs = np.flatnonzero(~movable)
    for i in still:
        normals = []
        for w in walls:
            a, b = np.array(w.start), np.array(w.end)
            u = b - a
            s = np.clip(dot(pos[i] - a, u) / dot(u, u), 0.0, 1.0)
            d = pos[i] - (a + s * u)
            normals.append((d, rad[i]))
        for j in pegs:
            normals.append((pos[i] - pos[j], rad[i] + rad[j]))
        for d, contact in normals:
            dist = float(np.hypot(*d))
            if (dist <= contact * (1.0 + OVERLAP_TOL) and float(dot(vel[i], d)) == 0.0
                    and float(dot(g, d)) < 0.0):
                raise ValueError(
                    f"{what}: disk {i} rests on a wall segment or an immovable "
                    "disk with no velocity along the contact while gravity presses "
                    "it on, which would take unboundedly many bounces at one "
                    "instant: lift it by a small gap or give it a velocity (only "
                    "box walls hold disks at rest)")
