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
# The factor of the rounding-error bounds of :func:`_bisect`: 16 unit roundoffs, more
# than the chains of roundings there add up to (8 for ``s``, 11 for ``f``).
_ROUNDING = 8.0 * 2.0**-52


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
def _segment_frame(x, y, vx, vy, ax, ay, bx, by):
    """The segment ``a -> b`` seen from a centre at ``(x, y)`` moving at ``v``: its
    vector ``u``, ``u.u``, its unit normal ``n`` (to the left of ``u``), the signed
    distance ``h = (p - a).n`` of the centre from its line and the normal velocity
    ``w = v.n``."""
    ux = bx - ax
    uy = by - ay
    ll = ux * ux + uy * uy
    inv_len = 1.0 / math.sqrt(ll)
    nx = -uy * inv_len
    ny = ux * inv_len
    return ux, uy, ll, nx, ny, (x - ax) * nx + (y - ay) * ny, vx * nx + vy * ny


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
    ux, uy, ll, nx, ny, h, w = _segment_frame(x, y, vx, vy, ax, ay, bx, by)
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


# ---------------------------------------------------------------- growing disks
# Under growth every radius grows at a constant speed (``r_i' = rate R_i``), so a contact
# distance grows linearly, ``d + d' t``; the flight stays a straight line.


@njit
def growth_factor(t, growth):
    """Under growth (``layout.Growth``): the factor ``1 + rate (t - t0)`` by which every
    radius at ``t`` exceeds its stored value ``S[i, R]`` (the radius at ``t0``); each
    radius grows at the speed ``rate S[i, R]``.  1 without growth."""
    if growth is None:
        return 1.0
    return 1.0 + growth.rate * (t - growth.t0)


@njit
def pair_time_grow(dx, dy, dvx, dvy, d, dd):
    """Time until two circles with separation ``(dx, dy)`` and relative velocity
    ``(dvx, dvy)`` come to the distance ``d + dd t`` that grows at the speed ``dd >= 0``
    (the sum of their radii's growth speeds), or ``inf``.

    The contact is the first root of ``a t^2 + 2 b t + c = 0`` with ``a = dv^2 - dd^2``,
    ``b = dp.dv - d dd`` and ``c = dp^2 - d^2``; ``a`` has either sign.  The gap
    ``|dp + dv t| - (d + dd t)`` is convex in ``t`` (a norm of a line less a linear
    function) and has the sign of that quadratic, so:

    - ``b < 0`` (the quadratic falls): its first root, when there is one, is
      ``c / (-b + sqrt(disc))`` with ``disc = b^2 - a c``, free of cancellation as in
      :func:`pair_time`; for ``a <= 0`` there is always one.  Overlapping by rounding
      (``c <= 0``): contact now.
    - ``b >= 0``: only if the growth outruns the relative speed (``a < 0``) does the
      quadratic come back down; its root is then the larger one,
      ``(b + sqrt(disc)) / -a`` (a sum of positive numbers).  Overlapping by rounding
      with no root at all (``disc < 0``: the growth never lets them part): contact now.
    """
    b = dx * dvx + dy * dvy - d * dd
    c = dx * dx + dy * dy - d * d
    a = dvx * dvx + dvy * dvy - dd * dd
    if b < 0.0:
        if c <= 0.0:
            return 0.0
        disc = b * b - a * c
        if disc <= 0.0:
            return INF  # (only for a > 0: a miss, or a tangential touch)
        return c / (-b + math.sqrt(disc))
    if a >= 0.0:
        return INF
    disc = b * b - a * c
    if disc < 0.0:
        return 0.0
    return (b + math.sqrt(disc)) / -a


@njit
def box_wall_time_grow(x, vx, r, dr, length):
    """Time until a circle at coordinate ``x`` whose radius ``r`` grows at the speed
    ``dr`` touches the wall at 0 or at ``length``: ``(dt, side)``, side 0 for the lower
    wall, 1 for the upper one (a disk at rest grows into both: the earlier counts)."""
    lo = INF
    if vx - dr < 0.0:
        lo = max((x - r) / (dr - vx), 0.0)
    hi = INF
    if vx + dr > 0.0:
        hi = max((length - r - x) / (vx + dr), 0.0)
    if lo <= hi:
        return lo, (0 if lo < INF else -1)
    return hi, 1


