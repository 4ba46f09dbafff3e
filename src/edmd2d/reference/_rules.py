"""The collision rules of the reference engine: what a contact does to the disks.

:class:`CollisionRules` is the part of ``ReferenceSimulation`` that resolves the
contact its search found, once the disks are moved to it: a pair's impulse with its
coefficient of restitution and the TC model, a reflection at a box wall or a wall
segment (side or end point; a moving segment reflects the velocity relative to its own,
and does work on the disk), a heated wall's new velocity, a disk coming to rest on a
box wall that gravity presses it into, and contacts of growing disks.  Under shear a
pair may meet through a sliding image, whose velocity differs from its disk's; the
impulse is the same, computed with the image's velocity, and every pair's impulse adds
to the collisional virial.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from ..geometry import Oscillation
from ._resting import RestingRules
from ._rough import RoughRules
from ._times import _dot


class CollisionRules(RestingRules, RoughRules):
    """The collision rules, as methods of the simulation whose state they update.

    The state is the one ``ReferenceSimulation`` sets up: the per-disk lists ``p``,
    ``v``, ``r``, ``m``, ``dr``, ``t_last``, ``resting`` and ``species``, the settings
    ``tc``, ``growth``, ``restitution``, ``wall_restitution``, ``gravity`` and
    ``wall_kt``, the moving segments' ``motions``, the clock ``time``, the tallies
    ``dissipated``, ``wall_heat``, ``wall_work``, ``collisions``, ``wall_collisions``,
    ``virial_xx``, ``virial_yy`` and ``virial_xy``, ``heat_x`` and ``heat_y``, and the
    random draws ``_u`` and ``_gauss`` (one stream for the whole run, shared with the
    thermostat); and, where disks come
    to rest (``rest`` not ``None``), the state of :class:`RestingRules`, whose rules
    it calls after each contact.
    """

    # The state described above, set up by ReferenceSimulation.
    p: list[list[float]]
    v: list[list[float]]
    r: list[float]
    m: list[float]
    dr: list[float]
    t_last: list[float]
    resting: list[set[int]]
    species: list[int]
    tc: float
    growth: float | None
    restitution: float | list[list[float]]
    wall_restitution: float
    gravity: tuple[float, float]
    wall_kt: dict[int, float]
    time: float
    motions: dict
    dissipated: float
    wall_heat: list[float]
    wall_work: list[float]
    collisions: int
    wall_collisions: int
    virial_xx: float
    virial_yy: float
    virial_xy: float
    heat_x: float
    heat_y: float
    rest: Any
    _u: Callable[[], float]
    _gauss: Callable[[], float]

    def _recent(self, k):
        """The TC rule for disk ``k``: movable and collided less than ``tc`` ago."""
        return not math.isinf(self.m[k]) and self.time - self.t_last[k] < self.tc

    def _soft(self, vn):
        """Whether a contact of normal speed ``|vn|`` is soft, hence elastic (where
        disks come to rest: below the criteria's ``soft``)."""
        if self.rest is None:
            return False
        self._close("soft", abs(vn), self.rest.soft, self.rest.soft)
        return abs(vn) < self.rest.soft

    def _pair_restitution(self, i, j, vn):
        if self._recent(i) or self._recent(j) or self._soft(vn):
            return 1.0
        if isinstance(self.restitution, float):
            return self.restitution
        return self.restitution[self.species[i]][self.species[j]]

    def _wall_restitution(self, i, vn):
        return 1.0 if self._recent(i) or self._soft(vn) else self.wall_restitution

    def _resolve(self, kind, i, partner, detail):
        """Resolve the contact ``next_event`` found (``kind``, disk ``i``, its
        ``partner`` and the ``detail`` of the contact), the disks moved to its time.

        A pair's detail is the shift of the image of ``j`` that ``i`` touches, from
        ``j``: ``(dx, dy)``, or under shear ``(dx, dy, du)`` with the image moving at
        ``v_j + (du, 0)`` (its shift at the contact's time)."""
        p, v = self.p[i], self.v[i]
        if kind == "disk":
            j = partner
            if math.isinf(self.m[i]) and math.isinf(self.m[j]):
                raise RuntimeError(f"immovable disks {i} and {j} meet")
            if self.rest is not None and self.at_rest[i]:
                # (The search found the pair from the disk at rest: see it from the
                # flying one.)
                i, j, detail = j, i, (-detail[0], -detail[1])
                p, v = self.p[i], self.v[i]
            if self.rest is not None and self._meet(i, j, detail):
                # j at rest, and staying so: i bounces off it as off a fixed body.
                wedged = self._bounce_static(
                    i, j, detail, lambda vn: self._pair_restitution(i, j, vn))
                self._note(i)
                self._release(i)
                if wedged and not self._settle(i):
                    self._lift_off(i, j, detail)
                    self._release(i)
                self.collisions += 1
                self._settle(i)
                return
            # (The accelerations before the collision, which may release a disk that
            # slid on a box wall: see _part.)
            before = (self._acceleration(i), self._acceleration(j))
            sx, sy = detail[0], detail[1]
            # The velocity of the image of j: j's own, or j's plus (du, 0) under shear.
            vj = self.v[j] if len(detail) == 2 else (self.v[j][0] + detail[2], self.v[j][1])
            d = (p[0] - self.p[j][0] - sx, p[1] - self.p[j][1] - sy)
            norm = math.sqrt(_dot(d, d))
            n = (d[0] / norm, d[1] / norm)
            vn = (v[0] - vj[0]) * n[0] + (v[1] - vj[1]) * n[1]
            if self.growth is not None:
                # The gap closes at dd - vn: the rate the collision reverses (vn' - dd =
                # dd - vn); rounding may leave a contact not closing: nothing changes.
                # (Closing as the contact time's quadratic has it, d.dv < s ds with s
                # the contact distance: the same test, also for a pair that rounding
                # left overlapping.)
                dv = (v[0] - vj[0], v[1] - vj[1])
                s = self.r[i] + self.r[j]
                vn = min((_dot(d, dv) - s * (self.dr[i] + self.dr[j])) / norm, 0.0)
            e = self._pair_restitution(i, j, vn)
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
            e_before = 0.5 * self.m[i] * _dot(v, v) if fi else 0.0
            if self.rough and fi:
                e_before += self._spin_energy(i)
            self.v[i] = [v[0] - fi * vn * n[0], v[1] - fi * vn * n[1]]
            self.v[j] = [self.v[j][0] + fj * vn * n[0], self.v[j][1] + fj * vn * n[1]]
            # The kinetic energy of the relative normal motion, mu vn^2 / 2, times 1 - e^2.
            self.dissipated += 0.5 * (1.0 - e * e) * mu * vn * vn
            # The impulse on i, J = -(1+e) mu vn n (m_i fi = (1+e) mu), and the virial
            # r_a J_b with r = d, from the image of j to i.
            jx, jy = -k * mu * vn * n[0], -k * mu * vn * n[1]
            self.virial_xx += d[0] * jx
            self.virial_yy += d[1] * jy
            self.virial_xy += d[0] * jy
            if self.rough:
                self._tangential_pair(i, j, n, -k * mu * vn, d,
                                      self._recent(i) or self._recent(j))
            # The energy i gained, carried across d (the Helfand moment of heat).
            if fi:
                de = 0.5 * self.m[i] * _dot(self.v[i], self.v[i]) - e_before
                if self.rough:
                    de += self._spin_energy(i)
                self.heat_x += d[0] * de
                self.heat_y += d[1] * de
            for disk in (i, j):
                self._note(disk)
                self._release(disk)
            self.collisions += 1
            if self.rest is not None:
                self._part(i, j, detail, *before)
                # (Disk i again if only j came to rest, which may be the support it
                # lacked: the outcome does not depend on the order of i and j.)
                first = self._settle(i)
                if self._settle(j) and not first:
                    self._settle(i)
            return
        if math.isinf(self.m[i]):
            raise RuntimeError(f"immovable disk {i} reaches a wall")
        wall = partner if kind == "box" else 4 + partner
        if self.rest is not None:
            self.t_static[i] = self.time
        if wall in self.wall_kt:
            if kind == "box":
                sign = 1.0 if partner % 2 == 0 else -1.0
                n = (sign, 0.0) if partner < 2 else (0.0, sign)
            else:
                part, a, b = detail
                if part == "side":
                    n = (a[1] - b[1], b[0] - a[0])
                    if _dot(n, (p[0] - a[0], p[1] - a[1])) < 0.0:
                        n = (-n[0], -n[1])
                else:
                    end = a if part == "start" else b
                    n = (p[0] - end[0], p[1] - end[1])
                norm = math.sqrt(_dot(n, n))
                n = (n[0] / norm, n[1] / norm)
            self._heat(i, wall, n)
            self._note(i)
            self.wall_collisions += 1
            self._release(i)  # (a heated wall never holds a disk, and frees one it hits)
            return
        if kind == "box" and self.growth is not None:
            # The rim moves towards the wall at dr: v' reverses the closing rate.
            axis = partner // 2
            inward = 1.0 if partner % 2 == 0 else -1.0
            closing = min(v[axis] * inward - self.dr[i], 0.0)
            v[axis] -= 2.0 * closing * inward
            self.wall_collisions += 1
            return
        if kind == "box":
            axis = partner // 2
            vn = v[axis]
            e = self._wall_restitution(i, vn)
            v[axis] = -e * vn
            self.dissipated += 0.5 * (1.0 - e * e) * self.m[i] * vn * vn
            if self.rough:
                inward = 1.0 if partner % 2 == 0 else -1.0
                self._tangential_wall(i, (inward, 0.0) if axis == 0 else (0.0, inward),
                                      (1.0 + e) * self.m[i] * abs(vn), self._recent(i))
            g_in = self._pressing(partner)
            rebound = abs(v[axis])
            # Rest: the rebound would bring the disk back in 2 v / |g_n| < tc.
            if self._holds() and g_in < 0.0 and 2.0 * rebound < -g_in * self.tc:
                self.dissipated += 0.5 * self.m[i] * rebound * rebound
                v[axis] = 0.0
                self.resting[i].add(partner)
            self._note(i)
            self.wall_collisions += 1
            if self.rest is not None:
                self._slide(i, partner)
                self._settle(i)
            return
        # A moving segment's detail also holds its velocity uw at the contact (its end
        # points are those at the contact): the velocity relative to it, v - uw, is
        # reflected.  A fixed segment is uw = 0, and v - 0.0 is v to the last bit.
        part, a, b = detail[0], detail[1], detail[2]
        uw = detail[3] if len(detail) > 3 else (0.0, 0.0)
        if part == "side":
            u = (b[0] - a[0], b[1] - a[1])
            n = (-u[1], u[0])
        else:
            end = a if part == "start" else b
            n = (p[0] - end[0], p[1] - end[1])
        norm = math.sqrt(_dot(n, n))
        n = (n[0] / norm, n[1] / norm)
        vn = _dot((v[0] - uw[0], v[1] - uw[1]), n)
        if self.growth is not None:
            # (n points to the disk's side for an end point; for a side, the sign
            # of n drops out of vn n, but not of the growth term.)
            if part == "side":
                if _dot(n, (p[0] - a[0], p[1] - a[1])) < 0.0:
                    n = (-n[0], -n[1])
                    vn = -vn
                vn = min(vn - self.dr[i], 0.0)
            else:  # (as for a pair: the end point's separation times dv, less r dr)
                vn = min((vn * norm - self.r[i] * self.dr[i]) / norm, 0.0)
        e = self._wall_restitution(i, vn)
        k = 1.0 + e  # exactly 2.0 for e = 1, as in the elastic reflection
        self.v[i] = [v[0] - k * vn * n[0], v[1] - k * vn * n[1]]
        self._release(i)
        self.dissipated += 0.5 * (1.0 - e * e) * self.m[i] * vn * vn
        jn = k * self.m[i] * abs(vn)  # (the normal impulse, for friction)
        if len(detail) > 3:
            # The work of the impulse J = -(1+e) m vn n on the disk, J.uw: the kinetic
            # energy it gained beyond the loss, since v'^2 - v^2 = (v'-uw)^2 - (v-uw)^2
            # + 2 (v' - v).uw.
            self.wall_work[partner] += -k * self.m[i] * vn * _dot(n, uw)
            jn += self.m[i] * self._leave_moving(i, partner, part, p, a, n, uw)
        if self.rough:
            # (The normal from the segment to the disk's centre, for the tangent.)
            if _dot(n, (p[0] - (a if part != "end" else b)[0],
                        p[1] - (a if part != "end" else b)[1])) < 0.0:
                n = (-n[0], -n[1])
            self._tangential_wall(i, n, jn, self._recent(i), uw,
                                  partner if len(detail) > 3 else None)
        self._note(i)
        self.wall_collisions += 1
        if self.rest is not None:
            self._lift_segment(i, part, a, b)
            self._settle(i)

    def _leave_moving(self, i, partner, part, p, a, n, uw):
        """After a contact with an oscillating segment, disk ``i`` leaves it at the
        parting speed at least, ``sqrt(2 (A omega^2 + |g|) tol)`` with ``tol = 2^-40 (r
        + A)`` (slower, the segment could catch it again before the gap opens beyond
        rounding, without end); the segment does that work too.  Returns the normal
        velocity added (0 if none)."""
        motion = self.motions.get(partner)
        if not isinstance(motion, Oscillation):
            return 0.0
        if part == "side" and _dot(n, (p[0] - a[0], p[1] - a[1])) < 0.0:
            n = (-n[0], -n[1])  # (towards the disk)
        g = math.hypot(*self.gravity) if self.m[i] != math.inf else 0.0
        tol = 2.0**-40 * (self.r[i] + motion.amplitude)
        least = math.sqrt(2.0 * (motion.amplitude * motion.omega**2 + g) * tol)
        v = self.v[i]
        away = _dot((v[0] - uw[0], v[1] - uw[1]), n)
        if away < least:
            w = [v[0] + (least - away) * n[0], v[1] + (least - away) * n[1]]
            self.wall_work[partner] += 0.5 * self.m[i] * (_dot(w, w) - _dot(v, v))
            self.v[i] = w
            return least - away
        return 0.0

    def _heat(self, i, wall, n):
        """Disk ``i`` leaves heated ``wall`` (normal ``n`` into the box)."""
        s = math.sqrt(self.wall_kt[wall] / self.m[i])
        before = _dot(self.v[i], self.v[i])
        vn = s * math.sqrt(-2.0 * math.log(1.0 - self._u()))
        vt = s * self._gauss()
        self.v[i] = [vn * n[0] - vt * n[1], vn * n[1] + vt * n[0]]
        self.wall_heat[wall] += 0.5 * self.m[i] * (_dot(self.v[i], self.v[i]) - before)

    def _release(self, k):
        """After a collision, disk ``k`` stays held only by the walls along whose normal
        it still does not move."""
        self.resting[k] = {side for side in self.resting[k] if self.v[k][side // 2] == 0.0}

    def _holds(self):
        """Whether walls hold disks at rest by the TC model: some coefficient below 1,
        and tc > 0, where disks do not come to rest (which holds them otherwise)."""
        if self.rest is not None:
            return False
        table = (self.restitution if isinstance(self.restitution, list)
                 else [[self.restitution]])
        inelastic = self.wall_restitution < 1.0 or any(e < 1.0 for row in table for e in row)
        return inelastic and self.tc > 0.0

    def _pressing(self, side):
        """Gravity's component along the inward normal of box wall ``side`` (negative:
        it presses disks into that wall)."""
        g = self.gravity[side // 2]
        return g if side % 2 == 0 else -g
