"""Brute-force reference engine: seed section 3, literally, in plain Python.

At every step it examines *every* pair of disks (with all periodic images) and *every*
disk against every wall, box wall and wall end point, takes the earliest contact, moves
*all* disks to that moment, resolves it, and repeats.  It is slow (O(N^2) per event) and
meant to be read: it is the specification of what :class:`edmd2d.Simulation` computes
and the oracle its tests compare against.  It shares no code with the compiled engine;
only the value objects :class:`~edmd2d.Box` and :class:`~edmd2d.Wall` are common.

Examples
--------
>>> import edmd2d as ed
>>> from edmd2d.reference import ReferenceSimulation
>>> ref = ReferenceSimulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]],
...                           radii=1.0, box=ed.Box(10.0, 10.0, periodic=False))
>>> ref.advance(collisions=1).time
0.5
>>> ref.events
[(0.5, 'disk', 0, 1)]
"""

from __future__ import annotations

import math

import numpy as np

from .geometry import Box, Wall

__all__ = ["ReferenceSimulation"]

INF = math.inf


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def circle_contact_time(p, v, d):
    """Seed 4.1: earliest t >= 0 with |p + t v| = d, for an approaching pair, else inf.

    ``p`` and ``v`` are the relative position and velocity.  Written exactly as in the
    seed: t = -(v.p + sqrt((v.p)^2 - v^2 (p^2 - d^2))) / v^2.
    """
    vp = _dot(v, p)
    if vp >= 0:  # not approaching: no collision
        return INF
    vv = _dot(v, v)
    disc = vp * vp - vv * (_dot(p, p) - d * d)
    if disc <= 0:  # miss, or a touch without momentum exchange
        return INF
    t = -(vp + math.sqrt(disc)) / vv
    return max(t, 0.0)  # already touching and approaching: now


def segment_contact_time(p, v, r, a, b):
    """Seed 4.2 plus end points: earliest contact of a circle (p, v, r) with segment a-b.

    Returns (t, part) with part "side", "start" or "end"; (inf, None) if none.
    """
    u = (b[0] - a[0], b[1] - a[1])
    uu = _dot(u, u)
    rel = (p[0] - a[0], p[1] - a[1])
    # q: the projection of p - a on the wall; p~, v~: the components normal to the wall.
    q = _dot(rel, u) / uu
    pt = (rel[0] - q * u[0], rel[1] - q * u[1])
    k = _dot(v, u) / uu
    vt = (v[0] - k * u[0], v[1] - k * u[1])
    best, part = INF, None
    t = circle_contact_time(pt, vt, r)
    if t < INF:
        s = q + t * k  # where along the wall the contact happens
        if 0.0 <= s <= 1.0:
            best, part = t, "side"
    for name, e in (("start", a), ("end", b)):
        t = circle_contact_time((p[0] - e[0], p[1] - e[1]), v, r)
        if t < best:
            best, part = t, name
    return best, part


