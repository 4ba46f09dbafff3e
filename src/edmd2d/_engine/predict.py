"""Exact contact times (disk-disk, disk-segment and segment end points) and cell-exit times.

All functions return a time *interval* ``dt >= 0`` measured from the moment the
positions were taken, or ``inf`` for "never".  A tiny negative root produced by
rounding (two bodies already touching and still approaching) is returned as 0:
events are never scheduled into the past.
"""

from __future__ import annotations

import math

from .._jit import njit

INF = math.inf


@njit
def pair_time(dx, dy, dvx, dvy, d):
    """Time until two circles with separation ``(dx, dy)`` and relative velocity
    ``(dvx, dvy)`` come to the distance ``d``, or ``inf``.

    With ``b = dp.dv``, ``c = dp^2 - d^2`` and ``disc = b^2 - dv^2 c`` the earlier root of
    ``dv^2 t^2 + 2 b t + c = 0`` is ``(-b - sqrt(disc)) / dv^2``.  For an approaching pair
    (``b < 0``) both ``-b`` and ``sqrt(disc)`` are positive, so we use the algebraically
    equal ``c / (-b + sqrt(disc))``, which adds two positive numbers instead of
    subtracting nearly equal ones: no cancellation for grazing or slow pairs.
    Pairs that do not approach (``b >= 0``) never collide, even if touching.
    """
    b = dx * dvx + dy * dvy
    if b >= 0.0:
        return INF
    vv = dvx * dvx + dvy * dvy
    c = dx * dx + dy * dy - d * d
    disc = b * b - vv * c
    if disc <= 0.0:
        # No real root, or a double root: a tangential touch exchanges no momentum.
        return INF
    t = c / (-b + math.sqrt(disc))
    return t if t > 0.0 else 0.0


@njit
def segment_time(x, y, vx, vy, r, ax, ay, bx, by):
    """First contact of a moving circle with the segment ``a -> b`` (its side, or else an
    end point).

    Returns ``(dt, part)`` with ``part`` 0 for the side of the segment, 1 for the end
    point ``a`` and 2 for ``b``; ``(inf, -1)`` if never.

    The side: with ``n`` the unit normal of the segment, ``h = (p - a).n`` the signed
    distance and ``w = v.n`` the normal velocity, the contact quadratic for the normal
    components reads ``w^2 t^2 + 2 h w t + h^2 - r^2 = 0``; its discriminant is exactly
    ``w^2 r^2``, so the earlier root is ``(|h| - r) / |w|`` when the circle approaches the
    line (``h w < 0``) -- no square root and no cancellation.  The contact counts only if
    the foot point lies on the segment (``0 <= s <= 1``).  Otherwise the first contact,
    if any, is with an end point, a circle of radius 0 (:func:`pair_time` with ``d = r``).
    """
    ux = bx - ax
    uy = by - ay
    ll = ux * ux + uy * uy
    inv_len = 1.0 / math.sqrt(ll)
    nx = -uy * inv_len
    ny = ux * inv_len
    h = (x - ax) * nx + (y - ay) * ny
    w = vx * nx + vy * ny
    if h * w < 0.0:
        dt = (abs(h) - r) / abs(w)
        if dt < 0.0:
            dt = 0.0
        s = ((x + vx * dt - ax) * ux + (y + vy * dt - ay) * uy) / ll
        if 0.0 <= s <= 1.0:
            return dt, 0
    ta = pair_time(x - ax, y - ay, vx, vy, r)
    tb = pair_time(x - bx, y - by, vx, vy, r)
    if ta <= tb:
        if ta < INF:
            return ta, 1
        return INF, -1
    return tb, 2


@njit
def box_wall_time(x, vx, r, length):
    """Time until a circle at coordinate ``x`` hits the wall at 0 or at ``length``.

    Returns ``(dt, side)`` with side 0 for the lower wall, 1 for the upper one.
    """
    if vx < 0.0:
        dt = (x - r) / -vx
        return (dt if dt > 0.0 else 0.0), 0
    if vx > 0.0:
        dt = (length - r - x) / vx
        return (dt if dt > 0.0 else 0.0), 1
    return INF, -1


@njit
def exit_time(x, vx, c, side, ncell, periodic):
    """Time until a centre at coordinate ``x`` in cell ``c`` (cells of width ``side``)
    leaves it, and the direction (+1 or -1).  On a walled axis a centre cannot leave the
    outermost cells (the wall is hit first), so that crossing is never scheduled.
    """
    if vx > 0.0:
        if c + 1 >= ncell and not periodic:
            return INF, 0
        dt = ((c + 1) * side - x) / vx
        return (dt if dt > 0.0 else 0.0), 1
    if vx < 0.0:
        if c == 0 and not periodic:
            return INF, 0
        dt = (c * side - x) / vx
        return (dt if dt > 0.0 else 0.0), -1
    return INF, 0
