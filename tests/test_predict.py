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