@njit
def segment_time_grow(x, y, vx, vy, r, dr, ax, ay, bx, by):
    """:func:`segment_time` for a circle whose radius ``r`` grows at the speed ``dr``:
    its rim closes on the segment's line at ``dr`` plus its normal speed towards it,
    and on an end point as on a fixed circle of radius 0 (:func:`pair_time_grow`)."""
    ux, uy, ll, nx, ny, h, w = _segment_frame(x, y, vx, vy, ax, ay, bx, by)
    closing = dr - w if h >= 0.0 else dr + w  # the rate at which |h| - r shrinks
    if closing > 0.0:
        dt = max((abs(h) - r) / closing, 0.0)
        s = ((x + vx * dt - ax) * ux + (y + vy * dt - ay) * uy) / ll
        if 0.0 <= s <= 1.0:
            return dt, 0
    ta = pair_time_grow(x - ax, y - ay, vx, vy, r, dr)
    tb = pair_time_grow(x - bx, y - by, vx, vy, r, dr)
    if ta <= tb:
        if ta < INF:
            return ta, 1
        return INF, -1
    return tb, 2


# ---------------------------------------------------------------- uniform acceleration
# Under gravity a movable disk flies on a parabola.  The relative motion of two movable
# disks stays linear (same acceleration), so :func:`pair_time` serves them; everything
# else becomes a quadratic in time (a wall, a cell boundary, the line of a segment) or a
# quartic (a fixed point: a segment's end, an immovable disk).


@njit
def descend_time(c, b, a):
    """First ``t >= 0`` at which ``q(t) = c + b t + a t^2`` falls through zero
    (``q' < 0`` there), for a gap ``c = q(0)`` that is ``>= 0`` up to rounding; ``inf``
    if never.

    ``q`` is a gap closing under a constant acceleration: the distance of a centre to a
    cell boundary, of a disk's rim to a box wall or to the line of a segment (seen from
    the disk's side).  Only a crossing *towards* the boundary counts: a disk that has
    just touched a wall or crossed a boundary (``c`` 0 or a rounding below) and moves
    away is not stopped there, but an acceleration that turns it back brings it to the
    crossing again.  A gap ``c <= 0`` that is closing is crossed now (never in the
    past); one that is opening comes back, if at all, at ``t = (b + sqrt(D)) / -2a``
    with ``D = b^2 - 4 a c`` set to 0 where rounding left it negative (the turning
    point: the gap closes again there).

    Both roots are written without cancellation: for a closing gap ``b <= 0`` the root
    ``(-b - sqrt(D)) / 2a`` equals ``2c / (sqrt(D) - b)``, a sum of two non-negative
    numbers; for an opening gap ``b > 0`` the sum ``b + sqrt(D)`` is one already.
    With ``a = 0`` this is ``c / -b``, the free-flight time, to the last bit.
    """
    if b < 0.0 or (b == 0.0 and a < 0.0):  # closing now
        if c <= 0.0:
            return 0.0
        d = b * b - 4.0 * a * c
        if d < 0.0:
            return INF  # (a > 0: turns back before the boundary)
        return 2.0 * c / (math.sqrt(d) - b)
    if a >= 0.0:
        return INF  # opening (or at rest), and never turning back
    d = b * b - 4.0 * a * c
    if d < 0.0:
        d = 0.0
    return (b + math.sqrt(d)) / (-2.0 * a)


@njit
def return_time(c, b, a):
    """First ``t > 0`` at which ``q(t) = c + b t + a t^2`` falls through zero for a
    ``q(0) = c < 0`` well below it (no rounding case): ``q`` must first rise above zero,
    so it needs ``b > 0`` and ``a < 0`` and a real root, and the crossing down is the
    later root ``(b + sqrt(D)) / -2a`` (no cancellation: ``b > 0``); ``inf`` otherwise."""
    if b <= 0.0 or a >= 0.0:
        return INF
    d = b * b - 4.0 * a * c
    if d < 0.0:
        return INF
    return (b + math.sqrt(d)) / (-2.0 * a)


@njit
def box_wall_time_accel(x, vx, ax, r, length):
    """:func:`box_wall_time` for a centre with acceleration ``ax`` along the axis:
    the earlier of reaching the lower wall moving down and the upper one moving up."""
    t0 = descend_time(x - r, vx, 0.5 * ax)
    t1 = descend_time(length - r - x, -vx, -0.5 * ax)
    if t0 <= t1:
        return (t0, 0) if t0 < INF else (INF, -1)
    return t1, 1


