"""Property tests of the contact-time kernels against the seed's formulas (reference)."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from edmd2d._engine.predict import pair_time, segment_time
from edmd2d.reference import circle_contact_time, segment_contact_time

coord = st.floats(-10, 10, allow_nan=False)
# Zero or of physical size: below ~1e-150 the squares in the seed's formula underflow.
speed = st.one_of(st.just(0.0), st.floats(1e-6, 5.0), st.floats(-5.0, -1e-6))
radius = st.floats(0.05, 2.0)


@settings(max_examples=400, deadline=None)
@given(coord, coord, speed, speed, radius)
def test_pair_time_agrees_with_seed_formula(dx, dy, dvx, dvy, d):
    t = pair_time(dx, dy, dvx, dvy, d)
    t_ref = circle_contact_time((dx, dy), (dvx, dvy), d)
    if math.isinf(t_ref):
        assert math.isinf(t)
        return
    assert t == t_ref or abs(t - t_ref) <= 1e-9 * max(1.0, t_ref)
    if t > 0:
        # At the contact time the distance is exactly d (to rounding, scaled by how
        # far the bodies travelled).
        dist = math.hypot(dx + t * dvx, dy + t * dvy)
        travel = t * math.hypot(dvx, dvy) + math.hypot(dx, dy)
        assert abs(dist - d) <= 1e-12 * max(d, travel) / max(d, 1e-3) + 1e-12 * travel


@settings(max_examples=400, deadline=None)
@given(coord, coord, speed, speed, st.floats(0.05, 1.0), coord, coord, coord, coord)
def test_segment_time_agrees_with_seed_formula(x, y, vx, vy, r, ax, ay, bx, by):
    if math.hypot(bx - ax, by - ay) < 1e-3:
        return
    # Only start outside the segment's reach (a valid state).
    ux, uy = bx - ax, by - ay
    s = max(0.0, min(1.0, ((x - ax) * ux + (y - ay) * uy) / (ux * ux + uy * uy)))
    if math.hypot(x - ax - s * ux, y - ay - s * uy) <= r * (1 + 1e-9):
        return
    t, part = segment_time(x, y, vx, vy, r, ax, ay, bx, by)
    t_ref, part_ref = segment_contact_time((x, y), (vx, vy), r, (ax, ay), (bx, by))
    if math.isinf(t_ref):
        assert math.isinf(t)
        return
    assert abs(t - t_ref) <= 1e-9 * max(1.0, t_ref)
    # At the contact the distance from the centre to the segment is r.
    px, py = x + t * vx, y + t * vy
    s = max(0.0, min(1.0, ((px - ax) * ux + (py - ay) * uy) / (ux * ux + uy * uy)))
    dist = math.hypot(px - ax - s * ux, py - ay - s * uy)
    assert abs(dist - r) <= 1e-9 * (1 + t * math.hypot(vx, vy))



def _plain_bisection(which, lo, hi, neg_lo, px, py, vx, vy, ax, ay, d2):
    """Bisect ``[lo, hi]`` for the sign change of ``_value(which, ...)`` to the last bit,
    evaluating every midpoint: what ``predict._bisect`` reproduces with fewer
    evaluations."""
    from edmd2d._engine.predict import _value

    for _ in range(2200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if (_value.py_func(which, mid, px, py, vx, vy, ax, ay, d2)[0] < 0.0) == neg_lo:
            lo = mid
        else:
            hi = mid
    return lo, hi


@settings(max_examples=300, deadline=None)
@given(st.floats(-3, 3), st.floats(-3, 3), st.floats(-2, 2), st.floats(-2, 2),
       st.floats(0.05, 2.0), st.floats(-math.pi, math.pi), st.floats(0.3, 1.5),
       st.sampled_from([0.0, 1e-9, 1e-4]))
def test_point_time_is_the_plain_bisections_bit_for_bit(px, py, vx, vy, g, angle, d,
                                                         graze):
    """The compiled contact time of a parabola with a fixed point equals, to the last
    bit, the same search run in Python with every bisection evaluating every midpoint
    (starts near contact included: ``graze`` above the contact distance)."""
    from unittest import mock

    from edmd2d._engine import predict

    ax, ay = g * math.sin(angle), -g * math.cos(angle)
    norm = math.hypot(px, py)
    if norm > 0.0 and graze > 0.0:
        px, py = px / norm * (d + graze), py / norm * (d + graze)
    if px * px + py * py <= d * d:
        return
    t = predict.point_time(px, py, vx, vy, ax, ay, d, math.inf)
    with mock.patch.multiple(predict, _bisect=_plain_bisection,
                             _bisect_rate=predict._bisect_rate.py_func,
                             _fall=predict._fall.py_func):
        plain = predict.point_time.py_func(px, py, vx, vy, ax, ay, d, math.inf)
    assert t == plain or (math.isinf(t) and math.isinf(plain))
