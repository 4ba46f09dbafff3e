"""The contact-time oracles: when two given trajectories first touch.

Pure functions of positions, velocities, accelerations and sizes, one for each kind of
contact: two disks (straight flight, growing radii, or one of them accelerated), a disk
and a wall segment (its side or an end point), fixed or moving, a disk and the box walls
of one axis.  Under acceleration the contact functions are polynomials of degree up to
four, whose first crossing of zero :func:`_crossings` finds from the signs of the
geometry.  A translating segment is fixed in its own frame, phase by phase; against an
oscillating one, conservative advancement finds the first root of the gap.
"""

from __future__ import annotations

import math

import numpy as np

INF = math.inf
EPS = np.finfo(float).eps  # the unit roundoff times 2


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
    if vv == 0.0:  # (a speed whose square underflows: no contact in any finite time)
        return INF
    disc = vp * vp - vv * (_dot(p, p) - d * d)
    if disc <= 0:  # miss, or a touch without momentum exchange
        return INF
    t = -(vp + math.sqrt(disc)) / vv
    return max(t, 0.0)  # already touching and approaching: now


def circle_contact_time_growing(p, v, d, dd):
    """Earliest t >= 0 with |p + t v| = d + dd t, the distance closing there, else inf:
    the contact of two circles whose radii grow at speeds adding up to ``dd``.

    The square of the condition is the quadratic ``A t^2 + 2 B t + C = 0`` with
    ``A = v.v - dd^2``, ``B = v.p - d dd``, ``C = p.p - d^2``.  Where the gap closes
    the quadratic falls through zero: the smaller root if ``A > 0``, the larger if
    ``A < 0`` (then it opens upwards between them), ``-C / 2B`` if ``A = 0``.  Written
    as the textbook roots.  Overlapping already (``C <= 0``, by rounding) while the
    gap closes, or with no root at all: now.
    """
    a = _dot(v, v) - dd * dd
    b = _dot(v, p) - d * dd
    c = _dot(p, p) - d * d
    if c <= 0.0 and b < 0.0:
        return 0.0
    if a == 0.0:
        return -c / (2.0 * b) if b < 0.0 else INF
    disc = b * b - a * c
    if disc < 0.0:
        return 0.0 if c < 0.0 else INF  # (a < 0: overlapping for good; a > 0: a miss)
    if a > 0.0 and (b >= 0.0 or disc == 0.0):
        return INF  # moving apart, or a touch without momentum exchange
    # The smaller root for a > 0, the larger for a < 0: the same expression.
    return max((-b - math.sqrt(disc)) / a, 0.0)


def segment_contact_time(p, v, r, a, b, dr=None):
    """Earliest contact of a circle (p, v, r) with the segment a-b: its side or an end point.

    Returns (t, part) with part "side", "start" or "end"; (inf, None) if none.  With
    ``dr`` the circle's radius grows at that speed.
    """
    if dr is None:
        def contact(q, w, d):
            return circle_contact_time(q, w, d)
    else:
        def contact(q, w, d):
            return circle_contact_time_growing(q, w, d, dr)
    u = (b[0] - a[0], b[1] - a[1])
    uu = _dot(u, u)
    rel = (p[0] - a[0], p[1] - a[1])
    # q: the projection of p - a on the wall; p~, v~: the components normal to the wall.
    q = _dot(rel, u) / uu
    pt = (rel[0] - q * u[0], rel[1] - q * u[1])
    k = _dot(v, u) / uu
    vt = (v[0] - k * u[0], v[1] - k * u[1])
    best, part = INF, None
    t = contact(pt, vt, r)
    if t < INF:
        s = q + t * k  # where along the wall the contact happens
        if 0.0 <= s <= 1.0:
            best, part = t, "side"
    for name, e in (("start", a), ("end", b)):
        t = contact((p[0] - e[0], p[1] - e[1]), v, r)
        if t < best:
            best, part = t, name
    return best, part


def _at(p, v, a, t):
    """Position at time ``t`` of a body at ``p`` with velocity ``v`` and acceleration ``a``.

    The drift and the wall contact functions compute ``p + v t + a t^2 / 2`` with the
    same arithmetic, so that a disk moved to the time of a wall contact is where the
    search saw it (touching or overlapping by rounding, not short of the wall).
    """
    h = 0.5 * t * t
    return (p[0] + t * v[0] + h * a[0], p[1] + t * v[1] + h * a[1])


