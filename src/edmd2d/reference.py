"""Brute-force reference engine: the plain event loop, in plain Python.

At every step it examines *every* pair of disks (with all periodic images) and *every*
disk against every wall, box wall and wall end point, takes the earliest contact, moves
*all* disks to that moment, resolves it, and repeats.  It is slow (O(N^2) per event) and
meant to be read: it is the specification of what :class:`edmd2d.Simulation` computes
and the oracle its tests compare against.  It shares no code with the compiled engine;
only the value objects :class:`~edmd2d.Box` and :class:`~edmd2d.Wall` are common.

Collisions may be inelastic.  The disks are smooth: a collision changes only the normal
component of the relative velocity (of the disk's velocity, at a wall), which becomes
``-e`` times itself, with a coefficient of restitution ``e`` for each pair of species and
``e_w`` for all walls.  The kinetic energy lost, ``(1 - e**2)/2 * mu * vn**2`` per
collision with normal velocity ``vn`` and reduced mass ``mu`` (the disk's own mass
against a wall or an immovable disk), is added up in ``dissipated``.  The TC model of
Luding and McNamara (1998) keeps inelastic collapse away: a collision is elastic if one
of its movable disks has collided less than a time ``tc`` before.  With the defaults
(``e = e_w = 1``) every collision is elastic.

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
    """Earliest t >= 0 with |p + t v| = d, for an approaching pair, else inf.

    ``p`` and ``v`` are the relative position and velocity.  Written as the textbook
    root: t = -(v.p + sqrt((v.p)^2 - v^2 (p^2 - d^2))) / v^2.
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
    """Earliest contact of a circle (p, v, r) with the segment a-b: its side or an end point.

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

    Methods ``advance(until=None, collisions=None)``, ``kinetic_energy()`` and
    ``momentum()`` work as in :class:`edmd2d.Simulation`.  Input is trusted (no
    validation): it is a test oracle.

    Parameters
    ----------
    positions, velocities : array_like, shape (N, 2)
        Disk centres (inside the box) and velocities.
    radii, masses : float or array_like, shape (N,)
        Radii and masses (default 1.0); mass ``inf`` makes a disk immovable.
    box : Box
        The container.
    walls : iterable of Wall or of (start, end) pairs, optional
        Extra wall segments.
    time : float, default 0.0
        The clock at the given state.
    species : array_like of int, shape (N,), optional
        Species ids ``0 .. S-1`` (default: all 0); they only select ``restitution``.
    restitution : float or array_like, shape (S, S), default 1.0
        Normal coefficient of restitution ``e`` of disk-disk collisions, 0 < e <= 1:
        one value, or a symmetric table indexed by the two disks' species.
    wall_restitution : float, default 1.0
        Coefficient ``e_w`` of every collision of a disk with a box wall or a wall
        segment (side or end point).
    tc : float, default 0.0
        Duration (a time) of the TC model: a collision is elastic if a movable disk
        taking part collided less than ``tc`` before (``t - t_last < tc``).  Immovable
        disks act as walls and never make a collision elastic; ``tc = 0`` switches the
        rule off.

    Attributes
    ----------
    time : float
        The clock.
    positions, velocities : ndarray, shape (N, 2)
        The state at ``time`` (copies).
    events : list of (float, str, int, int)
        Every disk, wall and box event as ``(time, kind, disk, partner)``.
    collisions, wall_collisions : int
        Disk-disk and disk-wall (box walls and segments) collision counts.
    t_last : list of float
        Time of each disk's last collision (``-inf`` before the first; never set for
        immovable disks).
    dissipated : float
        Kinetic energy lost in collisions so far.  ``kinetic_energy() + dissipated`` is
        constant to rounding, unless immovable disks move (pistons do work).

    Notes
    -----
    A pair ``i, j`` with unit normal ``n`` from ``j`` to ``i`` and ``vn = (v_i - v_j).n``
    (< 0 when approaching) leaves with ``v_i' = v_i - (1+e) m_j/(m_i+m_j) vn n`` and
    ``v_j' = v_j + (1+e) m_i/(m_i+m_j) vn n`` (``v_i' = v_i - (1+e) vn n`` if ``j`` is
    immovable), which conserves momentum and turns ``vn`` into ``-e vn``.  At a box wall
    the normal velocity component becomes ``-e_w`` times itself; at a segment side or end
    point with unit normal ``n``, ``v' = v - (1+e_w)(v.n) n``.

    Examples
    --------
    A head-on collision with ``e = 0.5``: the relative speed 2 drops to 1, and a quarter
    of the reduced-mass energy ``mu vn^2 / 2 = 1`` is kept.

    >>> import edmd2d as ed
    >>> ref = ReferenceSimulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]],
    ...                           radii=1.0, box=ed.Box(10.0, 10.0, periodic=False),
    ...                           restitution=0.5)
    >>> ref.advance(collisions=1).velocities.tolist()
    [[-0.5, 0.0], [0.5, 0.0]]
    >>> ref.dissipated, ref.kinetic_energy()
    (0.75, 0.25)
    """

    def __init__(self, positions, velocities, radii, masses=1.0, box: Box | None = None,
                 walls=(), *, time=0.0, species=None, restitution=1.0,
                 wall_restitution=1.0, tc=0.0):
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
        self.species = [0] * n if species is None else [int(s) for s in species]
        if np.ndim(restitution) == 0:
            self.restitution = float(restitution)
        else:
            self.restitution = [[float(e) for e in row] for row in restitution]
        self.wall_restitution = float(wall_restitution)
        self.tc = float(tc)
        self.t_last = [-INF] * n
        self.dissipated = 0.0

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

    def _recent(self, k):
        """The TC rule for disk ``k``: movable and collided less than ``tc`` ago."""
        return not math.isinf(self.m[k]) and self.time - self.t_last[k] < self.tc

    def _pair_restitution(self, i, j):
        if self._recent(i) or self._recent(j):
            return 1.0
        if isinstance(self.restitution, float):
            return self.restitution
        return self.restitution[self.species[i]][self.species[j]]

    def _wall_restitution(self, i):
        return 1.0 if self._recent(i) else self.wall_restitution

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
            e = self._pair_restitution(i, j)
            # Impulse along n: v_i' = v_i - (1+e) m_j/(m_i+m_j) vn n, and the opposite
            # for j, so that vn becomes -e vn.  For e = 1, 1 + e is exactly 2.0: the
            # elastic result is the textbook one to the last bit.
            k = 1.0 + e
            if math.isinf(self.m[j]):
                fi, fj, mu = k, 0.0, self.m[i]
            elif math.isinf(self.m[i]):
                fi, fj, mu = 0.0, k, self.m[j]
            else:
                mt = self.m[i] + self.m[j]
                fi, fj = k * self.m[j] / mt, k * self.m[i] / mt
                mu = self.m[i] * self.m[j] / mt  # the reduced mass
            self.v[i] = [v[0] - fi * vn * n[0], v[1] - fi * vn * n[1]]
            self.v[j] = [self.v[j][0] + fj * vn * n[0], self.v[j][1] + fj * vn * n[1]]
            # The kinetic energy of the relative normal motion, mu vn^2 / 2, times 1 - e^2.
            self.dissipated += 0.5 * (1.0 - e * e) * mu * vn * vn
            for disk in (i, j):
                if not math.isinf(self.m[disk]):
                    self.t_last[disk] = self.time
            self.collisions += 1
            return
        if math.isinf(self.m[i]):
            raise RuntimeError(f"immovable disk {i} reaches a wall")
        e = self._wall_restitution(i)
        if kind == "box":
            axis = partner // 2
            vn = v[axis]
            v[axis] = -e * vn
        else:
            part, a, b = detail
            if part == "side":
                u = (b[0] - a[0], b[1] - a[1])
                n = (-u[1], u[0])
            else:
                end = a if part == "start" else b
                n = (p[0] - end[0], p[1] - end[1])
            norm = math.sqrt(_dot(n, n))
            n = (n[0] / norm, n[1] / norm)
            vn = _dot(v, n)
            k = 1.0 + e  # exactly 2.0 for e = 1, as in the elastic reflection
            self.v[i] = [v[0] - k * vn * n[0], v[1] - k * vn * n[1]]
        self.dissipated += 0.5 * (1.0 - e * e) * self.m[i] * vn * vn
        self.t_last[i] = self.time
        self.wall_collisions += 1

    def advance(self, until=None, collisions=None):
        """Events in time order up to ``until`` / ``collisions``."""
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
