"""Rough disks: rotation, and collisions that exchange it with translation.

Each disk carries an angular velocity ``w`` (counter-clockwise) and an angle, and a
moment of inertia ``I = q m r^2`` (``inv_inertia`` holds ``1 / I``, 0 for an
immovable disk).  At a contact with unit normal ``n`` (from the partner to the disk,
or from a wall into the disk's side) and tangent ``t = (-n_y, n_x)``, the relative
velocity of the contact points has the tangential component ``g_t = (v_i - v_j) . t -
(r_i w_i + r_j w_j)`` (at a wall ``v_i . t - r_i w_i``).  After the normal impulse
``J_n`` of the ordinary collision (:mod:`.response`), the tangential impulse ``J_t =
-(1 + beta) g_t / K``, ``K = 1/m_i + 1/m_j + r_i^2 / I_i + r_j^2 / I_j``, turns
``g_t`` into ``-beta g_t``; Coulomb friction caps it at ``mu J_n`` (Walton's model:
the contact slides beyond).  It changes ``v_i`` by ``J_t t / m_i`` and ``w_i`` by
``-r_i J_t / I_i`` (and ``j`` by the opposite impulse, ``w_j`` by ``-r_j J_t /
I_j``); the energy it takes, ``-(J_t g_t + K J_t^2 / 2)``, is dissipated.  The
reference's ``_rough.py`` writes the same rules out plainly.

The loop applies it after the ordinary collision: the normal is the pair's
separation (the wall's normal) at contact, and ``J_n`` the change that collision made
to the normal relative velocity over the sum of the inverse masses; a contact that
exchanged nothing (rounding left it not approaching) gets no tangential impulse
either.  A segment receives the opposite of the disk's tangential impulse in its
force tally.  Where the TC model made the contact elastic (decided
before the collision, :func:`smooth`), it is smooth as well.  A heated wall sets the
velocity only.  The thermostat draws the spin with the velocity, at its
temperature (:func:`redraw`).

``w`` changes only at these events; ``angle[i]`` holds the angle at ``t_angle[i]``,
brought forward (:func:`_turn`) before each change of ``w[i]``.
"""

from __future__ import annotations

import math

from .._jit import njit
from . import moving as _moving
from .layout import (
    A_DISSIPATED,
    A_THERMOSTAT,
    A_VIRIAL_XX,
    A_VIRIAL_XY,
    A_VIRIAL_YY,
    A_WORK,
    FIXED,
    M_DX,
    M_DY,
    SEGMENT,
    VX,
    VY,
    W_FX,
    W_FY,
    W_WORK,
    R,
    X,
    Y,
    unpack_shift,
)
from .response import RANDOM_PER_EVENT, wall_normal


@njit
def smooth(i, j, t, contact):
    """Whether the TC model makes the contact of ``i`` and ``j`` (``j == i``: a wall)
    elastic, hence smooth: one of them collided less than ``tc`` ago.  (Asked before
    the collision, which notes its own time.)"""
    if contact is None:
        return False
    tc = contact.tc
    return t - contact.t_last[i] < tc or t - contact.t_last[j] < tc


@njit
def _turn(i, t, rough):
    """Bring disk ``i``'s angle to ``t``."""
    rough.angle[i] += rough.w[i] * (t - rough.t_angle[i])
    rough.t_angle[i] = t


@njit
def _limited(j_t, jn, mu):
    """Coulomb's cap ``|J_t| <= mu J_n``."""
    limit = mu * jn
    if abs(j_t) <= limit:
        return j_t
    return math.copysign(limit, j_t)


