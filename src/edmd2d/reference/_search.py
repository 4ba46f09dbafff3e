"""The brute-force search for the next event: every pair, image, wall and box wall.

Given the disks' state, these functions try every candidate contact with the oracles of
``_times`` and return the earliest, in straight flight (:func:`next_event`) and
under gravity (:func:`next_event_accelerated`, which examines the candidates in order of
a lower bound on their contact time and stops once no later one can come first).  Both
leave out the segments that move (``skip``), which :func:`next_moving_wall_event` then
tries against the earliest of the others.
"""

from __future__ import annotations

import math
from typing import Any

from ..geometry import Translation
from ._times import (
    INF,
    _dot,
    _shift,
    box_contact_time_accelerated,
    circle_contact_time,
    circle_contact_time_accelerated,
    circle_contact_time_growing,
    oscillating_segment_contact_time,
    segment_contact_time,
    segment_contact_time_accelerated,
    translating_segment_contact_time,
)

# An event found: its time, its kind ("disk", "wall", "box"; None if there is none), the
# disk, its partner and the kind's detail of the contact.
Event = tuple[float, str | None, int, int, Any]


def _segment_distance(p, a, b):
    """Distance from the point ``p`` to the segment a-b."""
    u = (b[0] - a[0], b[1] - a[1])
    rel = (p[0] - a[0], p[1] - a[1])
    s = min(max(_dot(rel, u) / _dot(u, u), 0.0), 1.0)
    return math.hypot(rel[0] - s * u[0], rel[1] - s * u[1])


def _earliest(gap, speed, acceleration, scale):
    """A lower bound on the time two bodies ``gap`` apart need to touch, with relative
    speed ``speed`` and acceleration ``acceleration`` (magnitudes): the root of
    ``speed t + acceleration t^2 / 2 = gap``, for a gap cut by ``1e-9 (gap + scale)``
    so that rounding cannot make it too large.  0 for bodies (nearly) in contact."""
    gap -= 1e-9 * (abs(gap) + scale)
    if gap <= 0.0:
        return 0.0
    root = speed + math.sqrt(speed * speed + 2.0 * acceleration * gap)
    return 2.0 * gap / root if root > 0.0 else INF


def next_event(positions, velocities, radii, growth_speeds, walls, box, shifts,
               skip=frozenset()):
    """The earliest contact in straight flight, as ``ReferenceSimulation.next_event``.

    ``growth_speeds`` are the speeds at which the radii grow, or ``None`` without
    growth; ``shifts`` the periodic image shifts to try for each pair and wall:
    ``(dx, dy)``, the image's position less its disk's, or under shear (no walls)
    ``(dx, dy, du)``, the image also moving at ``du`` more along x.  A pair's
    contact through an image comes from their relative position ``p_i - (p_j + shift)``
    and velocity ``v_i - (v_j + (du, 0))``; its detail is the shift.  The segments whose
    indices are in ``skip`` (those that move) are left out.
    """
    best: Event = (INF, None, -1, -1, None)
    n = len(positions)
    for i in range(n):
        for j in range(i + 1, n):
            dv = (velocities[i][0] - velocities[j][0], velocities[i][1] - velocities[j][1])
            for shift in shifts:
                sx, sy = shift[0], shift[1]
                dp = (positions[i][0] - positions[j][0] - sx,
                      positions[i][1] - positions[j][1] - sy)
                rel = dv
                if len(shift) == 3:  # a sheared image: its velocity is v_j + (du, 0)
                    rel = (velocities[i][0] - (velocities[j][0] + shift[2]), dv[1])
                if growth_speeds is None:
                    t = circle_contact_time(dp, rel, radii[i] + radii[j])
                else:
                    t = circle_contact_time_growing(dp, rel, radii[i] + radii[j],
                                                    growth_speeds[i] + growth_speeds[j])
                if t < best[0]:
                    best = (t, "disk", i, j, shift)
        for k, wall in enumerate(walls):
            if k in skip:
                continue
            for sx, sy in shifts:
                a = (wall.start[0] + sx, wall.start[1] + sy)
                b = (wall.end[0] + sx, wall.end[1] + sy)
                t, part = segment_contact_time(positions[i], velocities[i], radii[i], a, b,
                                               None if growth_speeds is None
                                               else growth_speeds[i])
                if t < best[0]:
                    best = (t, "wall", i, k, (part, a, b))
        for axis, length in enumerate((box.width, box.height)):
            if box.periodic[axis]:
                continue
            x, vx, r = positions[i][axis], velocities[i][axis], radii[i]
            if growth_speeds is not None:
                # The rim grows towards both walls: the gaps x - r and
                # length - r - x close at dr - vx and dr + vx.
                dr = growth_speeds[i]
                for t, side in ((max((x - r) / (dr - vx), 0.0) if dr - vx > 0 else INF,
                                 2 * axis),
                                (max((length - r - x) / (dr + vx), 0.0)
                                 if dr + vx > 0 else INF, 2 * axis + 1)):
                    if t < best[0]:
                        best = (t, "box", i, side, None)
                continue
            if vx < 0:
                t, side = max((x - r) / -vx, 0.0), 2 * axis
            elif vx > 0:
                t, side = max((length - r - x) / vx, 0.0), 2 * axis + 1
            else:
                continue
            if t < best[0]:
                best = (t, "box", i, side, None)
    return best