@njit
def exit_time_accel(x, vx, ax, c, side, ncell, periodic):
    """:func:`exit_time` for a centre with acceleration ``ax`` along the axis: a disk
    moving up may turn back and leave through the lower boundary (an apex), so both
    boundaries are solved and the earlier crossing taken."""
    dn = INF
    up = INF
    if c > 0 or periodic:
        dn = descend_time(x - c * side, vx, 0.5 * ax)
    if c + 1 < ncell or periodic:
        up = descend_time((c + 1) * side - x, -vx, -0.5 * ax)
    if up < dn:
        return up, 1
    if dn < INF:
        return dn, -1
    return INF, 0


@njit
def _gap(t, px, py, vx, vy, ax, ay, d2):
    """``f(t) = |p + v t + a t^2/2|^2 - d^2`` and ``s(t) = f'(t) / 2``."""
    x = px + t * (vx + 0.5 * ax * t)
    y = py + t * (vy + 0.5 * ay * t)
    ux = vx + ax * t
    uy = vy + ay * t
    return x * x + y * y - d2, x * ux + y * uy


@njit
def _rate(t, px, py, vx, vy, ax, ay):
    """``s(t) = f'(t) / 2``, the rate at which the squared distance changes (halved)."""
    return _gap(t, px, py, vx, vy, ax, ay, 0.0)[1]


@njit
def _bisect_rate(lo, hi, px, py, vx, vy, ax, ay):
    """The zero of ``s`` in ``[lo, hi]``, where ``s`` is monotone and changes sign,
    bisected to the last bit (the turning point of the squared distance)."""
    neg_lo = _rate(lo, px, py, vx, vy, ax, ay) < 0.0
    return _bisect(0, lo, hi, neg_lo, px, py, vx, vy, ax, ay, 0.0)[0]


@njit
def _value(which, t, px, py, vx, vy, ax, ay, d2):
    """``which`` 0: ``s(t)`` and its slope; 1: ``-f(t)`` and its slope.  The value is
    computed exactly as :func:`_gap` computes it (the bisection's signs); the slope only
    guides the Newton steps of :func:`_bisect`."""
    f, s = _gap(t, px, py, vx, vy, ax, ay, d2)
    if which == 1:
        return -f, -2.0 * s
    x = px + t * (vx + 0.5 * ax * t)
    y = py + t * (vy + 0.5 * ay * t)
    ux = vx + ax * t
    uy = vy + ay * t
    return s, ux * ux + uy * uy + x * ax + y * ay


