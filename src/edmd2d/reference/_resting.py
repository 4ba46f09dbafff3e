"""Disks at rest in the reference engine: the rules, written plainly.

:class:`RestingRules` is the part of ``ReferenceSimulation`` that puts slow, held disks
to rest under gravity and wakes them again, with the criteria of a
:class:`edmd2d.physics.Resting` (``speed``, ``gap``, ``wake``, ``press``, ``soft`` and
``every``).  The rules are those its documentation states; here each is a short
method over the plain per-disk lists:

- *held* (:meth:`_cone`): the static bodies within ``gap`` of a disk (disks at rest,
  immovable disks standing still, box walls and wall segments, sides and end points,
  that are not heated) hold it when the direction against gravity lies strictly
  inside the cone of their normals (a normal on each side of it, less than half a turn
  apart), or one of them is a flat wall whose normal is that direction.  The normals
  are compared by their angles from that direction, ``atan2(up x n, up . n)``;
- *settle* (:meth:`_settle`), after every contact a disk takes part in (not with a
  heated wall): a movable disk no faster than ``speed`` and held comes to rest: its
  velocity is kept aside (``frozen``) and set to zero, its kinetic energy counted as
  dissipated, and the supports that hold it are noted (those on the two sides of the
  cone, or the flat wall alone, then the others, up to four).  After a pair, the first
  disk is examined again if only the second came to rest, so that the order of the
  two does not matter;
- a disk at rest does not move and feels no gravity: for the search it is a fixed
  circle, and two disks at rest never meet;
- *impact* (:meth:`_meet`): a flying disk meeting one at rest with a normal speed up
  to ``wake``, or up to ``press`` where the resting disk's static contacts can take
  the push (the impact's direction against the cone of their normals), bounces off it
  as off an immovable disk (:meth:`_bounce_static`), and leaves it at the parting
  speed at least (:meth:`_lift`).  If it met another static body at the same instant it
  is wedged (:meth:`_wedge`): it stops if held, to come to rest there; if not, it loses
  the part of its velocity that drives it into the static bodies it touches (the
  velocity nearest to its own that drives it into none, its loss dissipated) and
  leaves at the parting speed.  A faster impact, or one by an immovable
  disk, wakes the disk first (and the cascade below), and the two collide as any pair;
- *wake* (:meth:`_wake`): a woken disk resumes the velocity it came to rest with (the
  kinetic energy leaving the dissipated tally again), and every disk at rest that
  counted it among its supports is examined again: if the others no longer hold it,
  it wakes too, and so on upwards.  A thermostat redraw wakes its disk first;
- *soft impacts* are elastic: a contact whose normal speed is below ``soft``;
- *box walls*: after a bounce on a box wall that gravity presses the disk into, with
  a normal speed below ``speed`` left, the disk slides along the wall (its normal
  velocity, dissipated, removed), unless it collided at that same instant before and
  bounces faster than a thousandth of ``soft``.  After a wall segment or a disk at
  rest that gravity presses it into, the disk leaves at ``soft`` times the share of
  gravity that presses it (``-g.n / |g|``) at least;
- *parting*: two flying disks that gravity presses together (one slid on a box wall
  before they collided) part at ``soft`` times the share of gravity that presses them
  at least, by an impulse along their normal;
- *groups* (:meth:`_rest_groups`): at every multiple of ``every`` (after the events at
  that time), the slow flying disks that hold one another up come to rest together.
  Which groups hold is a static question, a linear program over the contact forces,
  answered by :func:`edmd2d._balance.held_groups`, which has its own tests
  (``tests/test_balance.py``); it is the one piece of the library this engine uses.

Every rest and wake is an event of its own, ``(time, "rest" or "wake", disk, -1)``:
the wakes an event causes come before it in ``events``, the rests after it.

Close calls.  These rules have thresholds, and a quantity within rounding of one
decides by its last bits: two runs whose arithmetic differs (this engine and the
compiled one) may then take different branches, both right, and part ways.  Each
decision whose quantity lies within ``CLOSE`` (relative) of its threshold is noted in
``close_calls`` as ``(time, what)``, so that a comparison can stop before the first.
"At one instant" (a disk wedged between two static bodies, or pushed into a floor)
is the sharpest: contact times at one instant differ by rounding, measured up to
3e-12 time units where the approach is slow (g = 1, unit diameters, clock ~ 5), so
the window (:meth:`_at_once`) adds the criteria's ``instant`` (1e-6 of ``soft / |g|``)
to a few units of rounding; two contacts within a factor 10 of that window are a close
call.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .._balance import TOL, held_groups  # (borrowed: see the notes)
from .._impacts import group as impact_group
from .._impacts import resolve as impact_resolve
from ._times import _dot

#: The supports noted per resting disk.
MAX_SUPPORTS = 4
#: A few units of rounding of the clock, relative: with the criteria's ``instant``,
#: the window within which two contacts of a disk come at one instant (:meth:`_at_once`).
INSTANT = 8.0 * 2.0 ** -52
#: A decision is a close call when its quantity lies within this relative distance of
#: its threshold.
CLOSE = 1e-6
#: The static bodies a wedged disk touches: gaps up to this fraction of its diameter.
WEDGE_TOUCH = 1e-9
#: Collisions of one disk in a row at one instant that make a stall, as in the engine.
STALL_COLLISIONS = 10_000
#: Impacts at one instant after which a stall stops the run, as in the engine.
IMPACTS_AT_ONCE = 8


def box_support(side: int) -> int:
    """The support code of box wall ``side``: ``-2 - side``."""
    return -2 - side


def segment_support(k: int) -> int:
    """The support code of wall segment ``k``: ``-6 - k``."""
    return -6 - k


class RestingRules:
    """The rules of disks at rest, as methods of the simulation whose state they update.

    Besides the state of ``CollisionRules``, they use ``rest`` (the criteria, or
    ``None``), and per disk ``at_rest``, ``frozen`` (the velocity it came to rest
    with), ``supports`` (codes: a disk's index, ``-2 - side`` for a box wall, ``-6 - k``
    for segment ``k``), ``t_static`` (its last contact with a static body) and
    ``t_before`` (the time of its collision before the last); the tallies
    ``rests`` and ``wakes``; and the lists ``_woken`` and ``_rested`` of the rests and
    wakes of the event being resolved.
    """

    # The state described above, set up by ReferenceSimulation.
    rest: Any
    p: list[list[float]]
    v: list[list[float]]
    r: list[float]
    m: list[float]
    species: list[int]
    box: Any
    walls: list[Any]
    gravity: tuple[float, float]
    wall_kt: dict[int, float]
    time: float
    dissipated: float
    resting: list[set[int]]
    at_rest: list[bool]
    frozen: list[tuple[float, float]]
    supports: list[list[int]]
    t_static: list[float]
    t_last: list[float]
    t_before: list[float]
    streak: list[int]
    restitution: Any
    wall_restitution: float
    thermostat: Any
    rests: int
    wakes: int
    collisions: int
    wall_collisions: int
    _woken: list[int]
    _rested: list[int]
    events: list[tuple[float, str, int, int]]
    close_calls: list[tuple[float, str]]
    # (Methods of ReferenceSimulation and CollisionRules.)
    _shifts: Callable[[], list[tuple[float, float]]]
    _acceleration: Callable[[int], tuple[float, float]]
    _release: Callable[[int], None]

    # -- close calls (see the module notes)
    def _close(self, what, value, threshold, scale):
        """Note a close call if ``value`` lies within ``CLOSE * scale`` of
        ``threshold``."""
        if abs(value - threshold) <= CLOSE * scale:
            self.close_calls.append((self.time, what))

    def _close_instant(self, before):
        """Note a close call if ``before`` lies within a factor 10 of the window of
        :meth:`_at_once` from the present."""
        window = INSTANT * abs(self.time) + self.rest.instant
        if 0.1 * window < self.time - before < 10.0 * window:
            self.close_calls.append((self.time, "instant"))

    # -- bodies that do not move
    def _static(self, k):
        """Whether disk ``k`` holds others without moving: at rest, or immovable and
        standing still."""
        return self.at_rest[k] or (math.isinf(self.m[k]) and self.v[k] == [0.0, 0.0])

    def _contacts(self, i, gap=None):
        """The static bodies within ``gap`` (default: the criteria's) of disk ``i``:
        ``(code, normal, flat)``, the normal a unit vector towards the disk's centre,
        ``flat`` whether it is a box wall or a segment's side; in the order box walls,
        segments, disks."""
        found = []  # (code, normal, flat)
        x, y = self.p[i]
        r = self.r[i]
        gap = self.rest.gap if gap is None else gap
        for side in range(4):
            axis = side // 2
            if self.box.periodic[axis] or side in self.wall_kt:
                continue
            length = (self.box.width, self.box.height)[axis]
            c = self.p[i][axis]
            self._close("gap", c - r if side % 2 == 0 else length - r - c, gap, gap)
            if (c - r if side % 2 == 0 else length - r - c) <= gap:
                inward = 1.0 if side % 2 == 0 else -1.0
                normal = (inward, 0.0) if axis == 0 else (0.0, inward)
                found.append((box_support(side), normal, True))
        for k, wall in enumerate(self.walls):
            if 4 + k in self.wall_kt:
                continue
            for sx, sy in self._shifts():
                a = (wall.start[0] + sx, wall.start[1] + sy)
                b = (wall.end[0] + sx, wall.end[1] + sy)
                u = (b[0] - a[0], b[1] - a[1])
                rel = (x - a[0], y - a[1])
                along = _dot(rel, u) / _dot(u, u)
                flat = 0.0 <= along <= 1.0
                if flat:
                    length = math.sqrt(_dot(u, u))
                    n = (-u[1] / length, u[0] / length)
                    h = _dot(rel, n)
                    if h < 0.0:
                        n = (-n[0], -n[1])
                    distance = abs(h)
                else:
                    end = a if along < 0.0 else b
                    distance = math.hypot(x - end[0], y - end[1])
                    n = ((x - end[0]) / distance, (y - end[1]) / distance)
                self._close("gap", distance - r, gap, gap)
                if distance - r <= gap:
                    found.append((segment_support(k), n, flat))
        for m in range(len(self.p)):
            if m == i or not self._static(m):
                continue
            for sx, sy in self._shifts():
                d = (x - self.p[m][0] - sx, y - self.p[m][1] - sy)
                distance = math.hypot(*d)
                self._close("gap", distance - (r + self.r[m]), gap, gap)
                if distance - (r + self.r[m]) <= gap:
                    found.append((m, (d[0] / distance, d[1] / distance), False))
        return found

    def _cone(self, i, up, write):
        """Whether the static bodies within ``gap`` of disk ``i`` hold it against a
        push opposite to the unit vector ``up`` (see the module notes); if so, and
        ``write``, its supports are noted."""
        contacts = self._contacts(i)
        below = above = None  # the nearest normal on each side of ``up``: (angle, code)
        flat = None
        for code, n, is_flat in contacts:
            angle = math.atan2(up[0] * n[1] - up[1] * n[0], _dot(up, n))
            if angle != 0.0 or not is_flat:
                self._close("side", angle, 0.0, 1.0)
            if angle == 0.0 and is_flat:
                flat = code
            if angle < 0.0 and (below is None or angle > below[0]):
                below = (angle, code)
            elif angle > 0.0 and (above is None or angle < above[0]):
                above = (angle, code)
        if flat is None and below is not None and above is not None:
            self._close("cone", above[0] - below[0], math.pi, math.pi)
        held = flat is not None or (below is not None and above is not None
                                    and above[0] - below[0] < math.pi)
        if held and write:
            if flat is not None:
                self.supports[i] = [flat]
            else:
                assert below is not None and above is not None
                first = [below[1], above[1]]
                others = [code for code, _, _ in contacts if code not in first]
                self.supports[i] = (first + others)[:MAX_SUPPORTS]
        return held

    def _up(self):
        g = math.hypot(*self.gravity)
        return (-self.gravity[0] / g, -self.gravity[1] / g)

    # -- coming to rest, and waking
    def _settle(self, i):
        """Put disk ``i`` to rest if it is movable, flying, no faster than ``speed`` and
        held; returns whether it was."""
        if math.isinf(self.m[i]) or self.at_rest[i]:
            return False
        self._close("speed", math.hypot(*self.v[i]), self.rest.speed, self.rest.speed)
        if math.hypot(*self.v[i]) > self.rest.speed:
            return False
        if not self._cone(i, self._up(), True):
            return False
        self._put_to_rest(i)
        return True

    def _put_to_rest(self, i):
        vx, vy = self.v[i]
        self.dissipated += 0.5 * self.m[i] * (vx * vx + vy * vy)
        self.frozen[i] = (vx, vy)
        self.v[i] = [0.0, 0.0]
        self.at_rest[i] = True
        self.resting[i] = set()  # (at rest, it slides along no box wall)
        self.rests += 1
        self._rested.append(i)

    def _wake_one(self, d):
        vx, vy = self.frozen[d]
        self.dissipated -= 0.5 * self.m[d] * (vx * vx + vy * vy)
        self.v[d] = [vx, vy]
        self.frozen[d] = (0.0, 0.0)
        self.at_rest[d] = False
        self.supports[d] = []
        self.wakes += 1
        self._woken.append(d)

    def _wake(self, j):
        """Wake disk ``j`` (if at rest), and in cascade the disks at rest that one
        woken disk supported and the others no longer hold."""
        if not self.at_rest[j]:
            return
        self._wake_one(j)
        todo = [j]
        while todo:
            d = todo.pop()
            for m in range(len(self.p)):
                if self.at_rest[m] and d in self.supports[m]:
                    if not self._cone(m, self._up(), True):
                        self._wake_one(m)
                        todo.append(m)

    def _rest_groups(self):
        """Put to rest the groups of slow flying disks that hold one another up."""
        n = len(self.p)
        static = np.array([self._static(k) for k in range(n)])
        movable = np.array([not math.isinf(m) for m in self.m])
        cold = np.array([k not in self.wall_kt for k in range(4 + len(self.walls))])
        ends = [(np.array(w.start, float), np.array(w.end, float)) for w in self.walls]
        rows, supports = held_groups(
            np.array(self.p), np.array(self.v), np.array(self.r), np.array(self.m), static,
            movable, self.box, ends, cold[:4], cold[4:], np.array(self.gravity),
            self.rest.speed, self.rest.gap, TOL)
        for k, i in enumerate(rows):
            self.supports[int(i)] = [int(c) for c in supports[k] if c != -1]
            self._put_to_rest(int(i))
        self.events.extend((self.time, "rest", i, -1) for i in self._rested)
        self._rested.clear()

    # -- contacts with disks at rest, and the parting speed
    def _meet(self, i, j, shift):
        """Flying disk ``i`` meets disk ``j``: whether ``j`` is at rest and stays so
        (see the module notes); a faster impact wakes it first."""
        if not self.at_rest[j]:
            return False
        if math.isinf(self.m[i]):  # (a piston carries it along)
            self._wake(j)
            return False
        d = (self.p[i][0] - self.p[j][0] - shift[0], self.p[i][1] - self.p[j][1] - shift[1])
        norm = math.hypot(*d)
        vn = _dot(self.v[i], d) / norm  # (j does not move)
        self._close("wake", -vn, self.rest.wake, self.rest.wake)
        self._close("press", -vn, self.rest.press, self.rest.press)
        if vn < 0.0 and -vn > self.rest.wake:
            if -vn <= self.rest.press and self._cone(j, (d[0] / norm, d[1] / norm), False):
                return True
            self._wake(j)
            return False
        return True

    def _bounce_static(self, i, j, shift, restitution):
        """Flying disk ``i`` bounces off disk ``j`` at rest as off an immovable disk,
        with the pair's ``restitution`` (a function of the normal speed); returns
        whether it was wedged."""
        d = (self.p[i][0] - self.p[j][0] - shift[0], self.p[i][1] - self.p[j][1] - shift[1])
        norm = math.hypot(*d)
        n = (d[0] / norm, d[1] / norm)
        before = self.t_static[i]
        wedged = self._at_once(before)
        self.t_static[i] = self.time
        vn = _dot(self.v[i], n)
        self._close_instant(before)  # (wedged or not decides the lift, too)
        if vn < 0.0:
            if wedged:
                self._wedge(i, n)
            else:
                e = restitution(vn)
                self.v[i] = [self.v[i][0] - (1.0 + e) * vn * n[0],
                             self.v[i][1] - (1.0 + e) * vn * n[1]]
                self.dissipated += 0.5 * (1.0 - e * e) * self.m[i] * vn * vn
        if not wedged:
            self._lift(i, n)
        return wedged

    def _wedge(self, i, n):
        """Disk ``i``, wedged (it met a static body, unit normal ``n``, at the instant
        it met one before), stops if the static bodies within ``gap`` hold it (then it
        comes to rest there); otherwise it loses the velocity that drives it into the
        static bodies it touches (this one, and those within ``WEDGE_TOUCH`` of its
        diameter): its velocity becomes the one nearest to it in the cone
        ``u . n_k >= 0``."""
        v = self.v[i]
        if self._cone(i, self._up(), False):
            self.dissipated += 0.5 * self.m[i] * _dot(v, v)
            self.v[i] = [0.0, 0.0]
            return
        normals = [n] + [normal for _, normal, _ in
                         self._contacts(i, WEDGE_TOUCH * 2.0 * self.r[i])]
        self._nearest_velocity(i, [(normal, 0.0) for normal in normals])

    def _nearest_velocity(self, i, bounds):
        """Disk ``i`` takes the velocity nearest to its own with ``n . u >= speed``
        for each ``(n, speed)`` of ``bounds`` (unit normals of its static contacts):
        its own, its projection on one bound's line, or the crossing of two lines
        (0 where the speeds are 0), whichever is nearest of those within all bounds
        (none: it keeps its own).  The change of kinetic energy is booked in the
        dissipated tally (a wedged disk's loss, a lift's gain)."""
        v = self.v[i]
        size = math.hypot(*v) + max(speed for _, speed in bounds)

        def within(u):
            return all(_dot(u, n) >= speed - 1e-12 * size for n, speed in bounds)

        if within(v):
            return
        options = []
        for n, speed in bounds:
            q = speed - _dot(v, n)
            options.append((v[0] + q * n[0], v[1] + q * n[1]))
        for k, (n1, s1) in enumerate(bounds):
            for n2, s2 in bounds[k + 1:]:
                det = n1[0] * n2[1] - n1[1] * n2[0]
                if abs(det) > 1e-12:
                    options.append(((s1 * n2[1] - s2 * n1[1]) / det,
                                    (n1[0] * s2 - n2[0] * s1) / det))
        options = [u for u in options if within(u)]
        if not options:
            return
        u = min(options, key=lambda u: (u[0] - v[0]) ** 2 + (u[1] - v[1]) ** 2)
        self.dissipated -= 0.5 * self.m[i] * (_dot(u, u) - _dot(v, v))
        self.v[i] = [u[0], u[1]]

    def _lift(self, i, n):
        """After disk ``i`` met a static body with unit normal ``n`` (towards the disk)
        that gravity presses it into: it leaves at ``soft`` times the share of
        gravity that presses it, at least."""
        pressed = _dot(self.gravity, n)
        if pressed >= 0.0:
            return
        w = _dot(self.v[i], n)
        target = self.rest.soft * -pressed / math.hypot(*self.gravity)
        if w >= target:
            return
        before = _dot(self.v[i], self.v[i])
        q = target - w
        self.v[i] = [self.v[i][0] + q * n[0], self.v[i][1] + q * n[1]]
        self.dissipated -= 0.5 * self.m[i] * (_dot(self.v[i], self.v[i]) - before)

    def _lift_off(self, i, j, shift):
        d = (self.p[i][0] - self.p[j][0] - shift[0], self.p[i][1] - self.p[j][1] - shift[1])
        norm = math.hypot(*d)
        self._lift(i, (d[0] / norm, d[1] / norm))

    def _part(self, i, j, shift, ai, aj):
        """After flying disks ``i`` and ``j`` collided, with accelerations ``ai`` and
        ``aj`` before it: if gravity presses them together (one of them slid on a box
        wall), they part at ``soft`` times the share of gravity that presses them, at
        least."""
        if math.isinf(self.m[i]) or math.isinf(self.m[j]):
            return
        d = (self.p[i][0] - self.p[j][0] - shift[0], self.p[i][1] - self.p[j][1] - shift[1])
        norm = math.hypot(*d)
        n = (d[0] / norm, d[1] / norm)
        pressed = _dot((ai[0] - aj[0], ai[1] - aj[1]), n)
        if ai != aj:  # (equal accelerations, both in free fall: exactly 0)
            # (Parting releases both from their walls: a decision, however small the
            # impulse.)
            self._close("pressed", pressed, 0.0, math.hypot(*self.gravity))
        if pressed >= 0.0:
            return
        w = _dot((self.v[i][0] - self.v[j][0], self.v[i][1] - self.v[j][1]), n)
        target = self.rest.soft * -pressed / math.hypot(*self.gravity)
        self._close("parting", w, target, self.rest.soft)
        if w >= target:
            return
        before = self.m[i] * _dot(self.v[i], self.v[i]) + self.m[j] * _dot(self.v[j], self.v[j])
        impulse = (target - w) * self.m[i] * self.m[j] / (self.m[i] + self.m[j])
        self.v[i] = [self.v[i][0] + impulse / self.m[i] * n[0],
                     self.v[i][1] + impulse / self.m[i] * n[1]]
        self.v[j] = [self.v[j][0] - impulse / self.m[j] * n[0],
                     self.v[j][1] - impulse / self.m[j] * n[1]]
        after = self.m[i] * _dot(self.v[i], self.v[i]) + self.m[j] * _dot(self.v[j], self.v[j])
        self.dissipated -= 0.5 * (after - before)
        self._release(i)
        self._release(j)

    def _slide(self, i, side):
        """After disk ``i`` bounced off box wall ``side``: it slides along the wall if
        gravity presses it into it and its normal speed is below ``speed``."""
        axis = side // 2
        inward = 1.0 if side % 2 == 0 else -1.0
        if self.gravity[axis] * inward >= 0.0:
            return
        vn = self.v[i][axis] * inward
        if vn > 1e-3 * self.rest.soft:
            # (Pushed: its collision before this one came at the same instant.)
            self._close_instant(self.t_before[i])
            if self._at_once(self.t_before[i]):
                return
        self._close("speed", vn, self.rest.speed, self.rest.speed)
        if vn < self.rest.speed:
            self.dissipated += 0.5 * self.m[i] * vn * vn
            self.v[i][axis] = 0.0
            self.resting[i].add(side)

    def _lift_segment(self, i, part, a, b):
        """:meth:`_lift` after disk ``i`` met a wall segment a-b (``part``)."""
        p = self.p[i]
        if part == "side":
            u = (b[0] - a[0], b[1] - a[1])
            length = math.hypot(*u)
            n = (-u[1] / length, u[0] / length)
            if _dot(n, (p[0] - a[0], p[1] - a[1])) < 0.0:
                n = (-n[0], -n[1])
        else:
            end = a if part == "start" else b
            norm = math.hypot(p[0] - end[0], p[1] - end[1])
            n = ((p[0] - end[0]) / norm, (p[1] - end[1]) / norm)
        self._lift(i, n)
        self._release(i)

    # -- the clock of collisions
    def _at_once(self, before):
        """Whether a contact at ``before`` and one now came at one instant, for the
        rules of rest: within a few units of rounding of the clock and the criteria's
        ``instant`` of each other (contact times at one instant differ by rounding)."""
        return self.time - before <= INSTANT * abs(self.time) + self.rest.instant

    def _note(self, k):
        """Movable disk ``k`` collided now: its clock of the TC model, and its streak of
        collisions at one instant (within a few units of rounding of the clock)."""
        if math.isinf(self.m[k]):
            return
        at_once = self.time - self.t_last[k] <= INSTANT * abs(self.time)
        self.streak[k] = self.streak[k] + 1 if at_once else 0
        self.t_before[k] = self.t_last[k]
        self.t_last[k] = self.time

    # -- disks caught between static bodies: one inelastic impact
    def _stalls(self, when, disks):
        """Whether the contact of ``disks`` at ``when`` would make a streak of
        ``STALL_COLLISIONS`` collisions of one movable disk at one instant (where disks
        come to rest and a model of contact counts streaks: restitution below 1, heated
        walls or a thermostat)."""
        if self.rest is None or not self._streaks():
            return False
        return any(not math.isinf(self.m[k])
                   and when - self.t_last[k] <= INSTANT * abs(when)
                   and self.streak[k] + 1 >= STALL_COLLISIONS for k in disks)

    def _streaks(self):
        table = (self.restitution if isinstance(self.restitution, list)
                 else [[self.restitution]])
        return (self.wall_restitution < 1.0 or any(e < 1.0 for row in table for e in row)
                or bool(self.wall_kt) or self.thermostat is not None)

    def _impact(self, seeds, stop=False):
        """The flying disks joined to ``seeds`` by contacts, and their contacts with
        static bodies (not heated walls), take one perfectly inelastic impact together
        (:mod:`edmd2d._impacts`), or stop if ``stop`` (they stalled again at this
        instant); each contact that takes an impulse is an event; then the groups
        that hold one another up come to rest.  Returns whether any velocity
        changed."""
        n = len(self.p)
        static = np.array([self._static(k) for k in range(n)])
        flying = ~static & np.array([not math.isinf(m) for m in self.m])
        nowhere = (np.full(2, np.nan), np.full(2, np.nan))
        ends = [nowhere if 4 + k in self.wall_kt
                else (np.array(w.start, float), np.array(w.end, float))
                for k, w in enumerate(self.walls)]
        cold = np.array([side not in self.wall_kt for side in range(4)])
        found = impact_group(seeds, np.array(self.p), np.array(self.r), flying, static,
                             self.box, ends, cold)
        if found is None or len(found[1]) == 0:
            return False
        members, a, b, side, segment, normal, _ = found
        invm = np.array([1.0 / m for m in self.m])
        before = [list(self.v[int(d)]) for d in members]
        if stop:
            after, impulse = np.zeros((len(members), 2)), np.zeros(len(a))
            lost = sum(0.5 * self.m[int(d)] * _dot(v, v) for d, v in zip(members, before))
        else:
            after, impulse, lost = impact_resolve(members, np.array(self.v), invm, a, b,
                                                  normal)
        self.dissipated += lost
        for k, d in enumerate(members):
            self.v[int(d)] = [float(after[k, 0]), float(after[k, 1])]
        # Each leaves the static disks and segments that gravity presses it into at the
        # parting speed, driving into none of its static contacts (a box wall only
        # bounds it: on a box wall it slides).
        for d in members.tolist():
            mine = [c for c in range(len(a)) if a[c] == d and b[c] < 0]
            bounds = []
            for c in mine:
                unit = (float(normal[c, 0]), float(normal[c, 1]))
                pressing = -_dot(self.gravity, unit)
                pressed = pressing > 0.0 and side[c] < 0
                speed = self.rest.soft * pressing / math.hypot(*self.gravity)
                bounds.append((unit, speed if pressed else 0.0, pressed))
            if any(pressed for _, _, pressed in bounds):
                self._nearest_velocity(d, [(unit, speed) for unit, speed, _ in bounds])
        if not stop and not (impulse > 0.0).any() and all(
                self.v[int(d)] == v for d, v in zip(members, before)):
            return False
        for d in members:
            self._release(int(d))
            self._note(int(d))
            self.streak[int(d)] = 0
        for c in np.flatnonzero(impulse > 0.0).tolist():
            if side[c] >= 0:
                self.events.append((self.time, "box", int(a[c]), int(side[c])))
                self.wall_collisions += 1
            elif segment[c] >= 0:
                self.events.append((self.time, "wall", int(a[c]), int(segment[c])))
                self.wall_collisions += 1
            else:
                other = int(b[c]) if b[c] >= 0 else -2 - int(b[c])
                self.events.append((self.time, "disk", int(a[c]), other))
                self.collisions += 1
        self._rest_groups()
        return True


__all__ = ["RestingRules"]
