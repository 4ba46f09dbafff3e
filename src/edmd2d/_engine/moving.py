"""Wall segments that move (``layout.Motion``): contact times and the wall's motion.

A moving segment keeps its shape and orientation: at time ``t`` it is shifted from where
it was given (the arrays ``wa``, ``wb``) by ``s(t)`` along a unit direction ``d``
(:func:`shift`), at the velocity ``s'(t) d`` (:func:`speed`):

- a *translation* (``LINEAR``) rests until ``t0``, moves at the speed ``c`` until
  ``t1`` and rests from then on, ``s(t) = c (clamp(t, t0, t1) - t0)``;
- an *oscillation* (``SINE``) is ``s(t) = A sin(omega t + phase)``.

Its wall lists (``grid.bucket_walls``) hold it in every cell its whole path comes near,
so the grid stays exact as it moves with no event of its own: a disk meets it only
where it is listed, and every prediction of a disk scans its cell's list.

**Contact times.**  A translation is three pieces of constant velocity.  On each piece,
seen from the segment, the disk flies at ``v - u`` with its own acceleration, so the
exact times of a fixed segment (:func:`.predict.segment_time`,
:func:`.predict.segment_time_accel`) apply to the segment's position and the disk's
state where the piece starts; the first contact that falls inside its piece is the
one.  A contact exactly at a piece's end belongs to the next piece, at the velocity the
segment has from then on (``[t0, t1)`` is the moving piece), which is the velocity the
collision then uses.

An oscillation makes the relative motion transcendental.  Seen from the segment (its
start point ``a``, unit tangent ``e``, unit normal ``n``, length ``L``), the centre's
position is ``q(tau) = p(tau) - a - A sin(omega (t + tau) + phase) d``, whose
components along ``n`` and ``e``, the distance ``h`` from the segment's line and the
foot coordinate ``f``, are each of the form

    F(tau) = c0 + c1 tau + c2 tau^2 - k A sin(omega (t + tau) + phase)

with ``|F''| <= M = 2 |c2| + |k| A omega^2``.  The gap is ``sqrt(h^2 + out(f)^2) - r``
with ``out(f) = max(0, -f, f - L)`` (the distance to the side or to the nearer end).
On an interval ``[a, b]`` the linear interpolation of ``F`` less its error bound,
``M (tau - a)(b - tau) / 2``, bounds ``F`` from below (and, added, from above); these
bound ``|h|`` and ``out(f)`` from below, and an interval on which the squares of those
bounds add up to more than ``(r + tol)^2`` holds no contact.  The search splits the
horizon in halves, left half first, drops every interval so cleared, and stops at the
first interval of the finest width (``2^-MAX_DEPTH`` of the horizon, or adjacent
floating-point numbers) whose gap falls from positive to not: the contact time is
that interval's start, where the disk does not yet touch the segment.  So no contact is
missed whose depth, had it been missed, exceeds ``tol`` (``TOL_REL`` of ``r`` plus the
amplitude); a graze shallower than that may pass unseen.  Each step of the search
costs one evaluation of the gap; a transversal contact is reached in about
``MAX_DEPTH`` steps, an interval far from the segment is cleared in few.

The horizon is the disk's next other event: the prediction passes its cell exit (a new
cell is scanned again), or, for a disk that stands still, one period of the wall (the
relative motion then repeats).
"""

from __future__ import annotations

import math

from .._jit import njit
from . import predict as _predict
from .layout import (
    FIXED,
    LINEAR,
    M_AMPLITUDE,
    M_BEGIN,
    M_DX,
    M_DY,
    M_END,
    M_OMEGA,
    M_PHASE,
    M_SPEED,
    pack_segment,
    pack_shift,
)
from .predict import INF

#: The deepest halving of the horizon in the oscillating wall's search.
MAX_DEPTH = 62
#: The depth, relative to ``r + A``, below which a graze of an oscillating wall may go
#: unseen (the margin of the search's lower bounds against rounding).
TOL_REL = 2.0**-48
#: The gap, relative to ``r + A``, that a disk leaving an oscillating segment at the
#: parting speed opens at least before the segment can catch up (:func:`parting`).
PARTING_REL = 2.0**-40
#: The most intervals the search examines: beyond, the disk is taken to touch the
#: segment where the search stands (a contact it then leaves at :func:`parting`).  The
#: quadratic part's range clears at once the stretches where a disk stays beyond the
#: sine's reach, so that the search needs many intervals only while the disk is within
#: the segment's sweep, where it is hit within a period: never reached in the tests.
MAX_STEPS = 1 << 20


@njit(inline="always")
def _reach(w, gx, gy, motion):
    """The largest acceleration of a disk (``g``) relative to the oscillating
    segment ``w``: ``|g| + A omega^2``."""
    amp = motion.par[w, M_AMPLITUDE]
    omega = motion.par[w, M_OMEGA]
    return amp * omega * omega + math.sqrt(gx * gx + gy * gy)