def _trim(c):
    """The coefficients without leading (highest-power) zeros."""
    k = 0
    while k < len(c) and c[k] == 0.0:
        k += 1
    return list(c[k:])


def _root_real_parts(c):
    """Real parts of all complex roots of the polynomial ``c`` (highest power first).

    Found with :func:`numpy.roots` (the eigenvalues of the companion matrix).  Roots
    with an imaginary part are kept too: a near-double root comes out as a complex pair
    whose real part is the place where the two real roots (or their near miss) are.
    """
    c = _trim(c)
    if len(c) <= 1:
        return []
    if len(c) == 2:
        return [-c[1] / c[0]]
    return [float(z.real) for z in np.roots(c)]


def _root_bound(c):
    """A bound above the modulus of every root of ``c`` (trimmed, degree >= 1).

    Fujiwara's bound ``2 max_k |c_k / c_0|^(1/k)``, itself doubled so that the
    polynomial's sign there is the sign of its leading coefficient beyond rounding.
    """
    return 4.0 * max(abs(c[k] / c[0]) ** (1.0 / k) for k in range(1, len(c)))


def _first_nonpositive(f, df, lo, hi, flo, fhi):
    """The float ``t`` in ``(lo, hi]`` where ``f`` turns from > 0 to <= 0.

    ``f`` decreases on ``[lo, hi]`` with ``flo = f(lo) > 0 >= f(hi) = fhi``.  Three
    stages, each evaluation narrowing the bracket ``lo < t <= hi`` by the sign of ``f``:

    1. Newton's method from the secant point, a step that leaves the bracket replaced by
       a bisection, until the step is a few units in the last place;
    2. steps of 1, 4, 16, ... units in the last place from there across the crossing,
       until the sign flips: a bracket a few floats wide;
    3. bisection until ``lo`` and ``hi`` are adjacent floats.

    Returns ``hi``, the first float at which ``f <= 0``.
    """
    t = lo + flo * ((hi - lo) / (flo - fhi))
    if not lo < t < hi:
        t = lo + 0.5 * (hi - lo)
    for _ in range(100):
        ft = f(t)
        if ft > 0.0:
            lo = t
        else:
            hi = t
        slope = df(t)
        nxt = t - ft / slope if slope < 0.0 else -INF
        if abs(nxt - t) <= 4.0 * math.ulp(t):
            break
        t = nxt if lo < nxt < hi else lo + 0.5 * (hi - lo)
        if not lo < t < hi:
            return hi
    step, up = math.ulp(t), t == lo
    while True:
        probe = t + step if up else t - step
        if not lo < probe < hi:
            break
        if f(probe) > 0.0:
            lo = probe
            if not up:
                break
        else:
            hi = probe
            if up:
                break
        step *= 4.0
    while True:
        mid = lo + 0.5 * (hi - lo)
        if not lo < mid < hi:
            return hi
        if f(mid) > 0.0:
            lo = mid
        else:
            hi = mid


