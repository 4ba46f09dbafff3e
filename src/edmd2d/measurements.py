"""Thermodynamic and kinetic measurements over a time window: :func:`measure`, and
profiles along an axis: :func:`profiles`, and a bed at rest: :func:`bed`.

Everything here is a true two-dimensional quantity with ``k_B = 1``.  The pressure comes
from the collision virial, which the engine accumulates exactly at every disk-disk
collision (no sampling of configurations), and error bars come from block averages over
equal sub-windows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from . import progress as _progress
from ._facade import require_simulation
from ._jsonable import decode, encode
from ._measurement import Measurement, _frozen, _stderr
from ._operations import Blocks, Every, Operation, Trigger, run
from ._sums import dot, weighted_sum
from ._validate import as_count, as_float_array, as_positive_float
from .geometry import Box, Wall, container

if TYPE_CHECKING:  # (for the annotations only: simulation imports this module)
    from .simulation import Simulation

__all__ = ["Measurement", "measure", "Measure", "kinetic_temperature",
           "rotational_temperature", "degrees_of_freedom", "container_area", "Cooling",
           "cooling", "profiles", "Profile", "Profiles", "bed", "Bed", "discharge", "Discharge"]


def degrees_of_freedom(sim: Simulation) -> tuple[int, tuple[bool, bool]]:
    """Kinetic degrees of freedom of the movable disks and the conserved momentum axes.

    A Cartesian component of the total momentum is conserved when its axis is periodic
    and nothing external can push along it: no wall segments (a segment's end points
    push in every direction), no immovable disks (``mass = inf``), no thermostat and
    no gravity along it.  Each conserved component removes one degree of freedom:
    ``f = 2N - 2`` in a fully periodic box of free disks, ``2N - 1`` in a channel
    periodic along one axis, ``2N`` in a closed box.

    Parameters
    ----------
    sim : Simulation
        The simulation whose disks, box, walls, gravity and thermostat count.

    Returns
    -------
    f : int
        The degrees of freedom.
    conserved : (bool, bool)
        Whether the x and y components of the total momentum are conserved.

    Examples
    --------
    >>> import edmd2d as ed
    >>> degrees_of_freedom(ed.make_gas(10, 0.2, seed=0))
    (18, (True, True))
    >>> degrees_of_freedom(ed.make_gas(10, 0.2, periodic=(True, False), seed=0))
    (19, (True, False))
    """
    movable = np.isfinite(sim.masses)
    # (A thermostat's redraws change the momentum too; gravity pushes along its axes.)
    free = bool(movable.all()) and not sim.walls and sim.thermostat is None
    x, y = (bool(sim.box.periodic[a] and free and sim.gravity[a] == 0.0) for a in range(2))
    return 2 * int(movable.sum()) - int(x) - int(y), (x, y)


def kinetic_temperature(sim: Simulation) -> float:
    """The kinetic temperature ``kT`` of the movable disks now (2D, ``k_B = 1``).

    ``kT = (sum m v^2 - sum_c P_c^2 / M) / f``: each disk has two translational degrees
    of freedom with ``<m v_a^2> = kT`` (equipartition in 2D, so the mean kinetic energy
    per disk is ``kT``, not the ``3 kT / 2`` of 3D).  ``P_c`` runs over the conserved
    components of the total momentum, ``M`` is the total mass and ``f`` comes from
    :func:`degrees_of_freedom`: the centre-of-mass motion along a conserved axis carries
    no heat.  ``nan`` when ``f <= 0`` (a single disk in a periodic box).

    Parameters
    ----------
    sim : Simulation
        The simulation, read at its current :attr:`~edmd2d.Simulation.time`.

    Returns
    -------
    float
        ``kT``, or ``nan`` without degrees of freedom.

    Examples
    --------
    >>> import edmd2d as ed
    >>> sim = ed.make_gas(100, 0.3, temperature=2.5, seed=1)
    >>> round(kinetic_temperature(sim), 12)
    2.5
    """
    dof, conserved = degrees_of_freedom(sim)
    if dof <= 0:
        return math.nan
    mass = sim.masses
    vel = sim.peculiar_velocities
    movable = np.isfinite(mass)
    m, v = mass[movable], vel[movable]
    twice_ke = float(dot(m, np.einsum("ij,ij->i", v, v)))
    momentum = weighted_sum(m, v)
    total_mass = float(m.sum())
    cm = sum(float(momentum[a]) ** 2 for a in range(2) if conserved[a]) / total_mass
    return (twice_ke - cm) / dof


def rotational_temperature(sim: Simulation) -> float:
    """The rotational temperature of rough disks now: ``kT_rot = sum I w^2 / N`` over
    the movable disks (2D, ``k_B = 1``).

    A disk turning in the plane has one rotational degree of freedom, so equipartition
    gives ``<I w^2> = kT``: in equilibrium ``kT_rot`` equals the (translational)
    :func:`kinetic_temperature`; a rough granular gas cools to a fixed ratio of the two
    (:func:`edmd2d.theory.rough_hcs_ratio`).  No angular momentum is taken out: walls,
    and the images of a periodic box, do not conserve it.

    Parameters
    ----------
    sim : Simulation
        With rough disks (:class:`edmd2d.physics.Rough`), read at its current time.

    Returns
    -------
    float
        ``kT_rot``, or ``nan`` without movable disks.

    Raises
    ------
    ValueError
        For smooth disks, which do not turn.

    Examples
    --------
    >>> import edmd2d as ed
    >>> sim = ed.make_gas(4, 0.2, seed=0, tangential_restitution=1.0,
    ...                   angular_velocities=2.0, inertia=0.5)
    >>> rotational_temperature(sim)  # I w^2 = 0.5 * 1 * 0.5**2 * 4
    0.5
    """
    if "rough" not in sim.families:
        raise ValueError("the disks are smooth and do not turn: a rotational temperature "
                         "needs rough disks (tangential_restitution)")
    movable = np.isfinite(sim.masses)
    n = int(movable.sum())
    return 2.0 * sim.rotational_energy() / n if n else math.nan


def measure(sim: Simulation, duration: float, *, blocks: int = 10,
            area: float | None = None, progress: _progress.ProgressArg = False) -> Measurement:
    """Run ``sim`` for ``duration`` and measure pressure, temperature and collision rates.

    The window is cut into ``blocks`` equal sub-windows; the values returned are the
    averages over the whole window, and the errors the standard errors of the block
    values.  Equilibrate first (``sim.advance(until=...)``): every collision of the
    window counts.

    This is one run with a :class:`edmd2d.operations.Measure` over
    ``Blocks(duration, blocks)``; to measure while the same run writes files or
    records frames, or to read the measurement block by block, pass that operation to
    :meth:`~edmd2d.Simulation.run` (the numbers are the same to the last bit).

    Formulas (2D, ``k_B = 1``; ``N`` movable disks, area ``A``, window length ``t``,
    ``C`` disk-disk collisions, ``J`` impulse magnitude, ``|r_ij|`` contact distance):

    - temperature ``kT = (sum m v^2 - P_c^2 / M) / f`` with ``f = 2N - (number of
      conserved momentum components)`` (:func:`kinetic_temperature`);
    - virial pressure ``P A = N kT + (1 / (2 t)) sum J |r_ij|`` (the 2D virial theorem;
      in 3D the factor would be ``1/(3t)`` and ``P V = N kT + ...``);
    - compressibility factor ``Z = P A / (N kT)``;
    - collision rate per disk ``2 C / (N t)``; mean free time its inverse; mean free
      path ``<|v|>`` times the mean free time;
    - wall pressure: impulse on the box walls per unit time per unit wall length;
    - on each wall segment: the mean force vector (impulse per unit time) and, on each
      side, the normal force per unit length (``segment_pressures``).

    The area ``A`` is that of the container holding the movable disks
    (:func:`container_area`): the box, or, when the disks sit inside a closed polygon
    of the simulation's wall segments, the polygon's area (less the closed polygons
    inside it, obstacles the disks flow around).  It is the container's area, bounded
    by the walls themselves, not the smaller area that the disk centres can reach (a
    distance ``a`` from every wall): that is the convention of the box (whose area is
    used the same way), it needs no disk radius (mixtures), and with it the virial
    pressure of a large container tends to the bulk pressure.  Pass ``area`` for walls
    that :func:`container_area` does not recognise as closed (a chamber closed by
    segments together with the box walls, segments whose ends do not meet).

    For a walled rectangular box of equal disks of radius ``a`` the virial theorem with
    the wall forces included reads exactly (in the time average)
    ``(W - 2a) F_x + (H - 2a) F_y = 2 P A``, where ``F_x`` is the mean force on one
    x-wall (``box_wall_pressures[0] * H``) and ``F_y`` that on one y-wall: the walls
    carry the virial ``2 P A`` at the distance ``a`` at which the disk centres touch.
    So ``wall_pressure`` differs from ``pressure`` by a surface term of relative size
    ``~ 2a / L``; in a channel (periodic along the walls) ``wall_pressure`` is the bulk
    pressure normal to the walls.

    The same holds in a container of wall segments.  A contact on a side pushes the
    disk along the side's unit normal ``n`` (towards the disk), whose centre is then at
    distance ``a`` from the side's line ``s . n = const`` (``s`` any point of it), so the
    virial theorem reads ``2 P A = sum_sides F_side (-(s . n) - a)`` (plus the end-point
    contacts), with ``F_side = segment_pressures * length`` the mean normal force on
    the side; the origin drops out because the mean forces balance.  For a convex
    container at uniform wall pressure ``p`` this is ``P A = p (A - a L / 2)``, ``L``
    its perimeter (exactly, whatever the pressure's profile, for a regular polygon):
    ``segment_pressure`` exceeds ``pressure`` by the surface term ``a L / (2 A)``.
    On a flat stretch of wall away from the corners the force per length is the bulk
    pressure of the gas at its density away from the walls (the contact theorem);
    within ``a cot(theta / 2)`` of a corner of angle ``theta`` no centre touches a
    side, so the mean over whole sides is lower by up to ``2 a cot(theta / 2)`` per
    side length (measured in an octagon of sides 19 diameters at packing 0.25: the
    middle thirds of the sides (-0.2 +- 0.4)% off the equation of state at the bulk
    density, whole sides 1.7% below it, the corners' share being 2.2%; the virial
    ``Z`` 0.6% above the equation of state at the mean density ``N / A``).

    With immovable disks, or wall segments that do not close a container around the
    disks, ``pressure`` keeps its formula but is no longer a thermodynamic pressure
    (the obstacles' virial is not included; closed obstacles are taken out of ``A``).
    The area of immovable disks is not taken out of ``A``.  A collision with an
    immovable disk adds to ``collisions`` like any other.

    Under gravity the pressure varies with height and ``pressure`` (the collision
    virial without the field's ``sum m g.r`` term) is not a pressure of the gas; the
    wall pressures still are the mean forces on the walls (on the floor, the weight of
    the gas over the floor's length, once it has settled).  Likewise a thermostat or
    heated walls drive the gas out of equilibrium: the wall pressures and ``Z`` are
    measured as defined, at the temperature of the disks.

    Parameters
    ----------
    sim : Simulation
        Advanced in place, from ``sim.time`` to ``sim.time + duration``.
    duration : float
        Length of the window, > 0.
    blocks : int, default 10
        Number of sub-windows for the error bars, >= 1.
    area : float, optional
        The area ``A`` of the pressure and of ``Z``, > 0.  Default: the container's
        area, :func:`container_area` (see above).
    progress : bool or tqdm bar, default False
        ``True`` shows a progress bar of the simulated time over the whole window
        (:mod:`edmd2d.progress`).

    Returns
    -------
    Measurement

    Raises
    ------
    TypeError, ValueError
        For a ``sim`` that is not a Simulation, a non-positive or non-finite
        ``duration`` or ``area``, or ``blocks < 1``.

    Examples
    --------
    A dilute gas: ``Z`` close to the hard-disk equation of state, and the temperature
    stays exactly what :func:`~edmd2d.make_gas` set:

    >>> import edmd2d as ed
    >>> from edmd2d import theory
    >>> sim = ed.make_gas(200, 0.2, seed=3)
    >>> _ = sim.advance(until=10.0)
    >>> m = sim.measure(duration=50.0)
    >>> round(m.temperature, 9)
    1.0
    >>> abs(m.compressibility_factor - theory.henderson_z(0.2)) < 0.03
    True
    >>> m.collisions == round(m.collision_rate * m.n * m.duration / 2)
    True
    """
    require_simulation(sim, "measure()")
    duration = as_positive_float("duration", duration)
    blocks = as_count("blocks", blocks, minimum=1)
    if area is not None:
        area = as_positive_float("area", area)
    window = Measure(Blocks(duration, blocks), area=area)
    _run_window(sim, duration, window, progress, "measure")
    return window.result()


def _run_window(sim, duration: float, operation: Operation, progress, desc: str) -> None:
    """Run ``sim`` for ``duration`` with ``operation``, and a progress bar of the
    simulated time if ``progress`` asks for one (closed after, if made here)."""
    bar, owned = _progress.bar(progress, total=duration, unit="time", desc=desc)
    try:
        run(sim, until=sim.time + duration, operations=[operation],
            progress=bar if bar is not None else False)
    finally:
        if owned:
            bar.close()


class Measure(Operation):
    """Measure pressure, temperature, collision rates and wall forces over a run, in
    blocks: the quantities of :func:`edmd2d.measurements.measure`.

    The window opens when the run starts (or, with a
    :class:`~edmd2d.operations.Blocks` trigger whose window starts later, when it
    does), and each firing of ``trigger`` ends a block.
    Nothing is sampled in between: the engine accumulates the collision virial and the
    wall impulses exactly at every event, and the operation keeps these sums, the
    temperatures and the counts at the block boundaries only.  :meth:`result` gives
    the :class:`~edmd2d.measurements.Measurement` over the blocks ended so far, at any
    time, so a table can show it growing.  A Measure used in a second run goes on with
    the same window (the accumulated sums are cumulative).

    With :class:`~edmd2d.operations.Blocks` the blocks have the length
    ``duration / blocks`` exactly and the result is bit for bit that of
    :func:`~edmd2d.measurements.measure`; with other triggers each block's length is
    the time between its boundaries.

    Parameters
    ----------
    trigger : Trigger
        The ends of the blocks, e.g. ``Blocks(duration=50.0, blocks=10)`` or
        ``Every(dt=5.0)``.
    area : float, optional
        The area of the pressure, > 0; default the container's
        (:func:`edmd2d.measurements.container_area`, taken when the window opens).

    Examples
    --------
    >>> import edmd2d as ed
    >>> from edmd2d import operations as op
    >>> sim = ed.make_gas(200, 0.3, seed=2)
    >>> window = op.Measure(op.Blocks(duration=4.0, blocks=4))
    >>> _ = sim.run(until=4.0, operations=[window])
    >>> m = window.result()
    >>> m.blocks, round(m.temperature, 9)
    (4, 1.0)
    >>> m.pressure == ed.make_gas(200, 0.3, seed=2).measure(duration=4.0, blocks=4).pressure
    True
    """

    def __init__(self, trigger: Trigger, *, area: float | None = None) -> None:
        super().__init__(trigger)
        self._area = None if area is None else as_positive_float("area", area)
        self._edges: list[dict] = []
        self._meta: dict | None = None  # (n, n_all, dof, area, area_source) at the start
        self._movable: np.ndarray | None = None
        self._box: Box | None = None
        self._walls: tuple[Wall, ...] | None = None

    @property
    def blocks(self) -> int:
        """The number of blocks ended so far."""
        return max(len(self._edges) - 1, 0)

    @property
    def times(self) -> np.ndarray:
        """The block boundaries so far (the first is the window's start), shape (B + 1,)."""
        return np.array([e["time"] for e in self._edges])

    def begin(self, sim: Simulation) -> None:
        """Open the window at the run's start (or wait for the start of the window of
        a :class:`~edmd2d.operations.Blocks` trigger), or check that a window already
        open goes on with the same simulation.

        Parameters
        ----------
        sim : Simulation

        Raises
        ------
        ValueError
            If the window of a :class:`~edmd2d.operations.Blocks` trigger started
            before the run and nothing was measured then, or ``sim`` is not the
            simulation measured so far.
        """
        self._box, self._walls = sim.box, sim.walls
        self._movable = np.isfinite(sim.masses)
        if self._edges:
            assert self._meta is not None  # (set with the first edge)
            if sim.time < self._edges[-1]["time"] or len(sim) != self._meta["n_all"]:
                raise ValueError(
                    f"this Measure's window has a boundary at t={self._edges[-1]['time']} "
                    f"for {self._meta['n_all']} disks; the simulation (t={sim.time}, "
                    f"{len(sim)} disks) is not the one it measured")
            return
        if isinstance(self.trigger, Blocks):
            t0 = self.trigger.window_start
            assert t0 is not None  # (the run started the trigger before this)
            if t0 < sim.time:
                raise ValueError(
                    f"the window of this Measure starts at t={t0}, before the run's start "
                    f"at t={sim.time}: nothing was measured there (give Blocks a start not "
                    "before the run's, or continue a Measure made with Measure.from_state)")
            if t0 > sim.time:
                return  # (the trigger fires at the window's start)
        self._open(sim)

    def _open(self, sim) -> None:
        if self._area is None:
            area, source = _container(sim)
        else:
            area, source = self._area, "given"
        assert self._movable is not None  # (set by begin, which a run calls first)
        n = int(self._movable.sum())
        box = sim.box
        self._meta = {"n": n, "n_all": len(sim), "area": area, "area_source": source,
                      "dof": degrees_of_freedom(sim)[0],
                      "box": [box.width, box.height, *box.periodic],
                      "walls": [[*w.start, *w.end] for w in sim.walls]}
        self._edges.append(_edge(sim, self._movable))

    def __call__(self, sim) -> None:
        """Take a block boundary (the first opens the window)."""
        if not self._edges:
            self._open(sim)
        else:
            assert self._movable is not None  # (set by begin, which a run calls first)
            self._edges.append(_edge(sim, self._movable))

    def result(self) -> Measurement:
        """The measurement over the blocks ended so far.

        Returns
        -------
        Measurement

        Raises
        ------
        ValueError
            If no block has ended yet.
        """
        k = self.blocks
        if k < 1:
            raise ValueError("no block of this measurement has ended yet")
        if isinstance(self.trigger, Blocks):
            tau = self.trigger.duration / self.trigger.blocks
            duration = self.trigger.elapsed(k)
        else:
            times = self.times
            tau = np.diff(times)
            duration = float(times[-1] - times[0])
        meta = self._meta
        assert meta is not None  # (set with the first edge)
        return _from_edges(
            self._edges, tau, duration, n=meta["n"], n_all=meta["n_all"], dof=meta["dof"],
            area=meta["area"], area_source=meta["area_source"], box=self._box,
            walls=self._walls)

    def state(self) -> dict:
        """What the measurement holds, in plain JSON-able values (floats kept exactly),
        to go on in another process with :meth:`from_state` (e.g. in a checkpoint's
        ``metadata``).

        Returns
        -------
        dict
        """
        window = None
        if isinstance(self.trigger, Blocks):
            t = self.trigger
            window = {"duration": t.duration, "blocks": t.blocks, "start": t.window_start,
                      "count": t.count}
        return {"edges": [encode(e) for e in self._edges], "meta": self._meta,
                "area": self._area, "window": window}

    @classmethod
    def from_state(cls, state: dict, trigger: Trigger | None = None, *,
                   count: int | None = None) -> Measure:
        """A Measure that goes on from :meth:`state`.

        Parameters
        ----------
        state : dict
            From :meth:`state`.
        trigger : Trigger, optional
            Default: the :class:`~edmd2d.operations.Blocks` of the saved window, at its
            start.
        count : int, optional
            With the default trigger, the number of blocks to end in all (default the
            saved trigger's).

        Returns
        -------
        Measure
        """
        if trigger is None:
            window = state.get("window")
            if window is None:
                raise ValueError("this state has no window of Blocks: pass its trigger")
            trigger = Blocks(
                window["duration"], window["blocks"], start=window["start"],
                count=window["count"] if count is None else count)
        out = cls(trigger, area=state["area"])
        out._edges = [decode(e) for e in state["edges"]]
        out._meta = meta = state["meta"]
        if meta is not None:  # (the box and walls: a result needs no simulation)
            width, height, px, py = meta["box"]
            out._box = Box(width, height, periodic=(px, py))
            out._walls = tuple(Wall((x0, y0), (x1, y1)) for x0, y0, x1, y1 in meta["walls"])
        return out


def _edge(sim, movable: np.ndarray) -> dict:
    """What a measurement window keeps at each block boundary: the time, the
    engine's accumulated sums (:meth:`Simulation._accumulators`, cumulative since the
    simulation was created, so that a window needs nothing from between boundaries),
    the temperatures, the mean speed and the counts."""
    counts = sim.counts
    edge = {
        "time": sim.time,
        "acc": sim._accumulators(),
        "temperature": kinetic_temperature(sim),
        "axis_temperatures": _axis_temperatures(sim, movable),
        "cross_temperature": _cross_temperature(sim, movable),
        "speed": _mean_speed(sim, movable),
        "collisions": counts.collisions,
        "wall_collisions": counts.wall_collisions,
    }
    if "rough" in sim.families:
        edge["rotational_temperature"] = rotational_temperature(sim)
    shear = sim.families.get("shear")
    if shear is not None:
        # (Sheared: the kinetic stress integrated exactly over every flight.)
        edge["flights"] = sim._state.kinetic_stress_integral()
        edge["shear_rate"] = shear.rate
    return edge


def _from_edges(edges: list, tau, duration: float, *, n: int, n_all: int, dof: int,
                area: float, area_source: str, box, walls) -> Measurement:
    """The :class:`Measurement` of the window whose block boundaries are ``edges``
    (from :func:`_edge`; at least two).

    ``tau`` holds the length of each block, shape (B,) (or one length for all), and
    ``duration`` that of the window: given rather than taken from the boundary times,
    so that equal blocks of a window cut as ``t0 + duration * b / B`` use the exact
    ``duration / B`` and ``duration``, as the formulas of :func:`measure` state them.
    """
    blocks = len(edges) - 1
    tau = np.broadcast_to(np.asarray(tau, dtype=float), (blocks,))
    tau3 = tau[:, None, None]  # (for the per-segment arrays, shape (B, S, 2))
    acc0 = edges[0]["acc"]
    edges_acc = [e["acc"] for e in edges]
    temps = np.array([e["temperature"] for e in edges])
    axis_temps = [e["axis_temperatures"] for e in edges]
    speeds = [e["speed"] for e in edges]
    coll = [e["collisions"] for e in edges]
    # Wall lengths in the order of the engine's box accumulators: x=0, x=W, y=0, y=H.
    lengths = np.array([box.height, box.height, box.width, box.width])
    walled = np.array([not box.periodic[0]] * 2 + [not box.periodic[1]] * 2)

    virial = np.diff([a["virial"] for a in edges_acc])
    virial_axes = np.array([edges_acc[-1][k] - acc0[k] for k in ("virial_xx", "virial_yy")])
    kt_axes = np.mean(np.array(axis_temps), axis=0)
    # The pressure tensor by blocks: kinetic part from each block's two boundaries,
    # collisional part from its collisions.  (A window kept from before the
    # off-diagonal was summed has none: nan.)
    virial_tensor = np.diff([[[a["virial_xx"], a.get("virial_xy", math.nan)],
                              [a.get("virial_xy", math.nan), a["virial_yy"]]]
                             for a in edges_acc], axis=0)
    kt_tensor = np.array([[[x, xy], [xy, y]] for (x, y), xy in
                          zip(axis_temps, (e.get("cross_temperature", math.nan)
                                           for e in edges))])
    box_imp = np.diff(np.array([a["box_impulse"] for a in edges_acc]), axis=0)
    seg_imp = edges_acc[-1]["segment_impulse"] - acc0["segment_impulse"]
    seg_len = np.array([w.length for w in walls]).reshape(-1, 1)
    seg_vec = np.diff(np.array([a["segment_impulses"] for a in edges_acc]), axis=0)
    seg_side = np.diff(np.array([a["segment_side_impulses"] for a in edges_acc]), axis=0)
    seg_contacts = edges_acc[-1]["segment_contacts"] - acc0["segment_contacts"]
    # The sides the disks reach: those touched since the simulation was created (not
    # only in this window, which would leave out, in a short window, the sides that
    # happened not to be touched, and bias the mean upwards).
    touched = edges_acc[-1]["segment_side_impulses"] > 0.0  # (S, 2)
    touched_length = float((seg_len * touched).sum())
    kt_block = 0.5 * (temps[1:] + temps[:-1])
    n_coll = np.diff(coll)

    kt = float(np.mean(temps))
    with np.errstate(divide="ignore", invalid="ignore"):
        p_block = (n * kt_block + virial / (2.0 * tau)) / area
        z_block = p_block * area / (n * kt_block) if kt > 0 else np.full(blocks, math.nan)
        rate_block = 2.0 * n_coll / (n_all * tau)
        pressure = (n * kt + float(virial.sum()) / (2.0 * duration)) / area
        z = pressure * area / (n * kt) if kt > 0 else math.nan
        p_axes = (n * kt_axes + virial_axes / duration) / area
        p_tensor_block = (n * 0.5 * (kt_tensor[1:] + kt_tensor[:-1])
                          + virial_tensor / tau3) / area
        p_xy = (n * float(np.mean(kt_tensor[:, 0, 1]))
                + float(virial_tensor[:, 0, 1].sum()) / duration) / area
        rate = 2.0 * float(n_coll.sum()) / (n_all * duration)
        rate_err = _stderr(rate_block)
        mft = 1.0 / rate if rate > 0 else math.inf
        mft_err = rate_err / rate**2 if rate > 0 else math.nan
        per_wall = box_imp.sum(axis=0) / (duration * lengths)
        if walled.any():
            wall_p = float(box_imp[:, walled].sum() / (duration * lengths[walled].sum()))
            wall_p_block = box_imp[:, walled].sum(axis=1) / (tau * lengths[walled].sum())
            wall_err = _stderr(wall_p_block)
        else:
            wall_p, wall_err = math.nan, math.nan
        seg_forces = seg_vec.sum(axis=0) / duration
        seg_forces_err = _stderr(seg_vec / tau3)
        seg_pressures = seg_side.sum(axis=0) / (duration * seg_len)
        seg_pressures_err = _stderr(seg_side / (tau3 * seg_len))
        if touched_length > 0.0:
            seg_p = float(seg_side[:, touched].sum() / (duration * touched_length))
            seg_p_err = _stderr(seg_side[:, touched].sum(axis=1) / (tau * touched_length))
        else:
            seg_p, seg_p_err = math.nan, math.nan
        sheared: dict = {}
        if all("flights" in e for e in edges):
            # Sheared: the kinetic part is the time integral of sum m u_a u_b over the
            # window (peculiar velocities u), exact, instead of the boundaries' samples.
            flights = np.diff(np.array([e["flights"] for e in edges]), axis=0)  # (B, 3)
            kin = flights[:, [[0, 2], [2, 1]]]  # (B, 2, 2)
            p_tensor_block = (kin + virial_tensor) / (tau3 * area)
            p_tensor = (kin.sum(axis=0) + virial_tensor.sum(axis=0)) / (duration * area)
            p_axes = np.diag(p_tensor)
            p_xy = float(p_tensor[0, 1])
            p_block = 0.5 * (p_tensor_block[:, 0, 0] + p_tensor_block[:, 1, 1])
            pressure = 0.5 * float(p_axes.sum())
            z = pressure * area / (n * kt) if kt > 0 else math.nan
            z_block = p_block * area / (n * kt_block) if kt > 0 else np.full(blocks, math.nan)
            rate_shear = float(edges[-1]["shear_rate"])
            sheared = {"shear_rate": rate_shear, "viscosity": -p_xy / rate_shear,
                       "viscosity_error": _stderr(p_tensor_block[:, 0, 1]) / abs(rate_shear)}
    mean_speed = float(np.mean(speeds))
    rotational: dict = {}
    if all("rotational_temperature" in e for e in edges):
        # (Rough disks: as the temperature, the mean of the boundaries, by blocks.)
        rot = np.array([e["rotational_temperature"] for e in edges])
        rotational = {"rotational_temperature": float(np.mean(rot)),
                      "rotational_temperature_error": _stderr(0.5 * (rot[1:] + rot[:-1]))}
    return Measurement(
        duration=float(duration),
        collisions=int(n_coll.sum()),
        wall_collisions=edges[-1]["wall_collisions"] - edges[0]["wall_collisions"],
        blocks=blocks,
        n=n,
        area=area,
        degrees_of_freedom=dof,
        temperature=kt,
        pressure=float(pressure),
        pressure_error=_stderr(p_block),
        pressure_xx=float(p_axes[0]),
        pressure_yy=float(p_axes[1]),
        compressibility_factor=float(z),
        compressibility_factor_error=_stderr(z_block),
        collision_rate=rate,
        collision_rate_error=rate_err,
        mean_free_time=mft,
        mean_free_time_error=mft_err,
        mean_speed=mean_speed,
        mean_free_path=mean_speed * mft,
        wall_pressure=wall_p,
        wall_pressure_error=wall_err,
        box_wall_pressures=tuple(float(p) if w else math.nan for p, w in zip(per_wall, walled)),
        segment_force=float(seg_imp / duration),
        area_source=area_source,
        segment_contacts=_frozen(seg_contacts),
        segment_forces=_frozen(seg_forces),
        segment_forces_error=_frozen(seg_forces_err),
        segment_pressures=_frozen(seg_pressures),
        segment_pressures_error=_frozen(seg_pressures_err),
        segment_pressure=seg_p,
        segment_pressure_error=seg_p_err,
        temperature_error=_stderr(kt_block),
        pressure_xy=p_xy,
        pressure_tensor_error=_frozen(_stderr(p_tensor_block)),
        **sheared,
        **rotational,
    )


def _axis_temperatures(sim, movable: np.ndarray) -> np.ndarray:
    """``kT_x, kT_y``: the kinetic temperature of each velocity component alone."""
    _, conserved = degrees_of_freedom(sim)
    m = sim.masses[movable]
    v = sim.peculiar_velocities[movable]
    out = np.full(2, math.nan)
    for a in range(2):
        dof = len(m) - int(conserved[a])
        if dof > 0:
            p = float(dot(m, v[:, a]))
            drift = p * p / m.sum() if conserved[a] else 0.0
            out[a] = (float(dot(m, v[:, a] ** 2)) - drift) / dof
    return out


def _cross_temperature(sim, movable: np.ndarray) -> float:
    """``kT_xy``: the covariance of the two velocity components, ``(sum m v_x v_y -
    P_x P_y / M) / (N - c)`` (the drift taken out, and ``c = 1``, where the dynamics
    conserves both momentum components), the kinetic part of ``P_xy A / N``."""
    _, conserved = degrees_of_freedom(sim)
    m = sim.masses[movable]
    v = sim.peculiar_velocities[movable]
    both = bool(conserved[0] and conserved[1])
    dof = len(m) - int(both)
    if dof <= 0:
        return math.nan
    drift = float(dot(m, v[:, 0])) * float(dot(m, v[:, 1])) / m.sum() if both else 0.0
    return (float(dot(m, v[:, 0] * v[:, 1])) - drift) / dof


def _mean_speed(sim, movable: np.ndarray) -> float:
    v = sim.peculiar_velocities[movable]
    return float(np.mean(np.hypot(v[:, 0], v[:, 1]))) if len(v) else math.nan


# --------------------------------------------------------------------------- containers
def container_area(sim: Simulation) -> float:
    """The area of the container that holds the movable disks of ``sim``: the box's,
    or that of the regions bounded by closed polygons of its wall segments that hold
    a movable disk's centre (the rules are those of :func:`edmd2d.geometry.container`).
    The area of immovable disks is not taken out.

    Parameters
    ----------
    sim : Simulation

    Returns
    -------
    float

    Examples
    --------
    A gas inside a square container of side 10 in a 12 x 12 box:

    >>> import edmd2d as ed
    >>> walls = ed.Wall.polygon([(1, 1), (11, 1), (11, 11), (1, 11)])
    >>> sim = ed.Simulation([[4.0, 4.0], [7.0, 6.0]], [[1.0, 0.0], [0.0, 1.0]],
    ...                     radii=0.5, box=ed.Box(12, 12, periodic=False), walls=walls)
    >>> container_area(sim)
    100.0
    """
    return _container(sim)[0]


def _container(sim) -> tuple[float, str]:
    """``(area, source)`` of :func:`container_area` (see :func:`edmd2d.geometry.container`)."""
    # (The segments where they are now: some may move.)
    where = getattr(sim, "wall_positions", None)
    walls = sim.walls if where is None else [Wall(a, b) for a, b in where]
    closed = [w for w, is_open in zip(walls, sim.open_walls) if not is_open]
    return container(sim.box, closed, sim.positions[np.isfinite(sim.masses)])


@dataclass(frozen=True)
class Cooling:
    """Results of :func:`cooling`: a cooling (inelastic) gas sampled at given times.

    Attributes
    ----------
    time : ndarray, shape (K,)
        The sampling times (the first is the start).
    collisions_per_disk : ndarray, shape (K,)
        Disk-disk collisions per disk since the start, ``2 C / N_all`` (every
        collision involves two disks).
    kinetic_energy : ndarray, shape (K,)
        Total kinetic energy of the movable disks.
    temperature : ndarray, shape (K,)
        Granular temperature, the kinetic temperature ``kT`` of
        :func:`kinetic_temperature` (mean kinetic energy per degree of freedom, with
        the conserved centre-of-mass motion left out).
    dissipated_energy : ndarray, shape (K,)
        Kinetic energy lost in collisions since the start (for rough disks, the
        rotational energy they took too).
    rotational_energy : ndarray, shape (K,)
        Rough disks (:class:`edmd2d.physics.Rough`): the rotational kinetic energy
        ``sum I w^2 / 2``; zero for smooth disks.
    rotational_temperature : ndarray, shape (K,)
        Rough disks: :func:`rotational_temperature`; ``nan`` for smooth disks.
    """

    time: np.ndarray
    collisions_per_disk: np.ndarray
    kinetic_energy: np.ndarray
    temperature: np.ndarray
    dissipated_energy: np.ndarray
    rotational_energy: np.ndarray
    rotational_temperature: np.ndarray


def cooling(sim: Simulation, times: ArrayLike) -> Cooling:
    """Run ``sim`` through the increasing ``times`` and sample how it cools.

    Parameters
    ----------
    sim : Simulation
        Advanced in place to ``times[-1]``.
    times : array_like, shape (K,)
        Increasing sampling times, the first not before ``sim.time`` (the run goes
        there first).

    Returns
    -------
    Cooling
        Time, collisions per disk, kinetic energy, granular temperature,
        dissipated energy and, for rough disks, the rotational energy and temperature
        at each sampling time.  For a homogeneous gas of
        restitution ``e``, ``T = T0 exp(-(1 - e^2) C / 2)`` against the collisions per
        disk ``C`` and Haff's law ``T = T0 / (1 + t / t_H)^2`` against time (see
        ``docs/restitution.md``).

    Raises
    ------
    ValueError
        If ``times`` is empty, not increasing or starts before ``sim.time``.
    """
    t = np.asarray(times, dtype=float)
    if t.ndim != 1 or len(t) == 0 or not np.all(np.isfinite(t)):
        raise ValueError(f"times must be a non-empty 1-D array of finite times, got {times!r}")
    if np.any(np.diff(t) <= 0):
        raise ValueError("times must be strictly increasing")
    if t[0] < sim.time:
        raise ValueError(f"times start at {t[0]}, before the simulation's time {sim.time}")
    n_all = sim.n
    rough = "rough" in sim.families
    rows = []
    c0 = e0 = None
    for tk in t:
        sim.advance(until=float(tk))
        c, lost = sim.counts.collisions, sim.dissipated_energy()
        if c0 is None or e0 is None:  # (the first sample: both are set together)
            c0, e0 = c, lost
        rows.append((2.0 * (c - c0) / n_all, sim.kinetic_energy(), kinetic_temperature(sim),
                     lost - e0, sim.rotational_energy(),
                     rotational_temperature(sim) if rough else math.nan))
    cols = np.array(rows).T
    return Cooling(t.copy(), *cols)


# --------------------------------------------------------------------------- profiles
_AXES = {"x": 0, "y": 1}


@dataclass(frozen=True)
class Profiles:
    """Profiles along one axis of the box, averaged over the samples of a run, with
    the standard errors of their block averages (``*_error``; NaN with one block).

    Each slab is the strip of the box between two ``edges`` along ``axis``, across the
    whole box on the other axis.  A disk counts in the slab of its centre.  Immovable
    disks are left out; disks at rest count, at rest.

    Attributes
    ----------
    axis : str
        ``"x"`` or ``"y"``.
    edges : ndarray, shape (B + 1,)
    centres : ndarray, shape (B,)
    density, density_error : ndarray, shape (B,)
        Disks per unit area.
    packing_fraction, packing_fraction_error : ndarray, shape (B,)
        The disks' area per unit area (each disk's whole area in the slab of its
        centre: a profile resolved to a diameter, not finer).
    velocity, velocity_error : ndarray, shape (B, 2)
        The flow velocity, the mass-weighted mean velocity of the disks in the slab.
    temperature, temperature_error : ndarray, shape (B,)
        The granular temperature, the mean over the blocks of ``sum m |v - u|^2 /
        (2 (n - 1))`` over the ``n`` disk visits of a block (``u`` the block's flow
        velocity in the slab; 2D, ``k_B = 1``); NaN where a block saw fewer than two.
    counts : ndarray of int64, shape (B,)
        Disk visits over the samples used (those that fill the blocks).
    samples, blocks : int
    """

    axis: str
    edges: np.ndarray
    centres: np.ndarray
    density: np.ndarray
    density_error: np.ndarray
    packing_fraction: np.ndarray
    packing_fraction_error: np.ndarray
    velocity: np.ndarray
    velocity_error: np.ndarray
    temperature: np.ndarray
    temperature_error: np.ndarray
    counts: np.ndarray
    samples: int
    blocks: int


class Profile(Operation):
    """Sample profiles along an axis at each firing of ``trigger``: the quantities of
    :class:`~edmd2d.measurements.Profiles` (see :func:`edmd2d.measurements.profiles`).

    Each firing bins the disks' positions and velocities at that moment into slabs;
    :meth:`result` averages the samples so far, in ``blocks`` consecutive groups of
    equal size for the error bars.

    Parameters
    ----------
    trigger : Trigger
        When to sample, e.g. ``Every(dt=0.5)``.
    axis : {"x", "y"}, default "y"
    bins : int, default 20
        Number of slabs, >= 1.
    span : (float, float), optional
        The range of the slabs along ``axis``; default the box's length on it.

    Examples
    --------
    >>> import edmd2d as ed
    >>> from edmd2d import operations as op
    >>> sim = ed.make_gas(200, 0.2, seed=1)
    >>> p = op.Profile(op.Every(dt=0.5), bins=4)
    >>> _ = sim.run(until=5.0, operations=[p])
    >>> prof = p.result(blocks=5)
    >>> prof.samples, prof.density.shape
    (10, (4,))
    """

    def __init__(self, trigger: Trigger, *, axis: str = "y", bins: int = 20,
                 span: ArrayLike | None = None) -> None:
        super().__init__(trigger)
        if axis not in _AXES:
            raise ValueError(f"axis must be 'x' or 'y', got {axis!r}")
        self.axis = axis
        self.bins = as_count("bins", bins, minimum=1)
        self._span = None
        if span is not None:
            lo, hi = as_float_array("span", span, (2,))
            if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
                raise ValueError(f"span must be two finite numbers, low < high, got {span!r}")
            self._span = (float(lo), float(hi))
        self._edges: np.ndarray | None = None
        self._across = 0.0
        self._rows: list[np.ndarray] = []  # per sample: (bins, 7) sums

    def begin(self, sim: Simulation) -> None:
        """Fix the slabs from ``sim``'s box (on the first run).

        Parameters
        ----------
        sim : Simulation
        """
        if self._edges is not None:
            return
        k = _AXES[self.axis]
        lo, hi = (0.0, float(sim.box.size[k])) if self._span is None else self._span
        self._edges = np.linspace(lo, hi, self.bins + 1)
        self._across = float(sim.box.size[1 - k])

    def __call__(self, sim) -> None:
        """Bin the disks of ``sim`` as they are now: one sample."""
        assert self._edges is not None  # (set by begin)
        mass = np.asarray(sim.masses)
        keep = np.isfinite(mass)
        pos = np.asarray(sim.positions)[keep]
        vel = np.asarray(sim.velocities)[keep]
        m = mass[keep]
        area = math.pi * np.asarray(sim.radii)[keep] ** 2
        k = _AXES[self.axis]
        slab = np.searchsorted(self._edges, pos[:, k], side="right") - 1
        inside = (slab >= 0) & (slab < self.bins)
        slab, m, vel, area = slab[inside], m[inside], vel[inside], area[inside]
        # Per slab: visits, area, mass, momentum (2), sum m v^2.
        sums = np.zeros((self.bins, 6))
        for col, w in enumerate((np.ones(len(m)), area, m, m * vel[:, 0], m * vel[:, 1],
                                 m * (vel ** 2).sum(axis=1))):
            sums[:, col] = np.bincount(slab, weights=w, minlength=self.bins)
        self._rows.append(sums)

    @property
    def samples(self) -> int:
        """The samples taken so far."""
        return len(self._rows)

    def result(self, blocks: int = 10) -> Profiles:
        """The profiles over the samples so far, in ``blocks`` groups for the errors.

        Parameters
        ----------
        blocks : int, default 10
            >= 1 and at most the number of samples; a remainder of samples that does
            not fill a block is left out.

        Returns
        -------
        Profiles

        Raises
        ------
        ValueError
            For fewer samples than ``blocks``.
        """
        blocks = as_count("blocks", blocks, minimum=1)
        if self._edges is None or len(self._rows) < blocks:
            raise ValueError(f"{len(self._rows)} samples taken, fewer than the {blocks} "
                             "blocks asked for: run longer or sample more often")
        per = len(self._rows) // blocks
        used = np.array(self._rows[:per * blocks])
        block = used.reshape(blocks, per, self.bins, 6).sum(axis=1)  # (blocks, bins, 6)
        widths = np.diff(self._edges) * self._across
        visits, area, mass = block[..., 0], block[..., 1], block[..., 2]
        momentum, kinetic = block[..., 3:5], block[..., 5]
        density = visits / (per * widths)
        packing = area / (per * widths)
        with np.errstate(invalid="ignore", divide="ignore"):
            flow = momentum / mass[..., None]
            heat = (kinetic - (momentum ** 2).sum(axis=-1) / mass) / (2.0 * (visits - 1.0))
        heat = np.where(visits >= 2, heat, np.nan)
        totals = used.sum(axis=0)
        with np.errstate(invalid="ignore", divide="ignore"):
            u = totals[:, 3:5] / totals[:, 2:3]
        return Profiles(
            axis=self.axis, edges=_frozen(self._edges),
            centres=_frozen(0.5 * (self._edges[1:] + self._edges[:-1])),
            density=_frozen(density.mean(axis=0)), density_error=_frozen(_stderr(density)),
            packing_fraction=_frozen(packing.mean(axis=0)),
            packing_fraction_error=_frozen(_stderr(packing)),
            velocity=_frozen(u), velocity_error=_frozen(_stderr(flow)),
            temperature=_frozen(heat.mean(axis=0)), temperature_error=_frozen(_stderr(heat)),
            counts=_frozen(totals[:, 0].round().astype(np.int64)),
            samples=per * blocks, blocks=blocks)


def profiles(sim: Simulation, duration: float, *, samples: int = 100, blocks: int = 10,
             axis: str = "y", bins: int = 20, span: ArrayLike | None = None,
             progress: _progress.ProgressArg = False) -> Profiles:
    """Run ``sim`` for ``duration`` and measure profiles along ``axis``: density,
    packing fraction, flow velocity and granular temperature in ``bins`` slabs, with
    error bars.

    The state is sampled ``samples`` times, every ``duration / samples`` (the last at
    the end of the window); the errors are the standard errors of the averages over
    ``blocks`` consecutive groups of samples (make a block much longer than the time
    over which the profile's fluctuations are correlated).  One run with a
    :class:`edmd2d.operations.Profile`; to sample while the same run does other things,
    pass that operation to :meth:`~edmd2d.Simulation.run`.

    Parameters
    ----------
    sim : Simulation
        Advanced in place by ``duration``.
    duration : float
        > 0.
    samples : int, default 100
        >= ``blocks``.
    blocks : int, default 10
        >= 1.
    axis : {"x", "y"}, default "y"
    bins : int, default 20
    span : (float, float), optional
        The range of the slabs along ``axis`` (default: the whole box).
    progress : bool or tqdm bar, default False

    Returns
    -------
    Profiles

    Raises
    ------
    ValueError
        For a non-positive ``duration``, fewer ``samples`` than ``blocks``, an
        ``axis`` other than ``"x"`` or ``"y"``, or a bad ``span``.

    Examples
    --------
    A uniform gas: five slabs of equal area, which hold all 400 disks at every sample.

    >>> import edmd2d as ed
    >>> sim = ed.make_gas(400, 0.2, seed=2)
    >>> prof = ed.measurements.profiles(sim, 20.0, bins=5)
    >>> round(float(prof.density.sum() * sim.box.width * sim.box.height / 5), 9)
    400.0
    >>> prof.density.shape, prof.velocity.shape, prof.samples
    ((5,), (5, 2), 100)
    """
    duration = as_positive_float("duration", duration)
    samples = as_count("samples", samples, minimum=1)
    blocks = as_count("blocks", blocks, minimum=1)
    if samples < blocks:
        raise ValueError(f"samples ({samples}) must be at least blocks ({blocks})")
    op = Profile(Every(dt=duration / samples), axis=axis, bins=bins, span=span)
    _run_window(sim, duration, op, progress, "profiles")
    return op.result(blocks)


@dataclass(frozen=True)
class Bed:
    """The disks at rest under gravity, as a bed: its height and packing fraction
    (:func:`edmd2d.measurements.bed`).  Heights are measured against gravity from the
    ``bottom``.

    Attributes
    ----------
    disks : int
        The disks at rest.
    bottom : float
        The floor (the box wall gravity points to), or on a periodic axis the lowest
        point of a disk at rest.
    height : float
        The mean height of the bed's top surface above the bottom: over columns one
        largest diameter wide across the box, the highest point of a disk at rest whose
        centre lies in the column (the bottom for a column without one).
    top : float
        The height of the highest point of a disk at rest.
    band : (float, float)
        The heights between which ``packing_fraction`` is measured: from the bottom to
        ``skin`` below ``height``, clear of the surface's roughness.
    packing_fraction : float
        The area of the disks at rest within ``band`` (exactly: each disk's part between
        the band's lines) over the band's area; NaN for an empty band.
    """

    disks: int
    bottom: float
    height: float
    top: float
    band: tuple[float, float]
    packing_fraction: float


def bed(sim: Simulation, *, skin: float | None = None) -> Bed:
    """The height and packing fraction of the bed of disks at rest in ``sim``.

    Gravity must point along a box axis.  The bed is the disks at rest
    (:attr:`~edmd2d.Simulation.resting`); immovable disks and disks in flight are not
    part of it.  On an axis along gravity that is periodic, the bottom is the lowest
    disk at rest: a bed across the box's edge there is not measured as one.

    Parameters
    ----------
    sim : Simulation
    skin : float, optional
        >= 0: how far below the bed's mean height the band of the packing fraction
        ends; default two largest diameters (the roughness of a settled surface).

    Returns
    -------
    Bed
        With ``disks = 0`` and NaN heights when no disk is at rest.

    Raises
    ------
    ValueError
        Without gravity, with gravity not along an axis, or for a negative ``skin``.

    Examples
    --------
    One row of touching disks on a floor: the band from the floor to the top of the
    row holds the disks' area, a quarter of pi of it.

    >>> import numpy as np, edmd2d as ed
    >>> x = np.arange(10) + 0.5
    >>> sim = ed.Simulation(np.c_[x, np.full(10, 0.5)], np.zeros((10, 2)), 0.5,
    ...                     box=ed.Box(10.0, 5.0, periodic=False), gravity=(0, -1),
    ...                     restitution=0.9)
    >>> _ = sim.advance(until=10.0)  # (past the first search for disks at rest)
    >>> b = ed.measurements.bed(sim, skin=0.0)
    >>> b.disks, round(b.height, 6), round(b.packing_fraction / (np.pi / 4), 6)
    (10, 1.0, 1.0)
    """
    g = sim.gravity
    if g is None or not np.any(g):
        raise ValueError("a bed needs gravity: this simulation has none")
    if g[0] != 0.0 and g[1] != 0.0:
        raise ValueError(f"a bed is measured with gravity along a box axis, got {tuple(g)}")
    d_max = 2.0 * float(np.max(sim.radii))
    skin = 2.0 * d_max if skin is None else float(as_float_array("skin", skin, ()))
    if not skin >= 0.0:
        raise ValueError(f"skin must be >= 0, got {skin}")
    rest = np.asarray(sim.resting)
    return _bed(np.asarray(sim.positions)[rest], np.asarray(sim.radii)[rest], sim.box,
                g, skin, d_max)


def _bed(pos, rad, box: Box, g, skin: float, d_max: float) -> Bed:
    """:func:`bed` of the disks ``pos``, ``rad`` (checked arguments)."""
    k = 0 if g[0] != 0.0 else 1
    length = float(box.size[k])
    across = float(box.size[1 - k])
    n = len(pos)
    if n == 0:
        return Bed(0, math.nan, math.nan, math.nan, (math.nan, math.nan), math.nan)
    # Heights against gravity, and the floor.
    up = pos[:, k] if g[k] < 0.0 else length - pos[:, k]
    bottom = 0.0 if not box.periodic[k] else float(np.min(up - rad))
    h = up - bottom
    columns = max(int(across // d_max), 1)
    column = np.minimum((pos[:, 1 - k] / across * columns).astype(np.int64), columns - 1)
    tops = np.zeros(columns)
    np.maximum.at(tops, column, h + rad)
    height = float(tops.mean())
    lo, hi = 0.0, height - skin
    if hi <= lo:
        packing = math.nan
    else:
        area = _area_below(hi - h, rad) - _area_below(lo - h, rad)
        packing = float(area.sum() / (across * (hi - lo)))
    return Bed(n, bottom, height, float(np.max(h + rad)), (lo, hi), packing)


def _area_below(d: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The area of a disk of radius ``r`` below a line ``d`` above its centre."""
    d = np.clip(d, -r, r)
    return r * r * (math.pi - np.arccos(d / r)) + d * np.sqrt(r * r - d * d)


@dataclass(frozen=True)
class Discharge:
    """Results of :func:`discharge`: the rate at which disks flow through a periodic
    axis (a silo whose outflow re-enters at its top).

    Attributes
    ----------
    rate : float
        Disks per unit time that cross a line across ``axis`` towards lower
        coordinates, net (negative: the flow goes the other way), averaged over the
        line's position along the axis and over the window.
    error : float
        Standard error of ``rate`` from the block values (independent blocks assumed:
        make them longer than the flow's correlation time).
    block_rates : ndarray, shape (blocks,)
        The rate in each block.
    duration : float
        The window's length.
    axis : int
        The periodic axis (0 ``x``, 1 ``y``).
    """

    rate: float
    error: float
    block_rates: np.ndarray
    duration: float
    axis: int


def discharge(sim, duration: float, *, blocks: int = 10, axis: int = 1,
              progress: _progress.ProgressArg = False) -> Discharge:
    """Run ``sim`` for ``duration`` and measure the rate at which its disks flow
    through the periodic ``axis``: a silo's discharge, its outflow re-entering at the
    top through the periodic boundary.

    A disk's unwrapped coordinate along the axis changes by the period ``L`` each time
    it crosses the whole box, so ``-sum_i du_i / L`` over a block is the net number of
    crossings of a line across the axis, averaged over where the line lies.  Each
    block gives a rate; the result is their mean with its standard error.

    Parameters
    ----------
    sim : Simulation
        Periodic along ``axis``; it is advanced by ``duration``.
    duration : float
        Length of the window, > 0.
    blocks : int, default 10
        Number of equal blocks, >= 2.
    axis : int, default 1
        The axis of the flow: 0 (``x``) or 1 (``y``).
    progress : bool or tqdm, optional
        As in :func:`measure`.

    Returns
    -------
    Discharge

    Raises
    ------
    TypeError, ValueError
        For a duration that is not > 0, fewer than 2 blocks, an axis other than 0 or
        1, or a box not periodic along it; the simulation is then not advanced.

    Examples
    --------
    A column of disks falling through a box periodic in ``y`` crosses it at the rate
    its speed gives:

    >>> import edmd2d as ed
    >>> box = ed.Box(4.0, 10.0, periodic=True)
    >>> sim = ed.Simulation([[2.0, 5.0]], [[0.0, -2.0]], 0.5, box=box)
    >>> round(ed.measurements.discharge(sim, 10.0, blocks=2).rate, 12)
    0.2
    """
    require_simulation(sim, "discharge()")
    duration = as_positive_float("duration", duration)
    blocks = as_count("blocks", blocks, minimum=2)
    if isinstance(axis, (bool, np.bool_)) or not isinstance(axis, (int, np.integer)) or (
            axis not in (0, 1)):
        raise ValueError(f"axis must be 0 (x) or 1 (y), got {axis!r}")
    axis = int(axis)
    if not sim.box.periodic[axis]:
        raise ValueError(f"discharge: the box is not periodic along axis {axis}: a flow "
                         f"through it has nowhere to re-enter")
    period = sim.box.size[axis]
    movable = np.isfinite(sim.masses)
    start = sim.time
    u = sim.unwrapped_positions[movable, axis]
    rates = np.empty(blocks)
    bar, owned = _progress.bar(progress, total=duration, unit="time", desc="discharge")
    try:
        for b in range(blocks):
            t0 = sim.time
            t1 = start + duration * (b + 1) / blocks
            sim.advance(until=t1, progress=bar if bar is not None else False)
            u1 = sim.unwrapped_positions[movable, axis]
            rates[b] = -float(np.sum(u1 - u)) / (period * (t1 - t0))
            u = u1
    finally:
        if owned:
            bar.close()
    return Discharge(float(np.mean(rates)), _stderr(rates), _frozen(rates), duration, axis)