@njit(inline="always")
def parting(r, w, gx, gy, motion):
    """The least speed at which a disk of radius ``r`` leaves the oscillating segment
    ``w`` after a contact: ``sqrt(2 a tol)``, ``a`` the largest relative acceleration
    (``A omega^2`` plus gravity's) and ``tol`` :data:`PARTING_REL` of ``r + A``, so that
    the gap opens to ``tol / 4`` at least before the segment can catch up again.
    Slower, the segment would catch it before the gap opened beyond rounding, without
    end (a disk lying on a floor that accelerates upwards is the case): this speed,
    given by the segment (its work is tallied), keeps every contact a separate event.
    0 for a translation (no acceleration)."""
    if motion.kind[w] == LINEAR:
        return 0.0
    tol = PARTING_REL * (r + motion.par[w, M_AMPLITUDE])
    return math.sqrt(2.0 * _reach(w, gx, gy, motion) * tol)


@njit(inline="always")
def shift(w, t, motion):
    """How far segment ``w`` is shifted at time ``t`` along its direction."""
    par = motion.par
    if motion.kind[w] == LINEAR:
        return par[w, M_SPEED] * (min(max(t, par[w, M_BEGIN]), par[w, M_END]) - par[w, M_BEGIN])
    return par[w, M_AMPLITUDE] * math.sin(par[w, M_OMEGA] * t + par[w, M_PHASE])


@njit(inline="always")
def speed(w, t, motion):
    """The speed of segment ``w`` along its direction at time ``t``."""
    par = motion.par
    if motion.kind[w] == LINEAR:
        return par[w, M_SPEED] if par[w, M_BEGIN] <= t < par[w, M_END] else 0.0
    return (par[w, M_AMPLITUDE] * par[w, M_OMEGA]
            * math.cos(par[w, M_OMEGA] * t + par[w, M_PHASE]))


@njit
def scan_walls(t, x, y, vx, vy, gx, gy, r, c, cx, cy, gi, gf, wa, wb, wstart, wwall, wsx,
               wsy, best, gravity, motion):
    """Earliest contact with the wall segments listed for cell ``c`` (the disk's, at
    ``(cx, cy)``), if before ``best``: ``(dt, segment, aux)`` as the prediction's scan of
    fixed segments gives them, a moving segment searched up to the disk's cell exit
    at the latest (a partial or full scan after the crossing takes it up again)."""
    partner = -1
    aux = 0
    if wa.shape[0] == 0:
        return best, partner, aux
    horizon = -1.0  # (the cell exit, found at the first moving segment of the list)
    for k in range(wstart[c], wstart[c + 1]):
        w = wwall[k]
        shx = wsx[k] * gf[0]
        shy = wsy[k] * gf[1]
        ax = wa[w, 0] + shx
        ay = wa[w, 1] + shy
        bx = wb[w, 0] + shx
        by = wb[w, 1] + shy
        if motion.kind[w] != FIXED:
            if horizon < 0.0:
                if gravity is None:
                    dtx, _ = _predict.exit_time(x, vx, cx, gf[2], gi[0], gi[2] != 0)
                    dty, _ = _predict.exit_time(y, vy, cy, gf[3], gi[1], gi[3] != 0)
                else:
                    dtx, _ = _predict.exit_time_accel(x, vx, gx, cx, gf[2], gi[0],
                                                      gi[2] != 0)
                    dty, _ = _predict.exit_time_accel(y, vy, gy, cy, gf[3], gi[1],
                                                      gi[3] != 0)
                horizon = min(dtx, dty)
            dtw, part = contact_time(t, x, y, vx, vy, gx, gy, r, ax, ay, bx, by, w, motion,
                                     min(best, horizon))
        elif gx == 0.0 and gy == 0.0:
            dtw, part = _predict.segment_time(x, y, vx, vy, r, ax, ay, bx, by)
        else:
            dtw, part = _predict.segment_time_accel(x, y, vx, vy, gx, gy, r, ax, ay, bx, by,
                                                    best)
        if dtw < best:
            best = dtw
            partner = w
            aux = pack_segment(part, pack_shift(wsx[k], wsy[k]))
    return best, partner, aux


@njit
def contact_time(t, x, y, vx, vy, gx, gy, r, ax, ay, bx, by, w, motion, horizon):
    """First contact, within ``horizon``, of a disk (centre ``(x, y)`` at time ``t``,
    velocity ``v``, acceleration ``g``, radius ``r``) with the moving segment ``w``
    given as ``a -> b`` (image shift included, the motion's shift not): ``(dt, part)``
    as :func:`.predict.segment_time`."""
    if motion.kind[w] == LINEAR:
        return _translation_time(t, x, y, vx, vy, gx, gy, r, ax, ay, bx, by, w, motion,
                                 horizon)
    return _oscillation_time(t, x, y, vx, vy, gx, gy, r, ax, ay, bx, by, w, motion, horizon)