def _crossings(coeffs, f, df, noise):
    """Every time ``t >= 0``, in order, at which ``f`` turns from > 0 to <= 0.

    ``coeffs`` are the coefficients of the polynomial ``f`` (highest power first); ``f``
    and ``df`` evaluate it and its derivative accurately (from the geometry rather than
    from the coefficients), and ``noise(t)`` bounds the rounding error of ``f(t)``.  A
    contact function ``f`` (a squared distance minus its square at contact, or a gap) is
    positive while the bodies are apart, so these are the moments they come into
    contact.

    * The real parts of all roots of the derivative (:func:`numpy.roots`), between 0 and
      a bound beyond every root of ``f``, cut ``[0, bound]`` into pieces on each of
      which ``f`` is monotonic.  Extra cuts (real parts of complex roots) do no harm,
      and no real root of the derivative is lost to a small imaginary part.
    * ``t = 0`` counts if ``f(0) <= 0`` and ``df(0) < 0``: the bodies touch or overlap
      by rounding and approach.
    * A piece with ``f > 0`` at its left end and ``f <= 0`` at its right end holds one
      crossing, located by :func:`_first_nonpositive`.

    A crossing counts only if ``df < 0`` there and the minimum of ``f`` that follows
    (at the next cut where ``f`` stops falling; none if ``f`` falls for ever) is below
    ``-noise``.  The first check drops a sign flip of rounding noise where ``f`` rises
    through zero (two bodies that just collided and separate); the second a tangential
    touch, a double root, whose minimum is zero to rounding: it exchanges no momentum.
    Apart from that the computed sign of ``f`` decides everything, so a near-double root
    (two close real roots, or a complex pair with a small imaginary part) is a crossing
    exactly when ``f`` dips below zero between them, whatever :func:`numpy.roots` made
    of it.
    """
    c = _trim(coeffs)
    if len(c) < 2:
        return
    bound = _root_bound(c)
    if bound == 0.0:  # every root at 0 (f = c t^n): any t > 0 is beyond them
        bound = 1.0
    if not bound < INF:
        return
    derivative = [c[k] * (len(c) - 1 - k) for k in range(len(c) - 1)]
    cuts = sorted({t for t in _root_real_parts(derivative) if 0.0 < t < bound})
    points = [0.0, *cuts, bound]
    values = [f(t) for t in points]

    def deep(k):
        # The local minimum from point k on: follow the cuts while f falls.  Past the
        # last cut f falls for ever if its leading coefficient is negative.
        while k + 1 < len(values) and values[k + 1] < values[k]:
            k += 1
        return (k == len(values) - 1 and c[0] < 0.0) or values[k] < -noise(points[k])

    # (Touching and closing, or at rest with f'' < 0: pressed together, e.g. a disk at
    # rest on a peg or on a disk held by the floor.  c[-3] is f''(0) / 2.)
    slope0 = df(0.0)
    pressed = slope0 == 0.0 and len(c) >= 3 and c[-3] < 0.0
    if values[0] <= 0.0 and (slope0 < 0.0 or pressed) and deep(0):
        yield 0.0
    for k in range(len(points) - 1):
        if values[k] > 0.0 and values[k + 1] <= 0.0 and deep(k + 1):
            t = _first_nonpositive(f, df, points[k], points[k + 1], values[k], values[k + 1])
            if df(t) < 0.0:
                yield t


def _sum_abs(*vectors):
    """``sum |x_k|``: the scale of the terms that make up a coordinate."""
    return sum(abs(x) for vec in vectors for x in vec)


def circle_contact_time_accelerated(p, v, a, d):
    """Earliest contact of two bodies whose relative position is ``p + v t + a t^2/2``.

    ``p``, ``v``, ``a``: relative position, velocity and acceleration (a disk against an
    immovable disk or a wall end point: ``a = g``); ``d`` the distance at contact.
    ``f(t) = |p + v t + a t^2/2|^2 - d^2`` is a quartic,

        (a.a/4) t^4 + (a.v) t^3 + (v.v + a.p) t^2 + 2 (v.p) t + p.p - d^2,

    and the contact is its first crossing from > 0 to <= 0 (:func:`_crossings`).
    Returns the time, or inf.
    """
    def rel(t):
        return _at(p, v, a, t)

    def f(t):
        x, y = rel(t)
        return x * x + y * y - d * d

    def df(t):
        x, y = rel(t)
        return 2.0 * (x * (v[0] + t * a[0]) + y * (v[1] + t * a[1]))

    def noise(t):
        # Each coordinate is a sum of terms of size ~terms, rounded; f adds squares.
        x, y = rel(t)
        terms = _sum_abs(p) + t * _sum_abs(v) + 0.5 * t * t * _sum_abs(a)
        return 8.0 * EPS * (2.0 * math.hypot(x, y) * terms + x * x + y * y + d * d)

    coeffs = [0.25 * _dot(a, a), _dot(a, v), _dot(v, v) + _dot(a, p), 2.0 * _dot(v, p),
              _dot(p, p) - d * d]
    return next(_crossings(coeffs, f, df, noise), INF)