@njit
def pair(i, j, t, aux, gf, vix, viy, vjx, vjy, S, invm, acc, rough):
    """The tangential impulse of the collision of ``i`` with the image ``aux`` of
    ``j`` at ``t``, whose normal impulse changed their velocities from ``(vix, viy)``
    and ``(vjx, vjy)``."""
    sx, sy = unpack_shift(aux)
    dx = S[i, X] - (S[j, X] + sx * gf[0])
    dy = S[i, Y] - (S[j, Y] + sy * gf[1])
    dist = math.sqrt(dx * dx + dy * dy)
    nx = dx / dist
    ny = dy / dist
    # The normal impulse on i: the change of the normal relative velocity over the
    # sum of the inverse masses (exact for either disk heavy).
    wsum = invm[i] + invm[j]
    jn = (((S[i, VX] - S[j, VX]) - (vix - vjx)) * nx
          + ((S[i, VY] - S[j, VY]) - (viy - vjy)) * ny) / wsum
    if not jn > 0.0:
        return
    tx = -ny
    ty = nx
    ri = S[i, R]
    rj = S[j, R]
    g_t = ((S[i, VX] - S[j, VX]) * tx + (S[i, VY] - S[j, VY]) * ty
           - (ri * rough.w[i] + rj * rough.w[j]))
    k = wsum + ri * ri * rough.inv_inertia[i] + rj * rj * rough.inv_inertia[j]
    j_t = _limited(-(1.0 + rough.beta) * g_t / k, jn, rough.friction)
    _turn(i, t, rough)
    _turn(j, t, rough)
    S[i, VX] += j_t * tx * invm[i]
    S[i, VY] += j_t * ty * invm[i]
    S[j, VX] -= j_t * tx * invm[j]
    S[j, VY] -= j_t * ty * invm[j]
    rough.w[i] -= ri * j_t * rough.inv_inertia[i]
    rough.w[j] -= rj * j_t * rough.inv_inertia[j]
    acc[A_DISSIPATED] -= j_t * g_t + 0.5 * k * j_t * j_t
    # The virial of the tangential impulse on i, across d.
    acc[A_VIRIAL_XX] += dx * j_t * tx
    acc[A_VIRIAL_YY] += dy * j_t * ty
    acc[A_VIRIAL_XY] += dx * j_t * ty


@njit
def wall(i, t, kind, partner, aux, vix, viy, S, invm, acc, wacc, gf, wa, wb, rough,
         motion):
    """The tangential impulse of disk ``i`` on the wall of a BOX or SEGMENT event at
    ``t``, whose normal impulse changed its velocity from ``(vix, viy)``; a segment
    receives the opposite impulse (``wacc``).  A moving segment (``motion``) turns the
    tangential velocity relative to its own, ``u``, and does the work ``J_t t.u``
    (``acc[A_WORK]``, ``wacc[partner, W_WORK]``): the energy taken in its frame is
    dissipated, as at a fixed wall."""
    nx, ny, nn, _ = wall_normal(i, t, kind, partner, aux, S, gf, wa, wb, motion)
    norm = math.sqrt(nn)
    nx /= norm
    ny /= norm
    jn = ((S[i, VX] - vix) * nx + (S[i, VY] - viy) * ny) / invm[i]
    if not jn > 0.0:
        return
    tx = -ny
    ty = nx
    ux = 0.0
    uy = 0.0
    moves = motion is not None and kind == SEGMENT and motion.kind[partner] != FIXED
    if moves:
        us = _moving.speed(partner, t, motion)
        ux = us * motion.par[partner, M_DX]
        uy = us * motion.par[partner, M_DY]
    ri = S[i, R]
    g_t = (S[i, VX] - ux) * tx + (S[i, VY] - uy) * ty - ri * rough.w[i]
    k = invm[i] + ri * ri * rough.inv_inertia[i]
    j_t = _limited(-(1.0 + rough.wall_beta) * g_t / k, jn, rough.wall_friction)
    _turn(i, t, rough)
    S[i, VX] += j_t * tx * invm[i]
    S[i, VY] += j_t * ty * invm[i]
    rough.w[i] -= ri * j_t * rough.inv_inertia[i]
    acc[A_DISSIPATED] -= j_t * g_t + 0.5 * k * j_t * j_t
    if kind == SEGMENT:
        wacc[partner, W_FX] -= j_t * tx
        wacc[partner, W_FY] -= j_t * ty
        if moves:
            work = j_t * (ux * tx + uy * ty)
            wacc[partner, W_WORK] += work
            acc[A_WORK] += work


@njit
def needs_random(uniforms):
    """Whether the buffer of random numbers is too low for the next event, a
    thermostat's redraw of a velocity and a spin taking two more than
    ``response.RANDOM_PER_EVENT``."""
    buffer = uniforms.buffer
    return (buffer.shape[0] > 0
            and uniforms.cursor[0] + RANDOM_PER_EVENT + 2 > buffer.shape[0])


@njit
def redraw(k, t, kt, gauss, acc, rough):
    """The thermostat's draw of disk ``k``'s spin: ``sqrt(kT / I) gauss``."""
    inv = rough.inv_inertia[k]
    before = rough.w[k] * rough.w[k] / inv
    _turn(k, t, rough)
    rough.w[k] = math.sqrt(kt * inv) * gauss
    acc[A_THERMOSTAT] += 0.5 * (rough.w[k] * rough.w[k] / inv - before)
