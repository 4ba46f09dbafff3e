"""Rough disks in the reference: rotation, and collisions that exchange it with
translation (tangential restitution, limited by Coulomb friction).

Written for clarity, as the rest of the reference: the rules the engine is checked
against.

A disk ``k`` carries an angle and an angular velocity ``w[k]`` (about the axis
normal to the plane, counter-clockwise positive) and a moment of inertia ``I[k] = q
m r^2``.  At a contact with unit normal ``n`` (from the partner to the disk, or from a
wall into the box) and tangent ``t = (-n_y, n_x)``, the contact points of ``i`` and of
``j`` move at ``v_i - r_i w_i t`` and ``v_j + r_j w_j t``, so that their relative
velocity has the tangential component ``g_t = (v_i - v_j) . t - (r_i w_i + r_j w_j)``
(a wall: ``v_i . t - r_i w_i``).  The collision turns ``g_t`` into ``-beta g_t``
(``beta = -1``: smooth, no tangential impulse; ``+1``: perfectly rough) by the
tangential impulse ``J_t = -(1 + beta) g_t / K`` on ``i`` (minus on ``j``), ``K = 1/m_i
+ 1/m_j + r_i^2 / I_i + r_j^2 / I_j`` (a wall, or an immovable disk, adds nothing to
``K``), which changes ``v_i`` by ``J_t t / m_i`` and ``w_i`` by ``-r_i J_t / I_i``
(and ``w_j`` by ``-r_j J_t / I_j``: both spins are driven the same way).  With Coulomb
friction ``mu`` the impulse is at most ``mu J_n`` (``J_n`` the normal impulse): a
contact that would need more slides, ``J_t = -mu J_n sign(g_t)`` (Walton's model).
Linear momentum and ``sum m r x v + sum I w`` are conserved in every disk-disk
collision; the energy for ``e = 1`` and ``beta = +-1``; what is lost, ``-(J_t g_t +
J_t^2 / (2 / K))``, joins ``dissipated``.

Where the TC model makes a contact elastic (a disk that collided less than ``tc``
ago), it makes it smooth too: no tangential impulse, no energy lost.
"""

from __future__ import annotations

import math

from ._times import _dot


class RoughRules:
    """The rules of rotation, as methods of the simulation whose state they update:
    ``rough`` (whether any of it applies), the per-disk lists ``p``, ``v``, ``r``,
    ``m``, ``w`` (angular velocities),
    ``angle`` and ``inertia`` (``I``), the coefficients ``beta``, ``friction``,
    ``wall_beta`` and ``wall_friction``, the tallies ``dissipated``, the virial and
    ``wall_work`` (set up by ``ReferenceSimulation``)."""

    p: list[list[float]]
    v: list[list[float]]
    r: list[float]
    m: list[float]
    rough: bool
    w: list[float]
    angle: list[float]
    inertia: list[float]
    beta: float
    friction: float
    wall_beta: float
    wall_friction: float
    dissipated: float
    virial_xx: float
    virial_yy: float
    virial_xy: float
    wall_work: list[float]

    def _turn(self, dt):
        """Advance every angle by ``w dt``."""
        self.angle = [a + w * dt for a, w in zip(self.angle, self.w)]

    def _spin_energy(self, k):
        """Disk ``k``'s rotational kinetic energy (0 if immovable)."""
        return 0.0 if math.isinf(self.inertia[k]) else 0.5 * self.inertia[k] * self.w[k] ** 2

    def _tangential_pair(self, i, j, n, jn, d, smooth):
        """The tangential impulse of the collision of ``i`` and ``j`` (normal ``n``
        from ``j`` to ``i``, normal impulse ``jn >= 0`` on ``i``, separation ``d``),
        after the normal one; ``smooth`` (the TC model's elastic contact): none."""
        if smooth or self.beta == -1.0:
            return
        t = (-n[1], n[0])
        vi, vj = self.v[i], self.v[j]
        g_t = (vi[0] - vj[0]) * t[0] + (vi[1] - vj[1]) * t[1] \
            - (self.r[i] * self.w[i] + self.r[j] * self.w[j])
        k = sum(0.0 if math.isinf(self.m[a]) else 1.0 / self.m[a] + self.r[a] ** 2 /
                self.inertia[a] for a in (i, j))
        j_t = self._limited(-(1.0 + self.beta) * g_t / k, jn, self.friction)
        for a, sign in ((i, 1.0), (j, -1.0)):
            if math.isinf(self.m[a]):
                continue
            self.v[a] = [self.v[a][0] + sign * j_t * t[0] / self.m[a],
                         self.v[a][1] + sign * j_t * t[1] / self.m[a]]
            self.w[a] -= self.r[a] * j_t / self.inertia[a]
        self.dissipated -= j_t * g_t + 0.5 * k * j_t * j_t
        # The virial of the tangential impulse (on i, across d).
        self.virial_xx += d[0] * j_t * t[0]
        self.virial_yy += d[1] * j_t * t[1]
        self.virial_xy += d[0] * j_t * t[1]

    def _tangential_wall(self, i, n, jn, smooth, uw=(0.0, 0.0), moving=None):
        """The tangential impulse of disk ``i`` on a wall (``n`` from the wall into the
        disk's side, normal impulse ``jn >= 0``), after the normal one; on the moving
        segment ``moving`` (velocity ``uw``) the tangential velocity relative to it
        turns, and the segment does the work ``J_t t.uw``."""
        if smooth or self.wall_beta == -1.0 or not jn > 0.0:
            return  # (no normal impulse, no friction: as the engine)
        t = (-n[1], n[0])
        v = self.v[i]
        g_t = _dot((v[0] - uw[0], v[1] - uw[1]), t) - self.r[i] * self.w[i]
        k = 1.0 / self.m[i] + self.r[i] ** 2 / self.inertia[i]
        j_t = self._limited(-(1.0 + self.wall_beta) * g_t / k, jn, self.wall_friction)
        self.v[i] = [self.v[i][0] + j_t * t[0] / self.m[i],
                     self.v[i][1] + j_t * t[1] / self.m[i]]
        self.w[i] -= self.r[i] * j_t / self.inertia[i]
        self.dissipated -= j_t * g_t + 0.5 * k * j_t * j_t
        if moving is not None:
            self.wall_work[moving] += j_t * _dot(t, uw)

    @staticmethod
    def _limited(j_t, jn, mu):
        """Coulomb's limit: ``|J_t| <= mu J_n`` (sliding at the limit beyond it)."""
        limit = mu * jn
        return j_t if abs(j_t) <= limit else math.copysign(limit, j_t)

    def rotational_energy(self) -> float:
        """The rotational kinetic energy of the movable disks.

        Returns
        -------
        float
            ``sum I w^2 / 2``.
        """
        return sum(self._spin_energy(k) for k in range(len(self.w)))

    def angular_momentum(self, unwrapped) -> float:
        """The total angular momentum about the origin of the movable disks, at the
        given unwrapped centres: ``sum m r x v + sum I w``.

        Parameters
        ----------
        unwrapped : array_like, shape (N, 2)

        Returns
        -------
        float
        """
        return sum(self.m[k] * (unwrapped[k][0] * self.v[k][1] - unwrapped[k][1] * self.v[k][0])
                   + self.inertia[k] * self.w[k]
                   for k in range(len(self.w)) if not math.isinf(self.m[k]))