class ReferenceSimulation:
    """Same constructor and core API as :class:`edmd2d.Simulation`, brute force.

    Attributes: ``time``, ``positions``, ``velocities``, ``radii``, ``masses``,
    ``events`` (every disk, wall and box event as ``(time, kind, disk, partner)``),
    ``collisions``, ``wall_collisions``; methods ``advance``, ``kinetic_energy``,
    ``momentum``.  Input is trusted (no validation): it is a test oracle.
    """

    def __init__(self, positions, velocities, radii, masses=1.0, box: Box | None = None,
                 walls=(), *, time=0.0):
        n = len(positions)
        self.box = box
        self.walls = [w if isinstance(w, Wall) else Wall(*w) for w in walls]
        self.p = [[float(x), float(y)] for x, y in positions]
        self.v = [[float(x), float(y)] for x, y in velocities]
        self.r = _per_disk(radii, n)
        self.m = _per_disk(masses, n)
        self.time = float(time)
        self.events: list[tuple[float, str, int, int]] = []
        self.collisions = 0
        self.wall_collisions = 0

    # -- the images of space: shifts to try on periodic axes.  Within one look-ahead
    # window (see _horizon) no disk moves more than a quarter of a periodic length, so
    # a pair's relative position changes by at most half a length and every image it
    # can touch is within two lengths of the stored (wrapped) positions.
    def _shifts(self):
        xs = (-2, -1, 0, 1, 2) if self.box.periodic[0] else (0,)
        ys = (-2, -1, 0, 1, 2) if self.box.periodic[1] else (0,)
        return [(sx * self.box.width, sy * self.box.height) for sx in xs for sy in ys]

    def _horizon(self):
        """How far ahead next_event may look on a periodic box (inf if walled)."""
        lengths = [length for axis, length in enumerate((self.box.width, self.box.height))
                   if self.box.periodic[axis]]
        vmax = max((math.hypot(*v) for v in self.v), default=0.0)
        if not lengths or vmax == 0.0:
            return INF
        return min(lengths) / (4.0 * vmax)

    def next_event(self):
        """The earliest event from now: (dt, kind, i, partner, detail)."""
        best = (INF, None, -1, -1, None)
        n = len(self.p)
        shifts = self._shifts()
        for i in range(n):
            for j in range(i + 1, n):
                dv = (self.v[i][0] - self.v[j][0], self.v[i][1] - self.v[j][1])
                for sx, sy in shifts:
                    dp = (self.p[i][0] - self.p[j][0] - sx, self.p[i][1] - self.p[j][1] - sy)
                    t = circle_contact_time(dp, dv, self.r[i] + self.r[j])
                    if t < best[0]:
                        best = (t, "disk", i, j, (sx, sy))
            for k, wall in enumerate(self.walls):
                for sx, sy in shifts:
                    a = (wall.start[0] + sx, wall.start[1] + sy)
                    b = (wall.end[0] + sx, wall.end[1] + sy)
                    t, part = segment_contact_time(self.p[i], self.v[i], self.r[i], a, b)
                    if t < best[0]:
                        best = (t, "wall", i, k, (part, a, b))
            for axis, length in enumerate((self.box.width, self.box.height)):
                if self.box.periodic[axis]:
                    continue
                x, vx, r = self.p[i][axis], self.v[i][axis], self.r[i]
                if vx < 0:
                    t, side = max((x - r) / -vx, 0.0), 2 * axis
                elif vx > 0:
                    t, side = max((length - r - x) / vx, 0.0), 2 * axis + 1
                else:
                    continue
                if t < best[0]:
                    best = (t, "box", i, side, None)
        return best

    def _drift(self, dt):
        """Move every disk along its straight line for ``dt``."""
        self.p = [[p[0] + dt * v[0], p[1] + dt * v[1]] for p, v in zip(self.p, self.v)]
        self.time += dt

    def _wrap(self):
        """Bring centres back into the box on periodic axes (after an event is resolved,
        so the image chosen by ``next_event`` still describes the contact)."""
        for p in self.p:
            for axis, length in enumerate((self.box.width, self.box.height)):
                if self.box.periodic[axis]:
                    p[axis] %= length

    def _resolve(self, kind, i, partner, detail):
        p, v = self.p[i], self.v[i]
        if kind == "disk":
            j = partner
            if math.isinf(self.m[i]) and math.isinf(self.m[j]):
                raise RuntimeError(f"immovable disks {i} and {j} meet")
            sx, sy = detail
            d = (p[0] - self.p[j][0] - sx, p[1] - self.p[j][1] - sy)
            norm = math.sqrt(_dot(d, d))
            n = (d[0] / norm, d[1] / norm)
            vn = (v[0] - self.v[j][0]) * n[0] + (v[1] - self.v[j][1]) * n[1]
            # Textbook elastic collision: v_i' = v_i - 2 m_j/(m_i+m_j) (dv.n) n.
            if math.isinf(self.m[j]):
                fi, fj = 2.0, 0.0
            elif math.isinf(self.m[i]):
                fi, fj = 0.0, 2.0
            else:
                mt = self.m[i] + self.m[j]
                fi, fj = 2.0 * self.m[j] / mt, 2.0 * self.m[i] / mt
            self.v[i] = [v[0] - fi * vn * n[0], v[1] - fi * vn * n[1]]
            self.v[j] = [self.v[j][0] + fj * vn * n[0], self.v[j][1] + fj * vn * n[1]]
            self.collisions += 1
            return
        if math.isinf(self.m[i]):
            raise RuntimeError(f"immovable disk {i} reaches a wall")
        if kind == "box":
            axis = partner // 2
            v[axis] = -v[axis]
        else:
            part, a, b = detail
            if part == "side":
                u = (b[0] - a[0], b[1] - a[1])
                n = (-u[1], u[0])
            else:
                e = a if part == "start" else b
                n = (p[0] - e[0], p[1] - e[1])
            norm = math.sqrt(_dot(n, n))
            n = (n[0] / norm, n[1] / norm)
            vn = _dot(v, n)
            self.v[i] = [v[0] - 2 * vn * n[0], v[1] - 2 * vn * n[1]]
        self.wall_collisions += 1

    def advance(self, until=None, collisions=None):
        """Seed section 3: events in time order up to ``until`` / ``collisions``."""
        target = INF if until is None else float(until)
        todo = INF if collisions is None else int(collisions)
        done = 0
        while done < todo:
            dt, kind, i, partner, detail = self.next_event()
            horizon = self._horizon()
            if dt > horizon and self.time + horizon < target:
                # Nothing within the look-ahead window: move there and look again.
                self._drift(horizon)
                self._wrap()
                continue
            if self.time + dt > target or dt == INF:
                break
            self._drift(dt)
            self._resolve(kind, i, partner, detail)
            self._wrap()
            self.events.append((self.time, kind, i, partner))
            done += kind == "disk"
        if until is not None and done < todo:
            self._drift(target - self.time)
            self._wrap()
        return self

    @property
    def positions(self):
        return np.array(self.p)

    @property
    def velocities(self):
        return np.array(self.v)

    def kinetic_energy(self):
        return sum(0.5 * m * _dot(v, v) for m, v in zip(self.m, self.v) if not math.isinf(m))

    def momentum(self):
        return sum((m * np.array(v) for m, v in zip(self.m, self.v) if not math.isinf(m)),
                   np.zeros(2))


def _per_disk(value, n):
    try:
        return [float(value)] * n
    except TypeError:
        return [float(x) for x in value]