def next_event_accelerated(positions, velocities, radii, acc, walls, box, shifts,
                           skip=frozenset()):
    """:func:`next_event` under gravity, ``acc`` each disk's acceleration; the segments
    in ``skip`` left out.

    Two movable disks (or two immovable ones) have no relative acceleration: the
    quadratic of straight flight.  A movable disk against an immovable one, a wall
    end point, a wall side or a box wall: the contact functions of
    :func:`circle_contact_time_accelerated`, :func:`segment_contact_time_accelerated`
    and :func:`box_contact_time_accelerated`.

    The candidates are the same as in straight flight (every pair, image, wall and
    box wall), only examined in order of a lower bound on their contact time:
    bodies a gap ``s`` apart, with relative speed ``w`` and acceleration ``a``, close
    it no sooner than the root of ``w t + a t^2 / 2 = s``.  Once that bound exceeds
    the earliest contact found, no later candidate can come first and the search
    stops.  Of equal times the candidate first in the loop order of straight flight
    wins, as there.
    """
    n = len(positions)
    # (lower bound on the time, loop order, kind, i, partner, detail)
    candidates: list[tuple[float, int, str, int, int, Any]] = []
    for i in range(n):
        p, v, r = positions[i], velocities[i], radii[i]
        for j in range(i + 1, n):
            dv = (v[0] - velocities[j][0], v[1] - velocities[j][1])
            da = (acc[i][0] - acc[j][0], acc[i][1] - acc[j][1])
            d = r + radii[j]
            for sx, sy in shifts:
                dp = (p[0] - positions[j][0] - sx, p[1] - positions[j][1] - sy)
                gap = math.hypot(*dp) - d
                candidates.append((_earliest(gap, math.hypot(*dv), math.hypot(*da), d),
                                   len(candidates), "disk", i, j, (sx, sy, dp, dv, da)))
        for k, wall in enumerate(walls):
            if k in skip:
                continue
            for sx, sy in shifts:
                a = (wall.start[0] + sx, wall.start[1] + sy)
                b = (wall.end[0] + sx, wall.end[1] + sy)
                gap = _segment_distance(p, a, b) - r
                candidates.append((_earliest(gap, math.hypot(*v), math.hypot(*acc[i]), r),
                                   len(candidates), "wall", i, k, (a, b)))
        for axis, length in enumerate((box.width, box.height)):
            if not box.periodic[axis]:
                gap = min(p[axis], length - p[axis]) - r
                candidates.append((_earliest(gap, abs(v[axis]), abs(acc[i][axis]), r),
                                   len(candidates), "box", i, axis, length))
    best: Event = (INF, None, -1, -1, None)
    best_key = (INF, -1)
    for bound, order, kind, i, partner, data in sorted(candidates, key=lambda c: c[:2]):
        if bound > best[0]:
            break
        event: Event
        p, v, r = positions[i], velocities[i], radii[i]
        if kind == "disk":
            sx, sy, dp, dv, da = data
            d = r + radii[partner]
            if da == (0.0, 0.0):
                t = circle_contact_time(dp, dv, d)
            else:
                t = circle_contact_time_accelerated(dp, dv, da, d)
            event = (t, "disk", i, partner, (sx, sy))
        elif kind == "wall":
            a, b = data
            if acc[i] == (0.0, 0.0):
                t, part = segment_contact_time(p, v, r, a, b)
            else:
                t, part = segment_contact_time_accelerated(p, v, acc[i], r, a, b)
            event = (t, "wall", i, partner, (part, a, b))
        else:
            axis = partner
            t, upper = box_contact_time_accelerated(p[axis], v[axis], acc[i][axis], r,
                                                    data)
            event = (t, "box", i, 2 * axis + int(bool(upper)), None)
        if (t, order) < best_key:
            best, best_key = event, (t, order)
    return best


def next_moving_wall_event(best, positions, velocities, radii, acc, walls, motions, time,
                           shifts, horizon):
    """The earliest of ``best`` and the contacts with the segments that move.

    ``best`` is the earliest event among the other bodies (:func:`next_event` or
    :func:`next_event_accelerated` with the moving segments skipped); ``motions`` maps a
    segment's index to its :class:`~edmd2d.Translation` or :class:`~edmd2d.Oscillation`,
    ``time`` is the clock and ``acc`` each disk's acceleration.  Segment ``k`` is
    given by ``walls[k]``, where it is when its shift is zero; in each periodic image
    ``(sx, sy)`` its end points move with it.

    A translation's contact time is exact whatever its time
    (:func:`translating_segment_contact_time`).  Against an oscillation
    (:func:`oscillating_segment_contact_time`) the search ends at the earliest event
    found so far, or at ``horizon`` (the look-ahead window of a periodic box) if that
    is sooner: no later contact can come first.  A disk that does not move (no velocity
    and no acceleration) meets the segment within one period or never, which bounds
    its search too.  A moving segment's contact must come strictly before ``best`` to
    replace it.  Its detail is ``(part, a, b, u)``: the part hit, the segment's end
    points in that image at the contact and its velocity there.
    """
    for i, (p, v, r, g) in enumerate(zip(positions, velocities, radii, acc)):
        still = v[0] == v[1] == g[0] == g[1] == 0.0
        for k, motion in motions.items():
            wall = walls[k]
            for sx, sy in shifts:
                a = (wall.start[0] + sx, wall.start[1] + sy)
                b = (wall.end[0] + sx, wall.end[1] + sy)
                if isinstance(motion, Translation):
                    t, part, u = translating_segment_contact_time(p, v, g, r, a, b, motion,
                                                                  time)
                else:
                    limit = min(best[0], horizon)
                    if still:
                        limit = min(limit, motion.period)
                    if not limit < INF:
                        raise RuntimeError(f"no end to the search of disk {i} against "
                                           f"oscillating segment {k}")
                    t, part, u = oscillating_segment_contact_time(p, v, g, r, a, b, motion,
                                                                  time, limit)
                if t < best[0]:
                    s = _shift(motion, time + t)
                    best = (t, "wall", i, k, (part, (a[0] + s[0], a[1] + s[1]),
                                              (b[0] + s[0], b[1] + s[1]), u))
    return best