def segment_contact_time_accelerated(p, v, g, r, a, b):
    """Earliest contact of a disk (p, v, r) accelerated by ``g`` with the segment a-b.

    Returns (t, part) with part "side", "start" or "end"; (inf, None) if none.

    Side: with ``n`` the unit normal of the line and ``d(t) = n.(x(t) - a)`` the signed
    distance of the centre, a parabola in ``t``, the disk starts to overlap the line
    when ``F(t) = d^2 - r^2`` (a quartic) crosses from > 0 to <= 0: ``d`` reaches ``+r``
    from above or ``-r`` from below.  That is a side contact if the foot of the centre,
    ``s = u.(x(t) - a) / u.u``, is on the segment, ``0 <= s <= 1``.  Every crossing is
    tried in order, not only the first: a disk can pass beside the end of a segment and
    come back onto its side.  End points: :func:`circle_contact_time_accelerated`.
    """
    u = (b[0] - a[0], b[1] - a[1])
    uu = _dot(u, u)
    length = math.sqrt(uu)
    n = (-u[1] / length, u[0] / length)

    def dist(t):
        x, y = _at(p, v, g, t)
        return n[0] * (x - a[0]) + n[1] * (y - a[1])

    def f(t):
        s = dist(t)
        return (s - r) * (s + r)

    def df(t):
        return 2.0 * dist(t) * (n[0] * (v[0] + t * g[0]) + n[1] * (v[1] + t * g[1]))

    def noise(t):
        s = dist(t)
        terms = _sum_abs(p, a) + t * _sum_abs(v) + 0.5 * t * t * _sum_abs(g)
        return 8.0 * EPS * (2.0 * abs(s) * terms + s * s + r * r)

    d0 = n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1])
    d1 = _dot(n, v)
    d2 = 0.5 * _dot(n, g)
    coeffs = [d2 * d2, 2.0 * d2 * d1, d1 * d1 + 2.0 * d2 * d0, 2.0 * d1 * d0, d0 * d0 - r * r]
    best, part = INF, None
    for t in _crossings(coeffs, f, df, noise):
        x, y = _at(p, v, g, t)
        s = (u[0] * (x - a[0]) + u[1] * (y - a[1])) / uu
        if 0.0 <= s <= 1.0:
            best, part = t, "side"
            break
    for name, e in (("start", a), ("end", b)):
        t = circle_contact_time_accelerated((p[0] - e[0], p[1] - e[1]), v, g, r)
        if t < best:
            best, part = t, name
    return best, part


def box_contact_time_accelerated(x, v, g, r, length):
    """Earliest contact of a disk (coordinate x, velocity v, acceleration g along one
    axis, radius r) with the walls at 0 and ``length`` of that axis: (t, upper).

    The gaps ``x(t) - r`` and ``length - r - x(t)`` are parabolas in ``t``; a contact is
    a gap's crossing from > 0 to <= 0 (:func:`_crossings`), so a disk moving away from a
    wall can still come back to it.  ``upper`` tells which wall; (inf, None) if none.
    """
    def pos(t):
        return x + t * v + (0.5 * t * t) * g

    def noise(t):
        return 8.0 * EPS * (abs(x) + t * abs(v) + 0.5 * t * t * abs(g) + r + length)

    def lower_gap(t):
        return pos(t) - r

    def upper_gap(t):
        return length - r - pos(t)

    def lower_slope(t):
        return v + t * g

    def upper_slope(t):
        return -(v + t * g)

    lower = next(_crossings([0.5 * g, v, x - r], lower_gap, lower_slope, noise), INF)
    upper = next(_crossings([-0.5 * g, -v, length - r - x], upper_gap, upper_slope, noise),
                 INF)
    if lower == upper == INF:
        return INF, None
    return (lower, False) if lower <= upper else (upper, True)


# -- wall segments that move (see ReferenceSimulation's ``wall_motions``) ----------------
#
# A moving segment keeps its orientation: at clock t its end points are a + S(t) and
# b + S(t), S the motion's ``shift``.  The oracles below take the end points as given
# (S = 0) and the clock ``t0`` of the disk's state; they return (t, part, u): the time
# from t0, the part hit and the segment's velocity at the contact.

#: The most steps :func:`oscillating_segment_contact_time` takes before it gives up.
MAX_ADVANCES = 100_000


def _shift(motion, t):
    """The motion's displacement at clock ``t``, a pair of floats."""
    s = motion.shift(t)
    return (float(s[0]), float(s[1]))


def _wall_velocity(motion, t):
    """The motion's velocity at clock ``t``, a pair of floats."""
    u = motion.velocity_at(t)
    return (float(u[0]), float(u[1]))