@njit
def _bisect(which, lo, hi, neg_lo, px, py, vx, vy, ax, ay, d2):
    """The adjacent floats ``(lo, hi)`` at which bisecting ``[lo, hi]`` for the sign
    change of the monotone ``v`` (:func:`_value` ``which``; ``lo``'s side: ``(v < 0)
    == neg_lo``) ends: the same two floats, bit for bit, but with about a third of the
    evaluations.

    Bisection from a wide interval to the last bit takes some 60 halvings, nearly all
    of them far from the root, where the sign of ``v`` is certain.  So the root is first
    bracketed by safeguarded Newton steps, and points ``a < root < b`` are found where
    ``|v|`` exceeds twice a bound on its rounding error over ``[lo, hi]`` (``v`` is
    monotone on it, so every point below ``a`` has ``lo``'s sign when computed, and
    every point above ``b`` has ``hi``'s).  The halvings are then replayed: a midpoint
    outside ``[a, b]`` takes its side without an evaluation, one inside is evaluated
    as before.  Within the rounding band around the root, where the computed sign may
    flip back and forth, the evaluations are the bisection's own, so the result is."""
    # A bound on the rounding error of v over [lo, hi] (0 <= t <= T): each coordinate
    # of p + v t + a t^2/2 and of v + a t is computed to within a few roundings of the
    # sum of its terms' magnitudes.
    T = max(abs(lo), abs(hi))
    xx = abs(px) + T * (abs(vx) + 0.5 * abs(ax) * T)
    xy = abs(py) + T * (abs(vy) + 0.5 * abs(ay) * T)
    if which == 0:
        err = _ROUNDING * (xx * (abs(vx) + abs(ax) * T) + xy * (abs(vy) + abs(ay) * T))
    else:
        err = _ROUNDING * (xx * xx + xy * xy + d2)
    cert = 2.0 * err
    a = lo  # certain: a midpoint at or below a is on lo's side, at or above b on hi's
    b = hi  # (the ends themselves are never midpoints)
    wl = lo
    wh = hi
    t = 0.5 * (lo + hi)
    slope = 0.0
    for _ in range(200):
        v, slope = _value(which, t, px, py, vx, vy, ax, ay, d2)
        sure = abs(v) > cert
        if (v < 0.0) == neg_lo:
            wl = t
            if sure:
                a = t
        else:
            wh = t
            if sure:
                b = t
        if not sure:
            break  # (in the rounding band around the root)
        step = t - v / slope
        if not (wl < step < wh):  # (outside the bracket, or a zero slope: halve)
            step = 0.5 * (wl + wh)
            if step <= wl or step >= wh:
                break
        t = step
    # Points a little below and above the estimate t, where the sign is certain.
    w0 = max(cert / abs(slope) if slope != 0.0 else 0.0, 4.0 * _ROUNDING * abs(t))
    w = w0
    q = t - w
    for _ in range(200):
        if q <= a:
            break
        v = _value(which, q, px, py, vx, vy, ax, ay, d2)[0]
        if abs(v) > cert:
            if (v < 0.0) == neg_lo:
                a = q
                break
            b = min(b, q)  # (the root lies below q)
        q -= w
        w *= 2.0
    w = w0
    q = t + w
    for _ in range(200):
        if q >= b:
            break
        v = _value(which, q, px, py, vx, vy, ax, ay, d2)[0]
        if abs(v) > cert:
            if (v < 0.0) != neg_lo:
                b = q
                break
            a = max(a, q)  # (the root lies above q)
        q += w
        w *= 2.0
    # The bisection, its certain steps taken without an evaluation.
    for _ in range(2200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if mid <= a:
            lo = mid
        elif mid >= b:
            hi = mid
        elif (_value(which, mid, px, py, vx, vy, ax, ay, d2)[0] < 0.0) == neg_lo:
            lo = mid
        else:
            hi = mid
    return lo, hi


@njit
def point_time(px, py, vx, vy, ax, ay, d, horizon):
    """First contact by ``horizon`` (a time, may be ``inf``) of a centre at relative
    position ``p``, velocity ``v`` and constant acceleration ``a`` (not zero) with a
    fixed point at distance ``d`` (a segment's end point, an immovable disk); ``inf``
    if none.

    ``f(t) = |p + v t + a t^2/2|^2 - d^2`` is a quartic: no closed form is stable, so
    its roots are bracketed.  ``s = f'/2`` is a cubic whose derivative
    ``s' = |v + a t|^2 + (p + v t + a t^2/2).a`` is the quadratic
    ``(v.v + p.a) + 3 (v.a) t + 1.5 (a.a) t^2``: its roots (closed form, without
    cancellation) split time into pieces on which ``s`` is monotone, each turning point
    of ``f`` (a zero of ``s``) is bisected on its piece, and between turning points
    ``f`` is monotone: the contact is the first turning-point interval on which ``f``
    falls from above zero to zero or below, bisected to the last bit (the returned
    time is the end at which ``f <= 0``: touching).  A contact the starting state
    already makes (``f(0) <= 0`` and closing) is now; bodies that touch and separate
    get their next contact, if gravity brings them back.  A dip of ``f`` that stays
    above zero is a miss (a tangential touch exchanges no momentum).

    Beyond ``T* = (|v| + sqrt(|v|^2 + 2 |a| (|p| + d))) / |a|`` the distance exceeds
    ``d`` for ever (``|a| t^2/2 - |v| t - |p| > d``), which bounds the search.
    """
    d2 = d * d
    f0, s0 = _gap(0.0, px, py, vx, vy, ax, ay, d2)
    # Touching (to rounding) and closing now, or at rest with the acceleration pressing
    # the bodies together (s = 0, s' = v.v + p.a < 0): in contact now.
    if f0 <= 0.0 and (s0 < 0.0 or (s0 == 0.0 and vx * vx + vy * vy + px * ax + py * ay
                                    < 0.0)):
        return 0.0
    aa = ax * ax + ay * ay
    amag = math.sqrt(aa)
    vmag = math.sqrt(vx * vx + vy * vy)
    pmag = math.sqrt(px * px + py * py)
    h = (vmag + math.sqrt(vmag * vmag + 2.0 * amag * (pmag + d))) / amag
    # Out of reach before the horizon: the distance shrinks by at most |v| t + |a| t^2/2.
    if horizon < h and pmag - d > horizon * (vmag + 0.5 * amag * horizon):
        return INF
    # (The search itself always spans [0, T*], so that the time found does not depend
    # on the horizon: the same contact seen from two predictions, or the shared corner
    # of two segments, gets the same time to the last bit.)
    # Pieces on which s is monotone: cut at the roots r1 <= r2 of s' in (0, h).
    c2 = 1.5 * aa
    c1 = 3.0 * (vx * ax + vy * ay)
    c0 = vx * vx + vy * vy + px * ax + py * ay
    disc = c1 * c1 - 4.0 * c2 * c0
    r1 = h
    r2 = h
    if disc > 0.0:
        q = -0.5 * (c1 + math.copysign(math.sqrt(disc), c1))
        r1 = q / c2
        r2 = c0 / q if q != 0.0 else r1
        if r1 > r2:
            r1, r2 = r2, r1
        r1 = min(max(r1, 0.0), h)
        r2 = min(max(r2, 0.0), h)
    # Walk the pieces; each zero of s ends an interval on which f is monotone.
    lo_f = 0.0
    flo = f0
    prev = 0.0
    for k in range(3):
        end = r1 if k == 0 else (r2 if k == 1 else h)
        if end <= prev:
            continue
        if (_rate(prev, px, py, vx, vy, ax, ay) < 0.0) != (
                _rate(end, px, py, vx, vy, ax, ay) < 0.0):
            turn = _bisect_rate(prev, end, px, py, vx, vy, ax, ay)
            t, flo_next = _fall(lo_f, turn, flo, px, py, vx, vy, ax, ay, d2)
            if t < INF:
                return t if t <= horizon else INF
            lo_f = turn
            flo = flo_next
        prev = end
    t = _fall(lo_f, h, flo, px, py, vx, vy, ax, ay, d2)[0]
    return t if t <= horizon else INF


@njit
def _fall(lo, hi, flo, px, py, vx, vy, ax, ay, d2):
    """On ``[lo, hi]``, where ``f`` is monotone and ``f(lo) = flo``: the time at which
    ``f`` falls through zero, bisected to the last bit, or ``inf``; and ``f(hi)``.

    Of the two adjacent floats around the root the one where ``|f|`` is smaller is
    returned (the nearest): always taking the side with ``f <= 0`` would leave every
    contact a rounding too deep, and a disk bouncing on a point for ever (elastic
    under the TC rule) would sink by that much at each bounce.  An interval that
    starts at or below zero and falls is a rebound that rounding never lifted clear of
    contact (as ``descend_time``'s turning point): the contact comes back at its
    start, the turning point."""
    fhi = _gap(hi, px, py, vx, vy, ax, ay, d2)[0]
    if flo <= 0.0:
        return (lo, fhi) if fhi < flo else (INF, fhi)
    if fhi > 0.0:
        return INF, fhi
    lo, hi = _bisect(1, lo, hi, True, px, py, vx, vy, ax, ay, d2)
    f_lo = _gap(lo, px, py, vx, vy, ax, ay, d2)[0]
    f_hi = _gap(hi, px, py, vx, vy, ax, ay, d2)[0]
    return (lo if f_lo < -f_hi else hi), fhi


@njit
def segment_time_accel(x, y, vx, vy, gx, gy, r, ax, ay, bx, by, horizon):
    """:func:`segment_time` for a disk with acceleration ``g`` (a parabolic flight).

    The signed distance of the centre from the segment's line, ``h(t)``, is a
    parabola: the contact with the side is where ``|h|`` falls to ``r`` with the foot
    point on the segment.  On the disk's own side that is :func:`descend_time` of the
    gap ``|h| - r``; but a disk can also pass beside an end, reach the other side of
    the line and come back onto the segment from there (thrown past the end of a
    shelf, it falls onto its top): that later crossing is :func:`return_time`.  The end
    points are fixed points (:func:`point_time`); the earliest valid candidate wins.
    """
    ux, uy, ll, nx, ny, h, w = _segment_frame(x, y, vx, vy, ax, ay, bx, by)
    an = 0.5 * (gx * nx + gy * ny)
    if h < 0.0:  # (look at the line from the disk's side)
        h = -h
        w = -w
        an = -an
    best = INF
    part = -1
    for k in range(2):
        if k == 0:
            dt = descend_time(h - r, w, an)
        else:
            dt = return_time(-h - r, -w, -an)
        if dt < best:
            px = x + dt * (vx + 0.5 * gx * dt)
            py = y + dt * (vy + 0.5 * gy * dt)
            s = ((px - ax) * ux + (py - ay) * uy) / ll
            if 0.0 <= s <= 1.0:
                best = dt
                part = 0
    lim = min(best, horizon)
    ta = point_time(x - ax, y - ay, vx, vy, gx, gy, r, lim)
    if ta < best:
        best = ta
        part = 1
        lim = min(best, horizon)
    tb = point_time(x - bx, y - by, vx, vy, gx, gy, r, lim)
    if tb < best:
        best = tb
        part = 2
    if best < INF:
        return best, part
    return INF, -1