@njit
def _translation_time(t, x, y, vx, vy, gx, gy, r, ax, ay, bx, by, w, motion, horizon):
    par = motion.par
    dx = par[w, M_DX]
    dy = par[w, M_DY]
    c = par[w, M_SPEED]
    t0 = par[w, M_BEGIN]
    t1 = par[w, M_END]
    accel = gx != 0.0 or gy != 0.0
    for piece in range(3):
        lo = -INF if piece == 0 else (t0 if piece == 1 else t1)
        hi = t0 if piece == 0 else (t1 if piece == 1 else INF)
        if t >= hi:
            continue
        ts = max(t, lo)
        dts = ts - t
        if dts >= horizon:
            break
        u = c if piece == 1 else 0.0
        s = shift(w, ts, motion)
        sx = s * dx
        sy = s * dy
        px = x + dts * (vx + 0.5 * gx * dts)
        py = y + dts * (vy + 0.5 * gy * dts)
        qx = vx + gx * dts - u * dx
        qy = vy + gy * dts - u * dy
        if accel:
            dtw, part = _predict.segment_time_accel(px, py, qx, qy, gx, gy, r, ax + sx,
                                                    ay + sy, bx + sx, by + sy, horizon - dts)
        else:
            dtw, part = _predict.segment_time(px, py, qx, qy, r, ax + sx, ay + sy, bx + sx,
                                              by + sy)
        if dtw < INF and ts + dtw < hi:
            return dts + dtw, part
    return INF, -1


@njit(inline="always")
def _value(tau, c0, c1, c2, k, amp, omega, theta):
    """``c0 + c1 tau + c2 tau^2 - k A sin(omega tau + theta)`` (``theta`` the phase
    at the prediction's time)."""
    return c0 + tau * (c1 + c2 * tau) - k * amp * math.sin(omega * tau + theta)


@njit(inline="always")
def _out(f, length):
    """How far the foot ``f`` lies beyond the segment ``[0, length]``."""
    return max(-f, f - length, 0.0)


@njit(inline="always")
def _part(f, length):
    """The part of the segment nearest a centre whose foot is ``f``: 0 the side, 1 the
    start point, 2 the end point (as ``predict.segment_time``)."""
    return 1 if f < 0.0 else (2 if f > length else 0)


@njit(inline="always")
def _span(c0, c1, c2, a, b):
    """The least and the largest value of ``c0 + c1 tau + c2 tau^2`` on ``[a, b]``."""
    pa = c0 + a * (c1 + c2 * a)
    pb = c0 + b * (c1 + c2 * b)
    lo = min(pa, pb)
    hi = max(pa, pb)
    if c2 != 0.0:
        v = -0.5 * c1 / c2
        if a < v < b:
            pv = c0 + v * (c1 + c2 * v)
            lo = min(lo, pv)
            hi = max(hi, pv)
    return lo, hi


@njit(inline="always")
def _low(fa, fb, m, width):
    """The least value on an interval of ``width`` of a function with values ``fa``,
    ``fb`` at its ends and ``|F''| <= m``: the minimum of its linear interpolation less
    ``m (tau - a)(b - tau) / 2``."""
    if m == 0.0:
        return min(fa, fb)
    q = 0.5 * m * width * width
    z = 0.5 - (fb - fa) / (2.0 * q)
    z = min(max(z, 0.0), 1.0)
    return fa + (fb - fa) * z + q * (z * z - z)


