"""One perfectly inelastic impact of a group of touching disks (edmd2d._impacts): closed
forms, the optimality conditions against an independent solver, and the engine's and
the reference's use of it."""

import numpy as np
import pytest

import edmd2d as ed
from edmd2d import Box, _impacts
from edmd2d.reference import ReferenceSimulation

BOX = Box(20.0, 20.0, periodic=False)
MODEL = dict(restitution=0.9, wall_restitution=0.9, gravity=(0.0, -1.0))


def both_engines(pos, vel, mass, box):
    """The engine and the reference on one system of unit disks under gravity, with
    the bed model and the engine's criteria of rest."""
    sim = ed.Simulation(pos, vel, 0.5, masses=mass, box=box, **MODEL)
    state = sim._state
    ref = ReferenceSimulation(pos, vel, 0.5, mass, box, resting=state.families["resting"],
                              tc=float(state.model.tc), **MODEL)
    return sim, ref


def impact(pos, vel, static=None, mass=None, seeds=(0,), box=BOX, ends=()):
    pos = np.asarray(pos, float)
    n = len(pos)
    static = np.zeros(n, bool) if static is None else np.asarray(static)
    mass = np.ones(n) if mass is None else np.asarray(mass, float)
    flying = ~static & np.isfinite(mass)
    found = _impacts.group(list(seeds), pos, np.full(n, 0.5), flying, static, box,
                           [tuple(map(np.asarray, e)) for e in ends], np.ones(4, bool))
    assert found is not None
    members, a, b, side, segment, normal, distance = found
    after, impulse, lost = _impacts.resolve(members, np.asarray(vel, float), 1.0 / mass,
                                            a, b, normal)
    return members, a, b, side, segment, normal, after, impulse, lost


def test_a_disk_pushed_into_one_lying_on_a_wall_stops_with_it():
    # Disk 1 moves left at 1 into disk 0, which touches the wall x = 0: the pair can
    # only stop (the wall takes the push through disk 0), and all the energy goes.
    members, a, b, side, _, _, after, impulse, lost = impact(
        [[0.5, 5.0], [1.5, 5.0]], [[0.0, 0.0], [-1.0, 0.0]], seeds=(1,))
    assert members.tolist() == [0, 1]
    np.testing.assert_allclose(after, 0.0, atol=1e-15)
    assert lost == pytest.approx(0.5, rel=1e-14)
    # Each contact carries the momentum 1: the pair's and the wall's.
    np.testing.assert_allclose(impulse, 1.0, rtol=1e-14)
    assert sorted(side.tolist()) == [-1, 0]


def test_two_free_disks_end_with_the_centre_of_mass_velocity():
    # Head-on, touching, no static body: the perfectly plastic impact of a heavy disk
    # (mass 3, speed 1) on a light one (mass 1, at rest): both move at 3/4.
    _, _, _, _, _, _, after, impulse, lost = impact(
        [[5.0, 5.0], [6.0, 5.0]], [[1.0, 0.0], [0.0, 0.0]], mass=[3.0, 1.0])
    np.testing.assert_allclose(after, [[0.75, 0.0], [0.75, 0.0]], atol=1e-15)
    assert impulse.tolist() == pytest.approx([0.75])
    assert lost == pytest.approx(0.5 * 3.0 - 0.5 * 4.0 * 0.75 ** 2)


def test_a_disk_falling_into_a_groove_of_two_static_disks_stops():
    # The static disks below it at +-30 degrees from the vertical: each takes 1/sqrt(3).
    s = np.sqrt(3.0) / 2.0
    pos = [[5.0, 5.0 + s], [4.5, 5.0], [5.5, 5.0]]
    _, a, _, _, _, _, after, impulse, _ = impact(pos, [[0.0, -1.0], [0, 0], [0, 0]],
                                                 static=[False, True, True])
    np.testing.assert_allclose(after, 0.0, atol=1e-15)
    np.testing.assert_allclose(impulse, 1.0 / np.sqrt(3.0), rtol=1e-13)


def test_a_disk_sliding_along_a_static_one_keeps_its_tangential_velocity():
    # Pushed into a static disk at 45 degrees: only the normal half goes.
    pos = [[5.0, 5.0], [5.0 + np.sqrt(0.5), 5.0 + np.sqrt(0.5)]]
    _, _, _, _, _, _, after, _, lost = impact(pos, [[0.0, 0.0], [-1.0, 0.0]],
                                              static=[True, False], seeds=(1,))
    np.testing.assert_allclose(after[0], [-0.5, 0.5], atol=1e-15)
    assert lost == pytest.approx(0.25)