def translating_segment_contact_time(p, v, g, r, a, b, motion, t0):
    """Earliest contact of a disk (p, v, r) accelerated by ``g`` with the segment a-b
    that ``motion``, a :class:`~edmd2d.Translation` with its ``begin`` set, carries.

    The segment rests until ``begin``, moves at ``u = motion.velocity`` until ``end``,
    and rests from then on: up to three phases from ``t0``.  Within a phase the segment's
    velocity ``u`` is constant, so in its frame the disk starts where it is at the
    phase's start ``ts`` (its position ``p + v (ts - t0) + g (ts - t0)^2 / 2``), with
    velocity ``v + g (ts - t0) - u`` and acceleration ``g``, against the segment fixed
    where it is at ``ts``: the oracles of fixed segments (:func:`segment_contact_time`,
    :func:`segment_contact_time_accelerated`) give the contact.  The first contact that
    lies inside its phase wins.

    Returns
    -------
    tuple
        ``(t, part, u)``: the time from ``t0``, the part ("side", "start", "end") and
        the segment's velocity in that phase; ``(inf, None, None)`` if none.
    """
    begin, end = motion.begin, motion.end
    starts = [t0, *(t for t in (begin, end) if t > t0)]
    for k, ts in enumerate(starts):
        te = starts[k + 1] if k + 1 < len(starts) else INF
        u = motion.velocity if begin <= ts < end else (0.0, 0.0)
        tau = ts - t0
        x = _at(p, v, g, tau)
        w = (v[0] + tau * g[0] - u[0], v[1] + tau * g[1] - u[1])
        s = _shift(motion, ts)
        a_s, b_s = (a[0] + s[0], a[1] + s[1]), (b[0] + s[0], b[1] + s[1])
        if g[0] == 0.0 and g[1] == 0.0:
            t, part = segment_contact_time(x, w, r, a_s, b_s)
        else:
            t, part = segment_contact_time_accelerated(x, w, g, r, a_s, b_s)
        if t < te - ts:
            return tau + t, part, (float(u[0]), float(u[1]))
    return INF, None, None