@njit
def _oscillation_time(t, x, y, vx, vy, gx, gy, r, ax, ay, bx, by, w, motion, horizon):
    par = motion.par
    dx = par[w, M_DX]
    dy = par[w, M_DY]
    amp = par[w, M_AMPLITUDE]
    omega = par[w, M_OMEGA]
    theta = omega * t + par[w, M_PHASE]
    if horizon == INF:
        # (A disk that stands still: the relative motion repeats every period.)
        horizon = 2.0 * math.pi / omega
    ux = bx - ax
    uy = by - ay
    length = math.sqrt(ux * ux + uy * uy)
    ex = ux / length
    ey = uy / length
    nx = -ey
    ny = ex
    # h(tau) along n and f(tau) along e.
    px = x - ax
    py = y - ay
    kh = nx * dx + ny * dy
    kf = ex * dx + ey * dy
    h0 = px * nx + py * ny
    h1 = vx * nx + vy * ny
    h2 = 0.5 * (gx * nx + gy * ny)
    f0 = px * ex + py * ey
    f1 = vx * ex + vy * ey
    f2 = 0.5 * (gx * ex + gy * ey)
    mh = 2.0 * abs(h2) + abs(kh) * amp * omega * omega
    mf = 2.0 * abs(f2) + abs(kf) * amp * omega * omega
    mq = _reach(w, gx, gy, motion)  # (the relative flight's largest acceleration)
    ah = abs(kh) * amp
    af = abs(kf) * amp
    tol = TOL_REL * (r + amp)
    reach = r + tol
    reach2 = reach * reach
    r2 = r * r
    # Touching now, to within the search's tolerance (just after a contact, say): a
    # contact now unless the gap opens at half the parting speed at least (a contact
    # sends it off at the full speed: the margin keeps rounding from making that contact
    # again at once).  If it opens, no contact can come before ``rate / a`` (the gap is
    # at least ``rate tau - a tau^2 / 2`` less rounding), and there it is open beyond
    # rounding: the search starts from then.
    start = 0.0
    ha = _value(0.0, h0, h1, h2, kh, amp, omega, theta)
    fa = _value(0.0, f0, f1, f2, kf, amp, omega, theta)
    oa = _out(fa, length)
    dist = math.sqrt(ha * ha + oa * oa)
    if dist <= reach:
        vw = amp * omega * math.cos(theta)
        dh = h1 - kh * vw
        df = f1 - kf * vw
        rate = (ha * dh + (0.0 if oa == 0.0 else (fa if fa < 0.0 else fa - length) * df)
                ) / dist
        if rate < 0.5 * parting(r, w, gx, gy, motion):
            return 0.0, _part(fa, length)
        start = rate / mq
        if start >= horizon:
            return INF, -1
        ha = _value(start, h0, h1, h2, kh, amp, omega, theta)
        fa = _value(start, f0, f1, f2, kf, amp, omega, theta)
        oa = _out(fa, length)
    # The dyadic intervals start + [j, j + 1] * span / 2^depth, visited in order of time.
    span = horizon - start
    depth = 0
    j = 0
    a = start
    steps = 0
    while True:
        steps += 1
        if steps > MAX_STEPS:
            return a, _part(fa, length)
        width = span / 2.0**depth
        b = start + (j + 1) * width
        hb = _value(b, h0, h1, h2, kh, amp, omega, theta)
        fb = _value(b, f0, f1, f2, kf, amp, omega, theta)
        # Bounds of h and f on [a, b]: the interpolation's, and the quadratic part's
        # range widened by the sine's amplitude (which clears long stretches at once
        # where the disk stays beyond the segment's reach); then lower bounds of |h|
        # and of out(f).
        plo, phi = _span(h0, h1, h2, a, b)
        low = max(_low(ha, hb, mh, width), plo - ah)
        high = min(-_low(-ha, -hb, mh, width), phi + ah)
        bh = low if low > 0.0 else (-high if high < 0.0 else 0.0)
        plo, phi = _span(f0, f1, f2, a, b)
        low = max(_low(fa, fb, mf, width), plo - af)
        high = min(-_low(-fa, -fb, mf, width), phi + af)
        bf = max(-high, low - length, 0.0)
        cleared = bh * bh + bf * bf > reach2
        if not cleared:
            ob = _out(fb, length)
            falls = ha * ha + oa * oa > r2 and hb * hb + ob * ob <= r2
            if falls and (
                    mq * width * width <= 8.0 * tol or (
                        ha * hb > 0.0 and _low(fa, fb, mf, width) >= 0.0
                        and -_low(-fa, -fb, mf, width) <= length
                        and abs(h1 + 2.0 * h2 * a - kh * amp * omega
                                * math.cos(omega * a + theta)) > mh * width)):
                # The gap falls from positive to not, and the contact in between is
                # the first: the flight is straight there to within ``tol`` (the
                # distance from a straight line to the segment is convex), or the foot
                # stays on the side while the distance from the line changes
                # monotonically.  Halve it down to adjacent floating-point numbers.
                b_ = b
                while True:
                    mid = 0.5 * (a + b_)
                    if not a < mid < b_:
                        break
                    hm = _value(mid, h0, h1, h2, kh, amp, omega, theta)
                    fm = _value(mid, f0, f1, f2, kf, amp, omega, theta)
                    om = _out(fm, length)
                    if hm * hm + om * om > r2:
                        a = mid
                        fa = fm
                    else:
                        b_ = mid
                return a, _part(fa, length)
            mid = a + 0.5 * width
            if depth < MAX_DEPTH and a < mid < b:
                depth += 1  # look at the left half first
                j *= 2
                continue
            # The finest interval: a contact if the gap falls from positive to not.
            if falls:
                return a, _part(fa, length)
        # On to the next interval: up while this one is a right half.
        while j % 2 == 1:
            j //= 2
            depth -= 1
        j += 1
        if depth == 0 and j >= 1:
            return INF, -1
        a = b
        ha = hb
        fa = fb
        oa = _out(fa, length)