def test_only_touching_disks_join_the_group():
    # Disk 2 lies 1e-6 (relative) beyond contact: it is left out.
    pos = [[0.5, 5.0], [1.5, 5.0], [2.5 + 1e-6, 5.0]]
    members, *_ = impact(pos, [[0, 0], [-1.0, 0], [-1.0, 0]], seeds=(1,))
    assert members.tolist() == [0, 1]


@pytest.mark.parametrize("seed", range(6))
def test_the_impact_is_the_projection_an_independent_solver_finds(seed):
    # A random cluster of touching disks (a jammed patch of a triangular crystal, a
    # few of them static) with random velocities: the velocities after the impact
    # are the mass-weighted projection on those that close no contact, as a general
    # solver of the primal problem (SLSQP) finds it, and the impulses satisfy the
    # optimality conditions.
    from scipy import optimize

    rng = np.random.default_rng(seed)
    pos = np.array([[4.0 + c + 0.5 * (r % 2), 4.0 + r * np.sqrt(3.0) / 2.0]
                    for r in range(3) for c in range(4)])
    n = len(pos)
    static = np.zeros(n, bool)
    static[rng.choice(n, 3, replace=False)] = True
    mass = rng.uniform(0.5, 2.0, n)
    vel = rng.normal(size=(n, 2))
    vel[static] = 0.0
    seeds = [int(np.flatnonzero(~static)[0])]
    members, a, b, _, _, normal, after, impulse, lost = impact(pos, vel, static, mass,
                                                                seeds)
    k = len(members)
    col = {int(d): c for c, d in enumerate(members)}
    A = np.zeros((len(a), 2 * k))
    for c in range(len(a)):
        A[c, 2 * col[int(a[c])]:2 * col[int(a[c])] + 2] = normal[c]
        if b[c] >= 0:
            A[c, 2 * col[int(b[c])]:2 * col[int(b[c])] + 2] = -normal[c]
    m2 = np.repeat(mass[members], 2)
    v0 = vel[members].reshape(-1)
    primal = optimize.minimize(
        lambda u: 0.5 * np.sum(m2 * (u - v0) ** 2), v0, jac=lambda u: m2 * (u - v0),
        constraints=[{"type": "ineq", "fun": lambda u: A @ u, "jac": lambda u: A}],
        method="SLSQP", options={"ftol": 1e-14, "maxiter": 500})
    assert primal.success
    u = after.reshape(-1)
    np.testing.assert_allclose(u, primal.x, atol=1e-6)
    gap_rates = A @ u
    assert gap_rates.min() >= -1e-12  # no contact closes
    assert (impulse >= 0.0).all()
    assert abs(impulse @ gap_rates) <= 1e-12  # an impulse only where a contact stays shut
    assert lost == pytest.approx(0.5 * np.sum(m2 * (v0 ** 2 - u ** 2)), rel=1e-12)
    assert lost >= 0.0


def test_an_impact_changes_an_engine_run_as_it_changes_the_reference():
    # A disk pushed into a peg (on its upper right, at 30 degrees), under gravity, in
    # both engines: the same impact by hand, then the same events at the same times.
    c, s = np.cos(np.pi / 6.0), np.sin(np.pi / 6.0)
    pos = [[5.0, 5.0], [5.0 + c, 5.0 + s], [7.2, 5.3]]
    vel = [[0.0, 0.0], [-0.3, -0.1], [-0.2, -0.1]]
    sim, ref = both_engines(pos, vel, [np.inf, 1.0, 2.0], Box(12.0, 12.0, periodic=False))
    state = sim._state
    events = []
    sim.stream_events(events.append)
    assert state.impact([int(np.argsort(state.order)[1])])  # (the engine's row of disk 1)
    assert ref._impact([1])
    np.testing.assert_allclose(sim.velocities, ref.velocities, atol=1e-15)
    # The peg took the normal part of its push, 0.1 sin 30 + 0.3 cos 30, and gravity
    # presses the disk into it with the share sin 30: it leaves at the soft speed times
    # that (without it, it would meet the peg again at once, for ever).
    leave = state.families["resting"].soft * s
    assert sim.velocities[1] @ [c, s] == pytest.approx(leave, rel=1e-12)
    assert sim.dissipated_energy() == pytest.approx(
        0.5 * ((0.1 * s + 0.3 * c) ** 2 - leave ** 2), rel=1e-12)
    assert sim.dissipated_energy() == pytest.approx(ref.dissipated, rel=1e-14)
    sim.advance(until=3.0)
    ref.advance(until=3.0)
    got = np.concatenate(events)
    assert [(str(k), int(d), int(p)) for k, d, p in
            zip(got["kind"], got["disk"], got["partner"])] == [
        (k, d, p) for _, k, d, p in ref.events]
    np.testing.assert_allclose(got["time"], [t for t, *_ in ref.events], atol=1e-11)
    np.testing.assert_allclose(sim.positions, ref.positions, atol=1e-10)
    np.testing.assert_allclose(sim.total_energy() + sim.dissipated_energy(),
                               ref.total_energy() + ref.dissipated, rtol=1e-13)


