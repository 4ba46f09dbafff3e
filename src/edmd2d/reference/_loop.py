"""The reference event loop: :class:`ReferenceSimulation`, its state and its run.

The simulation keeps every disk's state in plain lists and repeats one step: find the
earliest event (a contact, by the search of ``_search``, or a thermostat redraw), move
every disk to it, resolve it (the rules of ``_rules``), and wrap the centres back
into a periodic box, or, under shear, a box with Lees-Edwards (sliding-brick)
boundaries: see :class:`ReferenceSimulation`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from ..geometry import Box, Oscillation, Translation, Wall
from . import _search
from ._resting import IMPACTS_AT_ONCE, INSTANT
from ._rules import CollisionRules
from ._times import INF, _at, _dot

# Trusted input (see ReferenceSimulation): a value per disk, or a pair of them.
Pairs = Sequence[Sequence[float]] | np.ndarray
PerDisk = float | Sequence[float] | np.ndarray


class ReferenceSimulation(CollisionRules):
    """Same constructor and core API as :class:`edmd2d.Simulation`, brute force.

    Methods ``advance(until=None, collisions=None)``, ``kinetic_energy()``,
    ``momentum()``, ``potential_energy()`` and ``total_energy()`` work as in
    :class:`edmd2d.Simulation`.  Input is trusted (no validation): it is a test oracle.

    Parameters
    ----------
    positions, velocities : array_like, shape (N, 2)
        Disk centres (inside the box) and velocities.
    radii, masses : float or array_like, shape (N,)
        Radii and masses (default 1.0); mass ``inf`` makes a disk immovable.
    box : Box
        The container.
    walls : iterable of Wall or of (start, end) pairs, optional
        Extra wall segments.
    time : float, default 0.0
        The clock at the given state.
    species : array_like of int, shape (N,), optional
        Species ids ``0 .. S-1`` (default: all 0); they only select ``restitution``.
    restitution : float or array_like, shape (S, S), default 1.0
        Normal coefficient of restitution ``e`` of disk-disk collisions, 0 < e <= 1:
        one value, or a symmetric table indexed by the two disks' species.
    wall_restitution : float, default 1.0
        Coefficient ``e_w`` of every collision of a disk with a box wall or a wall
        segment (side or end point).
    tc : float, default 0.0
        Duration (a time) of the TC model: a collision is elastic if a movable disk
        taking part collided less than ``tc`` before (``t - t_last < tc``).  Immovable
        disks act as walls and never make a collision elastic; ``tc = 0`` switches the
        rule off.
    gravity : (float, float), default (0.0, 0.0)
        A uniform acceleration of every movable disk.  Immovable disks feel none (they
        keep their velocity, zero unless they are pistons) and walls stay put.
        ``(0, 0)`` runs the straight-flight code, bit for bit as without it.
    wall_temperatures : dict, optional
        Heated walls ``{wall: kT}`` (``"left"``, ``"right"``, ``"bottom"``, ``"top"``
        or a segment index): a disk hitting one leaves with its normal velocity
        ``sqrt(kT/m) sqrt(-2 ln(1 - u))`` and its tangential velocity
        ``sqrt(kT/m) g`` (``g`` Gaussian), along the wall's unit normal ``n`` into the
        box and the tangent ``(-n_y, n_x)``.
    thermostat : (float, float), optional
        ``(kT, rate)``: an Andersen thermostat.  Its redraws come at the events of a
        Poisson process of ``rate * N`` (waiting times ``-ln(1 - u) / (rate N)``),
        each picking disk ``floor(u N)`` (an immovable one is left alone) and drawing
        both velocity components as ``sqrt(kT/m) g``: under shear those of its
        peculiar velocity, ``vx = sqrt(kT/m) g1 + gamma (y - height/2)``,
        ``vy = sqrt(kT/m) g2``.
    seed : int, optional
        Seed of the ``numpy.random.default_rng`` stream of uniforms ``u`` in
        ``[0, 1)`` behind every random draw, used in this order: the first waiting
        time (if there is a thermostat); then, at each redraw, the disk, the next
        waiting time and two Gaussians; at each heated-wall contact the normal speed
        and a Gaussian.  A Gaussian takes two: ``sqrt(-2 ln(1 - u1)) cos(2 pi u2)``.
        These are the engine's draws, in the engine's order, so that a seed gives
        the same run in both.
    growth : float, optional
        Growing radii: ``r_i(t) = r_i (1 + growth (t - time))`` (straight flight,
        elastic).  A contact reverses the rate ``dd - vn`` at which the gap closes
        (``vn`` the normal relative velocity, ``dd`` the growth speed of the contact
        distance): ``vn' = 2 dd - vn``, elastic in the frame of the growing rims.
    resting : edmd2d.physics.Resting, optional
        Disks come to rest under gravity with these criteria (``speed``, ``gap``,
        ``wake``, ``press``, ``soft``, ``instant`` and ``every``), by the rules written out in
        ``_resting.py``; the TC model then holds no disk on a box wall.  Pass the
        engine's own (``Simulation`` holds it when disks rest) to compare the two.
    shear_rate : float, default 0.0
        Lees-Edwards boundaries sliding at the shear rate ``gamma`` (either sign; see
        the notes): the images above move along x at ``U = gamma * height``.  A
        nonzero rate needs a box periodic on both axes, no wall segments, no gravity,
        no growth and no ``resting`` (:class:`ValueError` otherwise).  ``0`` runs the
        code of an ordinary periodic box, bit for bit as without it.
    shear_offset : float, default 0.0
        The offset of the images above at ``time`` (under shear).
    tangential_restitution : float, default -1.0
        Rough disks (see ``_rough.py``): ``beta`` in ``[-1, 1]``, the factor by which a
        disk-disk collision multiplies the tangential velocity of the contact points
        with a minus sign (``-1``: smooth, the default; ``+1``: perfectly rough).  Not
        with growth, ``resting`` or shear.
    friction : float, default inf
        Coulomb's coefficient ``mu >= 0``: the tangential impulse is at most ``mu``
        times the normal one.
    inertia : float or sequence, default 0.5
        ``q`` in ``(0, 1]``, per disk or for all: the moment of inertia ``q m r^2``
        (``1/2`` for a uniform disk).
    angular_velocities : float or sequence, default 0.0
        The disks' angular velocities at the start (counter-clockwise).
    wall_tangential_restitution, wall_friction : float, optional
        The same at box walls and wall segments (default: the disks' values).  A heated
        wall sets the velocity only, and leaves the spin.  The thermostat draws the spin
        too, at its temperature (a third Gaussian, after the two of the velocity).
    wall_motions : dict, optional
        Segments that move: ``{index: motion}`` with an :class:`~edmd2d.Translation`
        (a ``begin`` left ``None`` becomes ``time``) or an
        :class:`~edmd2d.Oscillation`.  Segment ``k`` is at ``start + shift(t)``,
        ``end + shift(t)`` at time ``t`` (see :meth:`wall_positions`); the box does
        not move.  Not with ``resting``, ``growth``, ``shear_rate`` or a heated
        segment (:class:`ValueError`, as for an index that is not a segment's or a
        value that is neither motion).

    Attributes
    ----------
    time : float
        The clock.
    positions, velocities : ndarray, shape (N, 2)
        The state at ``time`` (copies).
    events : list of (float, str, int, int)
        Every disk, wall and box event as ``(time, kind, disk, partner)``; with
        ``resting`` also ``"rest"`` and ``"wake"`` (partner -1).
    collisions, wall_collisions : int
        Disk-disk and disk-wall (box walls and segments) collision counts.
    t_last : list of float
        Time of each disk's last collision (``-inf`` before the first; never set for
        immovable disks).
    dissipated : float
        Kinetic energy lost in collisions so far.  ``kinetic_energy() + dissipated`` is
        constant to rounding, unless immovable disks move (pistons do work); under
        gravity ``total_energy() + dissipated`` is.  For rough disks the rotational
        energy joins in (``rotational_energy()``, and ``total_energy()`` holds it).
    gravity : tuple of float
        The acceleration ``(gx, gy)``.
    at_rest : list of bool
        Whether each disk is at rest (with ``resting``).
    supports : list of list of int
        The supports noted for each disk at rest: a disk's index, ``-2 - side`` for a
        box wall, ``-6 - k`` for wall segment ``k``.
    rests, wakes : int
        How many times disks came to rest and woke.
    close_calls : list of (float, str)
        The decisions of the rules of rest taken within rounding of their thresholds,
        ``(time, what)``: where another arithmetic may decide otherwise.
    images : list of [int, int]
        For each disk, the whole periodic lengths taken off each coordinate when it was
        wrapped back into the box: ``p + images * (width, height)`` is its unwrapped
        position, which :meth:`potential_energy` uses; under shear the x coordinate
        also takes ``images[1] * D(t)`` (see :attr:`unwrapped_positions`).
    shear_rate : float
        The shear rate ``gamma`` (0: no shear).
    t0 : float
        The ``time`` of construction, where the images' offset is ``shear_offset``.
    shear_offset : float
        The offset at ``t0``.
    thermostat_energy : float
        The kinetic energy the thermostat's redraws gave the disks (under shear, the
        kinetic energy of their peculiar velocities).
    virial_xx, virial_yy, virial_xy : float
        The collisional virial: ``sum r_a J_b`` over every disk-disk collision so far,
        ``r`` the separation of the disks at contact (from the image of the partner to
        the disk) and ``J`` the impulse on the disk (bounces off disks at rest, with
        ``resting``, aside).
    heat_x, heat_y : float
        ``sum d de`` over every disk-disk collision so far, ``de`` the kinetic energy
        the disk gained (the collisional part of :meth:`heat_moment`).
    motions : dict
        The moving segments' motions, ``{index: motion}``, each with its ``begin``.
    wall_work : list of float
        The energy each wall segment gave the disks, ``sum J.u`` over its contacts
        (``J`` the impulse on the disk, ``u`` the segment's velocity): 0 for a fixed
        one.  ``total_energy() + dissipated - sum(wall_work)`` is constant to rounding.

    Notes
    -----
    A pair ``i, j`` with unit normal ``n`` from ``j`` to ``i`` and ``vn = (v_i - v_j).n``
    (< 0 when approaching) leaves with ``v_i' = v_i - (1+e) m_j/(m_i+m_j) vn n`` and
    ``v_j' = v_j + (1+e) m_i/(m_i+m_j) vn n`` (``v_i' = v_i - (1+e) vn n`` if ``j`` is
    immovable), which conserves momentum and turns ``vn`` into ``-e vn``.  At a box wall
    the normal velocity component becomes ``-e_w`` times itself; at a segment side or end
    point with unit normal ``n``, ``v' = v - (1+e_w)(v.n) n``.

    Under gravity, between events ``x(t) = x0 + v0 t + g t^2 / 2`` and
    ``v(t) = v0 + g t`` for movable disks, and collisions act on the velocities at the
    contact time as above.  Each contact is a function ``f`` of time that is positive
    while the two bodies are apart: the squared distance minus its value at contact
    for two disks or a disk and a wall end point (a quadratic for two movable disks,
    whose relative acceleration is zero, a quartic otherwise), ``d^2 - r^2`` for the
    signed distance ``d`` of the centre from a segment's line (a quartic), the gap to
    a box wall (a parabola).  The contact is the first ``t >= 0`` at which ``f`` turns
    from > 0 to <= 0, or ``t = 0`` if ``f(0) <= 0`` (touching or overlapping by
    rounding) and ``f'(0) < 0`` (approaching).  A double root of ``f`` (a tangential
    touch, ``f`` at its minimum within rounding of zero) exchanges no momentum and is
    no event, and bodies that touch and separate may meet again later: a disk that
    bounced off a floor, a segment or an immovable disk comes back.  A side contact
    also needs the foot of the centre on the segment; the crossings are tried in
    order, as a disk can pass beside a segment's end and later fall back onto its
    side.

    To find the crossings, the real parts of all roots of ``f'``
    (:func:`numpy.roots`, complex roots included so that none is lost to a small
    imaginary part) cut ``[0, T]``, ``T`` beyond every root of ``f``, into pieces on
    which ``f`` is monotonic.  A piece with ``f > 0`` at its start and ``f <= 0`` at its
    end holds a crossing, located to the last float by safeguarded Newton steps and
    bisection on the sign of ``f``, evaluated from the positions rather than the
    polynomial's coefficients.  A crossing is dropped if ``f' >= 0`` there (rounding
    noise of two bodies separating) or if ``f``'s following minimum is not below
    zero by more than its rounding error (a tangential touch).

    A resting contact, a disk at rest (``f'(0) = 0``) on a fixed point or a disk that
    it is pressed against (``f''(0) < 0``), is a contact now: it repeats at one
    instant, which a run with ``tc`` reports as a collapse.  (A disk at rest on a box
    wall is held there by an inelastic model, see ``resting``.)
    The periodic look-ahead window accounts for the acceleration: a disk moves at most
    ``|v| h + |g| h^2 / 2`` in a time ``h``.

    Under shear (Lees-Edwards boundaries, rate ``gamma``, box ``Lx`` by ``Ly``) the
    images of the box above slide along x at ``U = gamma Ly``, those below at ``-U``.
    With the *offset* ``delta(t) = (delta_0 + U (t - t0)) mod Lx`` in ``[0, Lx)``
    (``delta_0``: ``shear_offset``), the image of disk ``j`` in box ``(sx, sy)`` (any
    integers) is at ``(x_j + sy delta(t) + sx Lx, y_j + sy Ly)`` with velocity ``(vx_j +
    sy U, vy_j)``.  A pair meets through an image in straight flight (relative position
    ``p_i`` less the image's, relative velocity ``v_i`` less the image's) and collides
    as usual with the image: the impulse along their separation acts on ``v_i`` and,
    opposite, on ``v_j``.  A centre leaving through the top (``y >= Ly``) comes back as
    its image below: ``y -= Ly``, ``x -= delta(t)``, ``vx -= U`` (through the bottom:
    ``+=``), then x is wrapped into ``[0, Lx)``.  The *peculiar* velocity, the velocity
    relative to the flow ``(gamma (y - Ly/2), 0)``, is ``u = (vx - gamma (y - Ly/2),
    vy)``: continuous across the top and the bottom, and in flight ``du_x/dt = -gamma
    vy``.  Its kinetic energy :meth:`peculiar_kinetic_energy` obeys, for elastic
    collisions without thermostat, ``K(t) - K(t') = -gamma (I_xy + virial_xy)`` over the
    run between ``t'`` and ``t``, where ``I_xy`` is the integral of ``sum m u_x u_y`` of
    :meth:`kinetic_stress_integral`: in flight ``d(m u_x^2/2)/dt = -gamma m u_x u_y``,
    and a collision, elastic in the frame of the image, changes ``K`` by ``-gamma r_y
    J_x``.  (Inelastic collisions take ``dissipated`` off too, redraws add
    ``thermostat_energy``.)  The total peculiar momentum ``sum m u`` changes in flight
    at ``-gamma (P_y, 0)`` only, ``P_y`` the (conserved) y momentum.

    A moving segment (``wall_motions``) is translated, never turned: at time ``t`` its
    end points are shifted by the motion's ``shift(t)``, and it moves at ``u =
    velocity_at(t)``.  A disk meets it when its centre comes within ``r`` of it (side or
    end point) while approaching it in its frame.  For a :class:`~edmd2d.Translation`
    the velocity is constant on each of three phases (rest, motion, rest): in the
    segment's frame the disk flies with velocity ``v - u`` against a fixed segment, and
    the oracles of fixed segments apply, phase by phase.  An
    :class:`~edmd2d.Oscillation` moves it along ``A sin(omega t + phase)``, which no
    polynomial describes: conservative advancement on the gap, with bisection at the
    end, finds the contact to the last float (see
    ``_times.oscillating_segment_contact_time``), searching no further than the
    earliest other event.  The collision reflects the velocity relative to the
    segment's at that instant: with ``n`` the unit normal at the contact,
    ``vn = (v - u).n < 0`` becomes ``-e_w vn`` (the TC model as at a fixed wall, which
    is ``u = 0``), ``v' = v - (1 + e_w) vn n``; ``(1 - e_w^2) m vn^2 / 2`` counts as
    dissipated, and the segment does the work ``J.u`` on the disk, ``J = m (v' - v)``
    the impulse: kinetic energy changes by ``J.u`` less the loss, which
    ``wall_work`` tallies.  An oscillating segment sends the disk off at its
    parting speed at least, ``sqrt(2 (A omega^2 + |g|) 2^-40 (r + A))`` (the rule of
    the engine, ``_engine.moving.parting``), doing that work too.

    Examples
    --------
    A head-on collision with ``e = 0.5``: the relative speed 2 drops to 1, and a quarter
    of the reduced-mass energy ``mu vn^2 / 2 = 1`` is kept.

    >>> import edmd2d as ed
    >>> ref = ReferenceSimulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]],
    ...                           radii=1.0, box=ed.Box(10.0, 10.0, periodic=False),
    ...                           restitution=0.5)
    >>> ref.advance(collisions=1).velocities.tolist()
    [[-0.5, 0.0], [0.5, 0.0]]
    >>> ref.dissipated, ref.kinetic_energy()
    (0.75, 0.25)

    Dropped from 2 above the floor with ``g = 4``: it lands at ``t = 1``, hops back up
    every 2 and is at rest at its starting height at ``t = 6``, all its energy
    potential again (``m g h = 4 * 3``).

    >>> ref = ReferenceSimulation([[5.0, 3.0]], [[0.0, 0.0]], radii=1.0,
    ...                           box=ed.Box(10.0, 10.0, periodic=False),
    ...                           gravity=(0.0, -4.0))
    >>> ref.advance(until=6.0).events
    [(1.0, 'box', 0, 2), (3.0, 'box', 0, 2), (5.0, 'box', 0, 2)]
    >>> ref.kinetic_energy(), ref.potential_energy(), ref.total_energy()
    (0.0, 12.0, 12.0)

    A piston moving left at 1 meets a disk flying right at 1: the gap of 4 closes at
    2, and the disk leaves at ``v - 2 (v - u) = -3``, the piston's work ``J.u = 4``
    making up the kinetic energy gained.

    >>> piston = ReferenceSimulation([[5.0, 5.0]], [[1.0, 0.0]], radii=1.0,
    ...                              box=ed.Box(20.0, 10.0, periodic=False),
    ...                              walls=[((10.0, 2.0), (10.0, 8.0))],
    ...                              wall_motions={0: ed.Translation((-1.0, 0.0), 5.0)})
    >>> piston.advance(until=2.5).events
    [(2.0, 'wall', 0, 0)]
    >>> piston.velocities.tolist(), piston.wall_work, piston.wall_positions().tolist()
    ([[-3.0, 0.0]], [4.0], [[[7.5, 2.0], [7.5, 8.0]]])
    """

    def __init__(self, positions: Pairs, velocities: Pairs, radii: PerDisk,
                 masses: PerDisk = 1.0, box: Box | None = None,
                 walls: Iterable[Wall | tuple] = (), *, time: float = 0.0,
                 species: Sequence[int] | np.ndarray | None = None,
                 restitution: float | Sequence[Sequence[float]] | np.ndarray = 1.0,
                 wall_restitution: float = 1.0, tc: float = 0.0,
                 gravity: tuple[float, float] = (0.0, 0.0),
                 wall_temperatures: dict | None = None,
                 thermostat: tuple[float, float] | None = None, seed: int | None = None,
                 growth: float | None = None, resting: Any = None,
                 shear_rate: float = 0.0, shear_offset: float = 0.0,
                 tangential_restitution: float = -1.0, friction: float = math.inf,
                 inertia: PerDisk = 0.5, angular_velocities: PerDisk = 0.0,
                 wall_tangential_restitution: float | None = None,
                 wall_friction: float | None = None,
                 wall_motions: dict | None = None) -> None:
        n = len(positions)
        # (Required: its default only lets it follow masses as a keyword.)
        assert box is not None, "ReferenceSimulation needs a box"
        self.box = box
        self.walls = [w if isinstance(w, Wall) else Wall(*w) for w in walls]
        self.p = [[float(x), float(y)] for x, y in positions]
        self.v = [[float(x), float(y)] for x, y in velocities]
        self.r = _per_disk(radii, n)
        self.m = _per_disk(masses, n)
        self.time = float(time)
        # Growth: each radius grows at its own constant speed dr[k] = growth r0[k] from
        # the radii r0 at time t_grow; self.r always holds the radii now.
        self.growth = None if not growth else float(growth)
        self.r0 = list(self.r)
        self.t_grow = self.time
        self.dr = [0.0 if self.growth is None else self.growth * r for r in self.r0]
        self.events: list[tuple[float, str, int, int]] = []
        self.collisions = 0
        self.wall_collisions = 0
        self.species = [0] * n if species is None else [int(s) for s in species]
        table = np.asarray(restitution, dtype=float)
        self.restitution: float | list[list[float]] = (
            float(table) if table.ndim == 0 else table.tolist())
        self.wall_restitution = float(wall_restitution)
        self.tc = float(tc)
        self.t_last = [-INF] * n
        self.dissipated = 0.0
        gx, gy = gravity
        self.gravity = (float(gx), float(gy))
        # Whole periodic lengths taken off each coordinate by _wrap: the unwrapped
        # position, which the potential energy needs, is p + images * length (under
        # shear, plus images[1] D(t) along x: see unwrapped_positions).
        self.images = [[0, 0] for _ in range(n)]
        # Lees-Edwards boundaries: the shear rate, and the time t0 of offset 0.
        self.shear_rate = float(shear_rate)
        self.t0 = self.time
        self.shear_offset = float(shear_offset)  # the offset at t0
        if wall_motions:
            # (Before the checks of shear, which refuse wall segments at all.)
            refused = [name for name, on in (("resting", resting is not None),
                                             ("growth", self.growth is not None),
                                             ("shear_rate", self.shear_rate != 0.0)) if on]
            if refused:
                raise ValueError(f"wall_motions do not combine with {', '.join(refused)} "
                                 "yet")
        if self.shear_rate != 0.0:
            if self.box.periodic != (True, True):
                raise ValueError("shear_rate needs a box periodic on both axes")
            if self.walls:
                raise ValueError("shear_rate does not combine with wall segments")
            if self.gravity != (0.0, 0.0):
                raise ValueError("shear_rate does not combine with gravity")
            if self.growth is not None:
                raise ValueError("shear_rate does not combine with growth")
            if resting is not None:
                raise ValueError("shear_rate does not combine with resting")
        # The stress tallies: the collisional virial sum r_a J_b (see _rules) and the
        # time integrals of sum m u_a u_b over the flights, (xx, yy, xy) (see _drift).
        self.virial_xx = 0.0
        self.virial_yy = 0.0
        self.virial_xy = 0.0
        self.flight_stress = [0.0, 0.0, 0.0]
        # The Helfand moment of heat: the time integrals of sum v e over the flights,
        # (x, y), e = m v^2 / 2 in the lab frame (see _flight_stress), and the energy
        # each collision carried across the pair, sum d de (see _rules).
        self.flight_heat = [0.0, 0.0]
        self.heat_x = 0.0
        self.heat_y = 0.0
        # Rough disks (_rough.py): the coefficients, and each disk's angular velocity,
        # angle and moment of inertia q m r^2 (infinite for an immovable disk).
        self.beta = float(tangential_restitution)
        self.friction = float(friction)
        self.wall_beta = self.beta if wall_tangential_restitution is None else float(
            wall_tangential_restitution)
        self.wall_friction = self.friction if wall_friction is None else float(wall_friction)
        q = _per_disk(inertia, n)
        for name, value in (("tangential_restitution", self.beta),
                            ("wall_tangential_restitution", self.wall_beta)):
            if not -1.0 <= value <= 1.0:
                raise ValueError(f"{name} must lie in [-1, 1], got {value}")
        for name, value in (("friction", self.friction), ("wall_friction", self.wall_friction)):
            if not value >= 0.0:
                raise ValueError(f"{name} must be >= 0, got {value}")
        if not all(0.0 < x <= 1.0 for x in q):
            raise ValueError(f"inertia must lie in (0, 1], got {inertia}")
        self.inertia = [INF if math.isinf(m) else x * m * r * r
                        for x, m, r in zip(q, self.m, self.r)]
        self.w = [0.0 if math.isinf(m) else w
                  for w, m in zip(_per_disk(angular_velocities, n), self.m)]
        self.angle = [0.0] * n
        self.rough = self.beta != -1.0 or self.wall_beta != -1.0 or any(self.w)
        if self.rough and (self.growth or resting is not None or self.shear_rate != 0.0):
            raise ValueError("rough disks do not combine with growth, resting or shear")
        # The box walls (0..3: x=0, x=width, y=0, y=height) each disk rests on.  An
        # inelastic model with tc > 0 holds a disk on a wall that gravity presses it
        # into once its next bounce would come within tc (and a disk that starts at
        # rest touching such a wall); a collision with a disk or a segment that gives it
        # a velocity along the wall's normal frees it.
        self.resting: list[set[int]] = [set() for _ in range(n)]
        names = {"left": 0, "right": 1, "bottom": 2, "top": 3}
        self.wall_kt = {(names[k] if isinstance(k, str) else 4 + k): float(t)
                        for k, t in (wall_temperatures or {}).items()}
        self.thermostat = thermostat
        # Disks at rest (see _resting): the criteria, and each disk's state.
        self.rest = resting
        self.at_rest = [False] * n
        self.frozen = [(0.0, 0.0)] * n
        self.supports: list[list[int]] = [[] for _ in range(n)]
        self.t_static = [-INF] * n
        self.t_before = [-INF] * n
        self.streak = [0] * n  # collisions in a row at one instant (where counted)
        self.close_calls: list[tuple[float, str]] = []
        self.rests = 0
        self.wakes = 0
        self._woken: list[int] = []
        self._rested: list[int] = []
        self.next_check = INF  # the next search for groups that hold one another up
        if resting is not None:
            every = resting.every
            self.next_check = every * (math.floor(self.time / every) + 1.0)
            if self.next_check <= self.time:
                self.next_check += every
        self.rng = np.random.default_rng(seed)
        self.wall_heat = [0.0] * (4 + len(self.walls))  # energy each wall gave the disks
        # Segments that move: {index: Translation or Oscillation}, and the work each
        # segment did on the disks (sum of J.u over its contacts).
        self.motions = self._motions(wall_motions)
        self.wall_work = [0.0] * len(self.walls)
        self.thermostat_energy = 0.0
        self.redraws = 0
        self.next_redraw = INF
        if thermostat is not None:
            self.next_redraw = self.time + self._waiting_time()
        if self._holds():
            for k in range(n):
                for side in range(4):
                    axis = side // 2
                    if (self.box.periodic[axis] or math.isinf(self.m[k])
                            or self.v[k][axis] != 0.0 or self._pressing(side) >= 0.0):
                        continue
                    length = (self.box.width, self.box.height)[axis]
                    gap = (self.p[k][axis] - self.r[k] if side % 2 == 0
                           else length - self.r[k] - self.p[k][axis])
                    if gap <= 1e-9 * self.r[k]:
                        self.resting[k].add(side)

    def _motions(self, wall_motions):
        """``wall_motions`` checked: each motion started at the clock, or the refusal of
        what moving segments do not combine with yet (resting, growth and shear are
        refused before)."""
        if not wall_motions:
            return {}
        # (Every refusal of wall_motions is a ValueError, whatever is wrong with it.)
        if not isinstance(wall_motions, dict):
            raise ValueError(  # noqa: TRY004
                "wall_motions must be a dict {segment index: Translation or Oscillation}, "
                f"got {type(wall_motions).__name__}")
        motions = {}
        for k, motion in wall_motions.items():
            if (isinstance(k, bool) or not isinstance(k, (int, np.integer))
                    or not 0 <= k < len(self.walls)):
                raise ValueError(f"wall_motions: {k!r} is not the index of a wall segment "
                                 f"(0 to {len(self.walls) - 1})")
            if not isinstance(motion, (Translation, Oscillation)):
                raise ValueError(  # noqa: TRY004
                    f"wall_motions[{k}] must be a Translation or an Oscillation, got "
                    f"{type(motion).__name__}")
            if 4 + int(k) in self.wall_kt:
                raise ValueError(f"wall_motions: segment {k} is heated (wall_temperatures); "
                                 "a heated segment cannot move yet")
            motions[int(k)] = motion.starting(self.time)
        return motions

    def wall_positions(self) -> np.ndarray:
        """Every wall segment's end points now.

        Returns
        -------
        ndarray, shape (S, 2, 2)
            ``[start, end]`` of each of the ``S`` segments at ``time``: those of
            ``wall_motions`` shifted by their motion's ``shift(time)``, the others as
            given.
        """
        ends = np.array([[w.start, w.end] for w in self.walls], dtype=float).reshape(-1, 2, 2)
        for k, motion in self.motions.items():
            ends[k] += motion.shift(self.time)
        return ends

    def _wall_speed(self):
        """The fastest a moving segment ever goes (0 if none moves)."""
        return max((m.speed if isinstance(m, Translation) else m.amplitude * m.omega
                    for m in self.motions.values()), default=0.0)

    # -- the images of space: shifts to try on periodic axes.  Within one look-ahead
    # window (see _horizon) no disk moves more than a quarter of a periodic length, so
    # a pair's relative position changes by at most half a length and every image it
    # can touch is within two lengths of the stored (wrapped) positions.
    def _shifts(self):
        xs = (-2, -1, 0, 1, 2) if self.box.periodic[0] else (0,)
        ys = (-2, -1, 0, 1, 2) if self.box.periodic[1] else (0,)
        return [(sx * self.box.width, sy * self.box.height) for sx in xs for sy in ys]

    def _sheared_shifts(self):
        """The images to try under shear: ``(dx, dy, du)``, the shift of the image's
        position from its disk's now and of its x velocity.

        Image ``(sx, sy)`` of disk ``j`` is at ``p_j + (sx Lx + sy delta, sy Ly)`` and
        moves at ``v_j + (sy U, 0)``.  Along y nothing changes: ``sy`` from -2 to 2, as
        in :meth:`_shifts`.  Along x, within the window of :meth:`_horizon` (``t <= h``)
        a pair touching through image ``(sx, sy)`` at time ``t`` has
        ``sx Lx + sy delta = (x_i - x_j) + (change of x_i - x_j) - sy U t - X`` with
        ``|X| <= r_i + r_j``, where ``|x_i - x_j| < Lx`` (stored positions), the change
        is at most ``Lx / 2`` (each disk moves at most a quarter length), ``|sy U t| <=
        2 |U| h <= Lx / 2`` (the window is also at most ``Lx / (4 |U|)``) and
        ``r_i + r_j < Lx`` (no disk overlaps its own image).  So ``|sx + c| < 3`` with
        ``c = sy delta / Lx``: the six integers from ``floor(-c) - 2`` to
        ``floor(-c) + 3`` hold every ``sx`` that can touch within the window.
        """
        w, h = self.box.width, self.box.height
        delta = self.offset
        speed = self.shear_rate * h  # U
        shifts: list[tuple[float, float, float]] = []
        for sy in (-2, -1, 0, 1, 2):
            first = math.floor(-sy * delta / w) - 2
            shifts.extend((sx * w + sy * delta, sy * h, sy * speed)
                          for sx in range(first, first + 6))
        return shifts

    def _horizon(self):
        """How far ahead next_event may look on a periodic box (inf if walled)."""
        lengths = [length for axis, length in enumerate((self.box.width, self.box.height))
                   if self.box.periodic[axis]]
        vmax = max((math.hypot(*v) for v in self.v), default=0.0)
        if self.motions:
            # (A moving segment moves no more than a disk as fast as it would.)
            vmax = max(vmax, self._wall_speed())
        if self._accelerated():
            # A disk moves at most vmax h + |g| h^2 / 2 in a time h: the window is the
            # positive root of vmax h + |g| h^2 / 2 = L / 4, written without cancellation.
            gabs = math.hypot(*self.gravity)
            if not lengths:
                return INF
            half = 0.5 * min(lengths)
            return half / (vmax + math.sqrt(vmax * vmax + gabs * half))
        window = INF if not lengths or vmax == 0.0 else min(lengths) / (4.0 * vmax)
        if self.shear_rate != 0.0:
            # The images slide too: at most a quarter width at U in the window, which
            # bounds the x shifts to try (see _sheared_shifts).
            window = min(window, self.box.width / (4.0 * abs(self.shear_rate * self.box.height)))
        return window

    def _accelerated(self):
        """Whether gravity is on and some disk feels it (a movable disk)."""
        return self.gravity != (0.0, 0.0) and any(not math.isinf(m) for m in self.m)

    def _acceleration(self, k):
        """Disk ``k``'s acceleration: gravity if movable (less the components held by
        the walls it rests on), zero if immovable."""
        if math.isinf(self.m[k]) or self.at_rest[k]:
            return (0.0, 0.0)
        held = {side // 2 for side in self.resting[k]}
        return tuple(0.0 if axis in held else g for axis, g in enumerate(self.gravity))

    # -- random draws: all from one stream of uniforms, as documented above
    def _u(self):
        return float(self.rng.random())

    def _gauss(self):
        r = math.sqrt(-2.0 * math.log(1.0 - self._u()))
        return r * math.cos(2.0 * math.pi * self._u())

    def _waiting_time(self):
        assert self.thermostat is not None  # (called only with a thermostat)
        return -math.log(1.0 - self._u()) / (self.thermostat[1] * len(self.p))

    def _redraw(self):
        """A thermostat event at the current time."""
        n = len(self.p)
        k = min(int(self._u() * n), n - 1)
        self.next_redraw += self._waiting_time()
        if math.isinf(self.m[k]):
            return
        assert self.thermostat is not None  # (called only with a thermostat)
        if self.rest is not None:
            self._wake(k)  # (the wakes come before the redraw)
            self.events.extend((self.time, "wake", d, -1) for d in self._woken)
            self._woken.clear()
        s = math.sqrt(self.thermostat[0] / self.m[k])
        # (The peculiar velocity: the velocity itself without shear.)
        before = _dot(self._peculiar(k), self._peculiar(k))
        vx = s * self._gauss()
        vy = s * self._gauss()
        if self.shear_rate != 0.0:
            # A peculiar velocity drawn: the flow's velocity at the disk added.
            vx += self.shear_rate * (self.p[k][1] - 0.5 * self.box.height)
        self.v[k] = [vx, vy]
        after = _dot(self._peculiar(k), self._peculiar(k))
        self.thermostat_energy += 0.5 * self.m[k] * (after - before)
        if self.rough:  # (the spin too, at the same temperature)
            spin = self._spin_energy(k)
            self.w[k] = math.sqrt(self.thermostat[0] / self.inertia[k]) * self._gauss()
            self.thermostat_energy += self._spin_energy(k) - spin
        self.resting[k].clear()
        self.redraws += 1
        self.events.append((self.time, "thermostat", k, -1))

    def next_event(self) -> _search.Event:
        """The earliest event from now, found by examining every pair and every wall.

        Returns
        -------
        tuple
            ``(dt, kind, i, partner, detail)``: the time from now (``inf`` if
            nothing ever happens), the kind (``"disk"``, ``"wall"``, ``"box"``, or
            ``None``), the disk, its partner (a disk, a segment or a box side) and
            what resolving the contact needs (a pair's periodic image shift
            ``(dx, dy)``, under shear ``(dx, dy, du)`` with the image's extra x
            velocity; a segment's part that is hit and its end points in that image,
            for a moving segment those at the contact and its velocity there, ``(part,
            a, b, u)``; ``None`` for a box wall).  The moving segments are tried
            last, against the earliest other event (``_search.next_moving_wall_event``).
        """
        shifts = self._shifts() if self.shear_rate == 0.0 else self._sheared_shifts()
        if not self.motions:
            if self._accelerated():
                acc = [self._acceleration(k) for k in range(len(self.p))]
                return _search.next_event_accelerated(self.p, self.v, self.r, acc,
                                                      self.walls, self.box, shifts)
            return _search.next_event(self.p, self.v, self.r,
                                      None if self.growth is None else self.dr, self.walls,
                                      self.box, shifts)
        # The fixed bodies first, then the moving segments against the earliest of them.
        skip = frozenset(self.motions)
        if self._accelerated():
            acc = [self._acceleration(k) for k in range(len(self.p))]
            best = _search.next_event_accelerated(self.p, self.v, self.r, acc, self.walls,
                                                  self.box, shifts, skip)
        else:
            acc = [(0.0, 0.0)] * len(self.p)
            best = _search.next_event(self.p, self.v, self.r, None, self.walls, self.box,
                                      shifts, skip)
        return _search.next_moving_wall_event(best, self.p, self.v, self.r, acc, self.walls,
                                              self.motions, self.time, shifts,
                                              self._horizon())

    def _drift(self, dt):
        """Move every disk for ``dt``: along its straight line, or on its parabola under
        gravity (movable disks; their velocities change by ``g dt``), and add the
        flight's integrals of the kinetic stress."""
        self._flight_stress(dt)
        if self.rough:
            self._turn(dt)
        if not self._accelerated():
            self.p = [[p[0] + dt * v[0], p[1] + dt * v[1]] for p, v in zip(self.p, self.v)]
            self.time += dt
            if self.growth is not None:
                f = 1.0 + self.growth * (self.time - self.t_grow)
                self.r = [r * f for r in self.r0]
            return
        acc = [self._acceleration(k) for k in range(len(self.p))]
        self.p = [list(_at(p, v, a, dt)) for p, v, a in zip(self.p, self.v, acc)]
        self.v = [[v[0] + dt * a[0], v[1] + dt * a[1]] for v, a in zip(self.v, acc)]
        self.time += dt

    def _flight_stress(self, dt):
        """Add to ``flight_stress`` the integrals over the next ``dt`` of ``sum m u_x^2``,
        ``sum m u_y^2`` and ``sum m u_x u_y`` (movable disks, ``u`` the peculiar
        velocity), exactly.

        In flight ``u`` changes at a constant rate ``b``: ``(a_x - gamma v_y, a_y)``
        with ``a`` the disk's acceleration (there is no gravity under shear, no shear
        under gravity, so one of the two terms is zero and ``v_y`` is constant where
        ``gamma`` is not).  With ``u(t) = u0 + b t`` the integral of ``u_a u_b`` over
        ``[0, dt]`` is ``u0_a u0_b dt + (u0_a b_b + b_a u0_b) dt^2/2 + b_a b_b dt^3/3``.
        """
        if dt == 0.0:
            return
        h2, h3 = 0.5 * dt * dt, dt * dt * dt / 3.0
        accelerated = self._accelerated()
        for k in range(len(self.p)):
            m = self.m[k]
            if math.isinf(m):
                continue
            ux, uy = self._peculiar(k)
            ax, ay = self._acceleration(k) if accelerated else (0.0, 0.0)
            bx, by = ax - self.shear_rate * self.v[k][1], ay
            for slot, (ua, ub, ba, bb) in enumerate(((ux, ux, bx, bx), (uy, uy, by, by),
                                                      (ux, uy, bx, by))):
                self.flight_stress[slot] += m * (ua * ub * dt + (ua * bb + ba * ub) * h2
                                                 + ba * bb * h3)
            # sum v_a e in the lab frame, v(t) = v0 + a t: v_a |v|^2 is a cubic in t.
            v0 = self.v[k]
            w2, wa, a2 = _dot(v0, v0), v0[0] * ax + v0[1] * ay, ax * ax + ay * ay
            for slot, (va, aa) in enumerate(((v0[0], ax), (v0[1], ay))):
                self.flight_heat[slot] += 0.5 * m * (
                    va * w2 * dt + (aa * w2 + 2.0 * va * wa) * h2
                    + (2.0 * aa * wa + va * a2) * h3 + aa * a2 * dt ** 4 / 4.0)

    def _wrap(self):
        """Bring centres back into the box on periodic axes (after an event is resolved,
        so the image chosen by ``next_event`` still describes the contact)."""
        if self.shear_rate != 0.0:
            self._wrap_sheared()
            return
        for p, images in zip(self.p, self.images):
            for axis, length in enumerate((self.box.width, self.box.height)):
                if self.box.periodic[axis]:
                    wrapped = p[axis] % length
                    if wrapped != p[axis]:
                        images[axis] += round((p[axis] - wrapped) / length)
                    p[axis] = wrapped

    def _wrap_sheared(self):
        """:meth:`_wrap` under shear: a centre that left through the top (bottom) comes
        back as its image below (above), then x is wrapped as usual.

        Leaving through the top (``k = 1`` box lengths taken off y; ``k = -1`` through
        the bottom): ``y -= k Ly``, ``x -= k delta(t)``, ``vx -= k U``, so that the
        disk's image above is where the disk was, with its velocity.  The unwrapped x,
        ``x + images_x Lx + images_y D(t)`` with ``D(t) = U (t - t0)`` not reduced,
        must not jump: ``images_y`` gains ``k`` and ``x`` loses ``k delta``, so
        ``images_x`` loses ``k`` times the whole widths ``(D - delta) / Lx`` in ``D``.
        """
        w, h = self.box.width, self.box.height
        delta = self.offset
        whole = round((self._displacement() - delta) / w)
        speed = self.shear_rate * h  # U
        for p, v, images in zip(self.p, self.v, self.images):
            wrapped = p[1] % h
            if wrapped != p[1]:
                k = round((p[1] - wrapped) / h)
                p[1] = wrapped
                p[0] -= k * delta
                v[0] -= k * speed
                images[1] += k
                images[0] -= k * whole
            wrapped = p[0] % w
            if wrapped != p[0]:
                images[0] += round((p[0] - wrapped) / w)
            p[0] = wrapped

    def advance(self, until: float | None = None,
                collisions: int | None = None) -> ReferenceSimulation:
        """Process events in time order up to a time or a number of collisions.

        Parameters
        ----------
        until : float, optional
            Process every event up to this time, then let all disks fly on to it.
        collisions : int, optional
            Stop right after this many further disk-disk collisions.  With both, the
            run stops at whichever comes first.

        Returns
        -------
        ReferenceSimulation
            ``self``; each processed event is appended to ``events`` as ``(time,
            kind, disk, partner)``.
        """
        target = INF if until is None else float(until)
        todo = INF if collisions is None else int(collisions)
        done = 0
        impacts, impact_time = 0, math.nan  # (impacts at one instant)
        while done < todo:
            dt, kind, i, partner, detail = self.next_event()
            horizon = self._horizon()
            wait = self.next_redraw - self.time
            check = self.next_check
            if (check <= target and check < self.time + dt and check < self.next_redraw
                    and check - self.time <= horizon):
                # The search for groups that hold one another up (after the events at
                # its time, and after a redraw at its time).
                self._drift(check - self.time)
                self.time = check
                self._wrap()
                self._rest_groups()
                self.next_check += self.rest.every
                continue
            if wait <= min(dt, horizon) and self.next_redraw <= target:
                # A thermostat redraw comes first (at a tie with a contact, too).
                t_redraw = self.next_redraw
                self._drift(wait)
                self.time = t_redraw
                self._wrap()
                self._redraw()
                continue
            if dt > horizon and self.time + horizon < target:
                # Nothing within the look-ahead window: move there and look again.
                self._drift(horizon)
                self._wrap()
                continue
            if self.time + dt > target or dt == INF:
                break
            assert kind is not None  # (an event: dt < inf)
            disks = [i, partner] if kind == "disk" else [i]
            if self._stalls(self.time + dt, disks):
                # Caught between static bodies: one impact of the group, now (they stop
                # if they stalled again at this instant).
                if not self.time - impact_time <= INSTANT * abs(self.time):
                    impacts = 0
                impact_time = self.time
                if impacts >= IMPACTS_AT_ONCE or not self._impact(disks, impacts > 0):
                    raise RuntimeError(f"inelastic collapse at t={self.time + dt}: disks "
                                       f"{disks} would collide again at the same time")
                impacts += 1
                continue
            self._drift(dt)
            if kind == "disk" and len(detail) == 3:
                # A sheared image slid by du dt against its disk since the search: its
                # shift at the contact, as the search's straight lines have it.
                detail = (detail[0] + detail[2] * dt, detail[1], detail[2])
            self._resolve(kind, i, partner, detail)
            self._wrap()
            # The wakes the event caused come before it, the rests after it.
            self.events.extend((self.time, "wake", d, -1) for d in self._woken)
            self.events.append((self.time, kind, i, partner))
            self.events.extend((self.time, "rest", d, -1) for d in self._rested)
            self._woken.clear()
            self._rested.clear()
            done += kind == "disk"
        if until is not None and done < todo:
            self._drift(target - self.time)
            self._wrap()
        return self

    @property
    def positions(self) -> np.ndarray:
        """The disk centres now, a new ``(N, 2)`` array."""
        return np.array(self.p)

    @property
    def velocities(self) -> np.ndarray:
        """The disk velocities now, a new ``(N, 2)`` array."""
        return np.array(self.v)

    def _displacement(self) -> float:
        """``D = shear_offset + shear_rate * height * (time - t0)``: the images' whole
        displacement, not reduced by widths."""
        return self.shear_offset + self.shear_rate * self.box.height * (self.time - self.t0)

    @property
    def offset(self) -> float:
        """The offset ``delta`` of the images above along x now, in ``[0, width)``.

        ``delta = D mod width`` with ``D = shear_offset + shear_rate * height * (time -
        t0)`` the images' whole displacement (``shear_offset`` at ``t0``); 0 without
        shear.
        """
        w = self.box.width
        delta = self._displacement() % w
        # (A tiny negative D rounds to w - D == w: the same images as 0.)
        return 0.0 if delta == w else delta

    @property
    def unwrapped_positions(self) -> np.ndarray:
        """The centres followed continuously through the periodic boundaries, a new
        ``(N, 2)`` array.

        ``(x + images_x width + images_y D, y + images_y height)`` with ``D =
        shear_offset + shear_rate * height * (time - t0)`` (0 without shear), not
        reduced by widths:
        the path in the infinite sheared system, where the copy of the box ``k``
        boxes up has slid by ``k D``.  A free disk's unwrapped x then moves at
        ``vx + images_y U``, its velocity in that system.
        """
        w, h = self.box.width, self.box.height
        slide = self._displacement() if self.shear_rate != 0.0 else 0.0
        return np.array([[p[0] + k[0] * w + k[1] * slide, p[1] + k[1] * h]
                         for p, k in zip(self.p, self.images)])

    def _peculiar(self, k):
        """Disk ``k``'s peculiar velocity: less the flow's ``(gamma (y - height/2), 0)``."""
        v = self.v[k]
        return (v[0] - self.shear_rate * (self.p[k][1] - 0.5 * self.box.height), v[1])

    def peculiar_kinetic_energy(self) -> float:
        """The kinetic energy of the movable disks' peculiar velocities.

        Returns
        -------
        float
            ``sum m |u|^2 / 2`` with ``u = (vx - shear_rate (y - height/2), vy)``: the
            kinetic energy relative to the shear flow (:meth:`kinetic_energy` without
            shear).
        """
        return sum(0.5 * self.m[k] * _dot(self._peculiar(k), self._peculiar(k))
                   for k in range(len(self.p)) if not math.isinf(self.m[k]))

    def kinetic_stress_integral(self) -> tuple[float, float, float]:
        """The time integrals of the kinetic stress since the start, up to now.

        Returns
        -------
        tuple of float
            ``(xx, yy, xy)``: the integrals of ``sum m u_x^2``, ``sum m u_y^2`` and
            ``sum m u_x u_y`` over the movable disks, ``u`` the peculiar velocity, each
            flight integrated exactly (``u_x`` changes at ``-shear_rate * vy`` in flight).
            With the virial (``virial_xx``, ...) gathered over the same time ``T`` they
            give the mean pressure tensor, ``(I + virial) / (T area)``.
        """
        xx, yy, xy = self.flight_stress
        return (xx, yy, xy)

    def heat_moment(self) -> tuple[float, float]:
        """The Helfand moment of heat since the start, up to now.

        Returns
        -------
        tuple of float
            ``(x, y)``: the time integrals of ``sum v e`` over the movable disks'
            flights (``e = m v^2 / 2``, lab frame, each flight integrated exactly)
            plus ``sum d de`` over the collisions (``d`` from the image of ``j`` to
            ``i`` at contact, ``de`` the kinetic energy ``i`` gained).
        """
        return (self.flight_heat[0] + self.heat_x, self.flight_heat[1] + self.heat_y)

    def kinetic_energy(self) -> float:
        """The kinetic energy of the movable disks.

        Returns
        -------
        float
            ``sum m v^2 / 2`` over the disks of finite mass.
        """
        return sum(0.5 * m * _dot(v, v) for m, v in zip(self.m, self.v) if not math.isinf(m))

    def momentum(self) -> np.ndarray:
        """The total momentum of the movable disks.

        Returns
        -------
        ndarray, shape (2,)
            ``sum m v`` over the disks of finite mass.
        """
        return sum((m * np.array(v) for m, v in zip(self.m, self.v) if not math.isinf(m)),
                   np.zeros(2))

    def potential_energy(self) -> float:
        """The potential energy in the uniform field ``gravity``.

        Returns
        -------
        float
            ``-sum m g.x`` over the movable disks, ``x`` the unwrapped centre (the
            stored one plus the whole periodic lengths taken off at each wrap): the
            height gained through a periodic boundary is kept.
        """
        gx, gy = self.gravity
        w, h = self.box.width, self.box.height
        return -sum(m * (gx * (p[0] + k[0] * w) + gy * (p[1] + k[1] * h))
                    for m, p, k in zip(self.m, self.p, self.images) if not math.isinf(m))

    def total_energy(self) -> float:
        """Kinetic plus potential energy (and, for rough disks, rotational).

        Returns
        -------
        float
            Constant in an elastic run (with immovable disks at rest), and
            ``total_energy() + dissipated`` constant otherwise.
        """
        total = self.kinetic_energy() + self.potential_energy()
        return total + self.rotational_energy() if self.rough else total

    @property
    def angular_velocities(self) -> np.ndarray:
        """Each disk's angular velocity (counter-clockwise), a copy."""
        return np.array(self.w)

    @property
    def angles(self) -> np.ndarray:
        """Each disk's angle, turned by ``w dt`` over each flight from 0 at the start."""
        return np.array(self.angle)


def _per_disk(value: PerDisk, n: int) -> list[float]:
    values = np.asarray(value, dtype=float)
    return [float(values)] * n if values.ndim == 0 else values.tolist()