def oscillating_segment_contact_time(p, v, g, r, a, b, motion, t0, limit):
    """Earliest contact within ``limit`` of a disk (p, v, r) accelerated by ``g`` with
    the segment a-b that ``motion``, an :class:`~edmd2d.Oscillation`, shakes.

    The relative motion is not a polynomial, so the first root of the gap
    ``G(t) = dist(x(t), segment(t)) - r`` (``x(t) = p + v t + g t^2/2``, the segment
    at clock ``t0 + t``) is found by *conservative advancement*: from a time at which
    ``G > 0`` a step that provably cannot pass a root, repeated.  Two bounds give the
    step ``h``, the larger of the two:

    * first order: ``|G'| <= V``, a bound on the relative speed ``|v + g t - u(t)| <=
      |v + g t| + |g| h + A omega`` over the step, so ``G`` stays positive for
      ``h < G / V``;
    * second order: while the disk does not overlap the segment, its distance ``D`` to it
      is at least ``r``, and the gradient of the distance to a segment (a convex set)
      turns at most at ``|X'| / D``: ``G'`` is Lipschitz with ``M = V^2 / r + |g| + A
      omega^2`` (``A omega^2`` bounds the segment's acceleration), so ``G(t + h) >= G +
      G' h - M h^2 / 2``, positive up to the smaller positive root of the right side.

    The second bound keeps the steps long where the first stalls: next to a segment the
    disk just bounced off (``G = 0``, opening) and at a near miss.  The bounds hold over
    a window that the step never leaves; the window is the rest of ``[0, limit]``, or
    twice the step if that was less than half of it (its bounds are then smaller).

    Towards a simple root the steps close in on it from the safe side, like Newton's
    method.  Once the computed gap is ``<= 0`` while closing (``G' < 0``), the contact
    lies between the last time at which ``G > 0`` and the time reached, and bisection on
    the sign of ``G`` finds the first float at which ``G <= 0``: the contact, if the gap
    closes there (``G' < 0``, as every contact returned); touching and closing at the
    start, it is now.  Where the computed gap is within its rounding error ``eps_G`` of
    zero, or below, but not closing (``G' >= 0``), the disk touches without closing:
    no contact, and the advance goes on as from a gap ``eps_G``.

    Accuracy: a contact's time is the first float at which the computed gap is ``<= 0``
    after one at which it is positive: the full double precision that the gap's own
    rounding allows (an error of about ``eps_G / |G'|``).  No contact within ``limit``
    is missed but a tangential touch whose gap dips below zero by at most ``2 eps_G``,
    rounding, at a closing speed that vanishes with it.  More than
    :data:`MAX_ADVANCES` steps (a graze that converges too slowly) raise
    :class:`RuntimeError`, never a wrong answer.

    Parameters
    ----------
    p, v, g : pair of float
        The disk's position, velocity and acceleration at clock ``t0``.
    r : float
        Its radius.
    a, b : pair of float
        The segment's end points as given (unshifted).
    motion : Oscillation
        The segment's motion, on the simulation's clock.
    t0 : float
        The clock now.
    limit : float
        The search's end, a finite time from ``t0``.

    Returns
    -------
    tuple
        ``(t, part, u)``: the time from ``t0``, the part ("side", "start", "end") and
        the segment's velocity there; ``(inf, None, None)`` if none within ``limit``.
    """
    if not limit < INF:
        raise ValueError("the search for an oscillating segment needs a finite limit")
    wall_speed = motion.amplitude * motion.omega  # |u| <= A omega
    wall_acc = wall_speed * motion.omega  # |u'| <= A omega^2
    gabs = math.hypot(*g)
    ab = (b[0] - a[0], b[1] - a[1])
    ll = _dot(ab, ab)
    scale = _sum_abs(p, a, b) + motion.amplitude + r

    def probe(tau):
        """(G, G', part) at ``tau``: the gap, its rate and the part nearest the centre."""
        t = t0 + tau
        s = _shift(motion, t)
        x = _at(p, v, g, tau)
        rel = (x[0] - a[0] - s[0], x[1] - a[1] - s[1])
        q = _dot(rel, ab) / ll
        if q <= 0.0:
            q, part = 0.0, "start"
        elif q >= 1.0:
            q, part = 1.0, "end"
        else:
            part = "side"
        d = (rel[0] - q * ab[0], rel[1] - q * ab[1])  # from the nearest point to x
        dist = math.hypot(*d)
        u = _wall_velocity(motion, t)
        w = (v[0] + tau * g[0] - u[0], v[1] + tau * g[1] - u[1])
        rate = _dot(d, w) / dist if dist > 0.0 else -INF
        return dist - r, rate, part

    def noise(tau):
        # The gap is a difference of coordinates of size ~ these terms, rounded.
        return 16.0 * EPS * (scale + tau * _sum_abs(v) + 0.5 * tau * tau * _sum_abs(g))

    def step(gap, rate, tau, span):
        # The bounds of the docstring over [tau, tau + span]; the step, at most span.
        speed = math.hypot(v[0] + tau * g[0], v[1] + tau * g[1]) + gabs * span + wall_speed
        m = speed * speed / r + gabs + wall_acc
        q = math.sqrt(rate * rate + 2.0 * m * gap)
        # The positive root of gap + rate h - m h^2 / 2, cancellation-free for both signs.
        second = (rate + q) / m if rate >= 0.0 else 2.0 * gap / (q - rate)
        return min(max(gap / speed, second), span)

    tau = 0.0
    clear = None  # the last time at which G > 0 (the steps since then are safe)
    for _ in range(MAX_ADVANCES):
        if tau > limit:
            return INF, None, None
        gap, rate, part = probe(tau)
        if gap <= 0.0 and rate < 0.0:
            if clear is not None:
                # The crossing is in (clear, tau]: bisect to the first float with G <= 0.
                lo, hi = clear, tau
                while True:
                    mid = lo + 0.5 * (hi - lo)
                    if not lo < mid < hi:
                        break
                    if probe(mid)[0] > 0.0:
                        lo = mid
                    else:
                        hi = mid
                tau = hi
                gap, rate, part = probe(tau)
            if rate < 0.0:
                if tau > limit:
                    return INF, None, None
                return tau, part, _wall_velocity(motion, t0 + tau)
        eps = noise(tau)
        if gap > 0.0:
            clear = tau
        else:
            clear = None  # (touching by rounding: no crossing from G > 0 before here)
        if gap <= eps and rate >= 0.0:
            gap = eps  # touching without closing: go on as from the rounding error
        h = step(gap, rate, tau, limit - tau)
        span = limit - tau
        if h < 0.5 * span:
            h = step(gap, rate, tau, 2.0 * h)  # the bounds over the shorter window
        after = tau + h
        tau = after if after > tau else math.nextafter(tau, INF)
    raise RuntimeError(
        f"no convergence in {MAX_ADVANCES} steps towards a contact of a disk at {tuple(p)} "
        f"with an oscillating segment {a}-{b} from t={t0}: a graze too close to call")