def clamped_row(velocities=(0.1, 0.0, -0.2, 0.0)):
    """Four disks lying on the floor end to end between two pegs (immovable disks
    standing still), every contact closed, two of them sent into the others faster
    than a disk comes to rest."""
    n = len(velocities)
    pos = np.c_[np.arange(n + 2) + 1.0, np.full(n + 2, 0.5)]
    vel = np.zeros((n + 2, 2))
    vel[1:-1, 0] = velocities
    mass = np.r_[np.inf, np.ones(n), np.inf]
    box = Box(n + 3.0, 4.0, periodic=False)
    return pos, vel, mass, box


def test_a_row_clamped_between_pegs_stops_with_one_impact_and_comes_to_rest():
    # The pulses run along the row and back at one instant, each collision elastic
    # (the TC model); without the impact the run stops with an inelastic collapse.
    # With it the row stops at once, its kinetic energy dissipated, and comes to rest:
    # the reference does the same.
    pos, vel, mass, box = clamped_row()
    sim, ref = both_engines(pos, vel, mass, box)
    k0 = sim.kinetic_energy()
    sim.advance(until=10.0)
    assert sim.time == 10.0
    assert sim.resting[1:-1].all()
    assert sim.counts.collisions > 10_000  # (one streak of collisions at one instant)
    assert sim.dissipated_energy() == pytest.approx(k0, rel=1e-12)
    np.testing.assert_array_equal(sim.positions, pos)  # (at t = 0 already)
    ref.advance(until=10.0)
    assert all(ref.at_rest[1:-1])
    assert ref.dissipated == pytest.approx(k0, rel=1e-12)
    assert ref.collisions > 10_000
    # (Their events differ: every contact comes at t = 0, in an order each engine
    # breaks its own way.)
    with pytest.raises(RuntimeError, match="inelastic collapse"):
        ed.Simulation(pos, vel, 0.5, masses=mass, box=box, resting=False,
                      **MODEL).advance(until=10.0)


# ---------------------------------------------------------------- a wedged disk
S3 = np.sqrt(3.0) / 2.0


def pegs(v, placed):
    """A disk at (5, 5) touching two pegs at the angles ``placed`` (degrees, from the
    disk), with velocity ``v``, in both engines (gravity, disks at rest)."""
    a = np.radians(placed)
    pos = [[5.0 + np.cos(a[0]), 5.0 + np.sin(a[0])],
           [5.0 + np.cos(a[1]), 5.0 + np.sin(a[1])], [5.0, 5.0]]
    return both_engines(pos, [[0.0, 0.0], [0.0, 0.0], list(v)], [np.inf, np.inf, 1.0],
                        Box(10.0, 10.0, periodic=False))


def wedge_engine(sim, normal):
    """Apply the engine's wedge rule to the disk (user index 2) at t = 0, as if it had
    just met a static body with ``normal``; return its velocity and the energy lost."""
    from edmd2d._engine import resting

    state = sim._state
    i = int(np.argsort(state.order)[2])
    before = sim.dissipated_energy()
    heated = state.model_families().heated
    resting.wedge(i, 0.0, normal[0], normal[1], state.S, state.E, state.invm, state.gi,
                  state.gf, state.head, state.nxt, state.wa, state.wb, state.wstart,
                  state.wwall, state.wsx, state.wsy, state.acc, heated,
                  state.gravity_bundle(), state.rest_bundle())
    return sim.velocities[2], sim.dissipated_energy() - before


LEFT = np.array([1.0, 0.0])  # (the normal of a peg on the disk's left)
LOWER_LEFT = np.array([0.5, S3])  # (of one below it on the left, at 240 degrees)


@pytest.mark.parametrize("v, met, expected", [
    # Into both: nothing is left.
    ((-1.0, -1.0), LEFT, (0.0, 0.0)),
    # Into the left one, and a little into the other: it keeps going up.
    ((-1.0, 0.5), LEFT, (0.0, 0.5)),
    # Straight down, into the lower one only: it slides along it, away from the other.
    ((0.0, -1.0), LOWER_LEFT, (S3 / 2.0, -0.25)),
])
def test_a_wedged_disk_not_held_keeps_the_velocity_that_drives_it_into_no_static_body(
        v, met, expected):
    # Two pegs on its left, at 180 and 240 degrees: they cannot hold it up.
    sim, ref = pegs(v, (180.0, 240.0))
    got, lost = wedge_engine(sim, met)
    np.testing.assert_allclose(got, expected, atol=1e-14)
    assert lost == pytest.approx(0.5 * (np.dot(v, v) - np.dot(expected, expected)),
                                 abs=1e-14)
    ref._wedge(2, tuple(met))
    np.testing.assert_allclose(ref.v[2], expected, atol=1e-14)
    for n in (LEFT, LOWER_LEFT):  # (it drives into neither)
        assert np.dot(got, n) >= -1e-14


def test_a_wedged_disk_held_in_a_groove_stops():
    # Two pegs below it at +-30 degrees from the vertical hold it: it stops there,
    # whatever the velocity along them, to come to rest.
    sim, ref = pegs((1.0, -1.0), (240.0, 300.0))
    got, lost = wedge_engine(sim, LOWER_LEFT)
    assert got.tolist() == [0.0, 0.0]
    assert lost == pytest.approx(1.0)
    ref._wedge(2, tuple(LOWER_LEFT))
    assert ref.v[2] == [0.0, 0.0]


def groove_row(velocities):
    """A row of flying disks in the grooves of a layer of pegs, between two pegs at its
    ends, every contact closed; the disks of the row sent along it at ``velocities``
    (the contacts slanted, unlike a row on a floor: an impact leaves them closing by
    rounding, which elastic collisions pass back and forth)."""
    k = len(velocities)
    bottom = [[1.0 + q, 0.5] for q in range(k + 3)]
    row = [[1.5 + q, 0.5 + S3] for q in range(k + 2)]
    pos = np.array(bottom + row)
    vel = np.zeros((len(pos), 2))
    vel[len(bottom) + 1:len(bottom) + 1 + k, 0] = velocities
    mass = np.full(len(pos), np.inf)
    mass[len(bottom) + 1:len(bottom) + 1 + k] = 1.0
    return pos, vel, mass, Box(k + 5.0, 4.0, periodic=False)


@pytest.mark.parametrize("velocities, reference", [
    ((0.1, 0.0, -0.2, 0.0), False),
    ((0.3, 0.0, 0.0, 0.0, 0.0, -0.1), True),
    ((0.1, -0.1), True),
    ((0.2, -0.05, 0.1), False),
    ((0.05, 0.0, 0.0, -0.3, 0.1), False),
])
def test_a_row_in_grooves_settles_after_its_impacts(velocities, reference):
    # Each stopped with an inelastic collapse at t = 0 or soon after, or ran on at one
    # instant, until a group that stalls again at an instant stops and a member left
    # on a static body with no normal speed leaves it even where no contact took an
    # impulse.
    pos, vel, mass, box = groove_row(velocities)
    sim, ref = both_engines(pos, vel, mass, box)
    e0 = sim.total_energy()
    sim.advance(until=5.0)
    assert sim.resting[np.isfinite(mass)].all()
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(e0, abs=1e-13)
    if reference:
        ref.advance(until=5.0)
        assert all(ref.at_rest[k] for k in np.flatnonzero(np.isfinite(mass)))
        assert ref.total_energy() + ref.dissipated == pytest.approx(e0, abs=1e-13)


def test_a_member_in_a_groove_leaves_it_straight_up_at_the_parting_speed():
    # A disk falling straight into the groove of two pegs below it: the impact stops
    # it, and it leaves both pegs, which gravity presses it into with the share cos 30
    # each, at soft cos 30 along each normal: straight up at soft, the nearest
    # velocity that does (lifting off one peg after the other would throw it
    # sideways, at (0.25, 1.30) soft).  Held there and slow, it then comes to rest
    # with that velocity, all its energy dissipated.
    sim, ref = pegs((0.0, -1.0), (240.0, 300.0))
    state = sim._state
    soft = state.families["resting"].soft
    row = int(np.argsort(state.order)[2])
    assert state.impact([row])
    assert ref._impact([2])
    assert sim.resting[2] and ref.at_rest[2]
    np.testing.assert_allclose(state.rest_frozen[row], [0.0, soft], atol=1e-15)
    np.testing.assert_allclose(ref.frozen[2], [0.0, soft], atol=1e-15)
    assert sim.dissipated_energy() == pytest.approx(0.5, rel=1e-12)
    assert ref.dissipated == pytest.approx(0.5, rel=1e-12)
