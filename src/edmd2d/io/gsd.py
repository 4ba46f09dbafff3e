"""GSD trajectories in the HOOMD schema, for OVITO, freud and HOOMD-blue tools.

:class:`Writer` appends frames of a :class:`~edmd2d.Simulation` to a GSD file;
:func:`record` runs a simulation and writes a frame at each of a list of times;
:func:`read` builds a Simulation from a frame (one written here, or by another
program); :func:`describe` says what a file holds and :func:`copy_until` keeps the
frames up to a time (those a run continued from a checkpoint goes on from).
Uses the ``gsd`` package, a dependency of edmd2d.

What a frame holds (HOOMD conventions):

- ``configuration.box = [W, H, 0, 0, 0, 0]`` and ``configuration.dimensions = 2``;
  ``configuration.step``: the number of events processed so far.  A sheared box
  (:class:`edmd2d.physics.Shear`) is written as HOOMD's triclinic box with the tilt
  ``xy = offset / H``, the images' offset (:attr:`Simulation.shear_offset
  <edmd2d.Simulation.shear_offset>`) taken between ``-W/2`` and ``W/2``: the images
  one box above sit ``xy H`` to the right, as Lees-Edwards boundaries place them, and
  OVITO and freud see the same neighbours across the sliding boundary.  The centres
  are then wrapped into that parallelogram, and ``image`` counts its sides.
- ``particles.position``: the centres at the frame's time, shifted so that the box is
  centred at the origin (``x - W/2``, ``y - H/2``, ``z = 0``), wrapped into the box;
  ``particles.image``: the periodic images crossed, so that ``position + image * L``
  is the unwrapped position; ``diameter`` (``2 r``), ``mass`` (an immovable disk's
  ``inf`` is stored as 0, HOOMD's "no mass"), ``velocity``, and ``typeid`` the species
  (types named ``"A"``, ``"B"``, ...).
- ``log/edmd2d/...``: what the schema has no place for, so that nothing is lost: the
  ``time``; the box's ``W, H`` in float64 (``box``); the ``periodic`` flags of the two
  axes (1 periodic, 0 walled); the wall segments ``walls`` as rows
  ``(x0, y0, x1, y1)`` in the frame's centred coordinates, as given, and where they
  are at the frame's time (``wall_positions``: segments that move, the family
  :class:`edmd2d.physics.MovingWalls`, have moved), and ``open_walls`` (1 for each
  segment open, ``Simulation.open_wall``);
  ``gravity``; ``<family>/<keyword>`` for each physics family registered with
  :func:`edmd2d.physics.register` that the simulation has (which :func:`read` passes
  back); ``immovable`` (1 for disks of infinite mass); the counts
  ``collisions``, ``wall_collisions`` and ``events``; the kinetic and total
  ``energy``; and, over the window from the writer's first frame to this one, the
  ``pressure`` (virial: ``P A = N kT + sum J |r_ij| / 2t``, with ``kT`` averaged over
  the frames written) and the ``wall_pressure`` on each box wall (x=0, x=W, y=0,
  y=H: its impulse per unit length and time, exact).
- ``log/particles/edmd2d/resting``: where disks come to rest (the family
  :class:`edmd2d.physics.Resting`), 1 for each disk at rest and 0 for each in flight
  (a per-particle quantity, which OVITO shows as a particle property).  :func:`read`
  starts every disk in flight: the disks at rest in a frame come to rest again.

**Precision.** GSD stores positions, velocities and diameters in float32: about 7
significant digits.  In a dense system two touching disks' centres are then known to
about ``1e-7`` of the box size, so a frame read back can overlap by that much, more
than :class:`~edmd2d.Simulation` accepts (``1e-9``).  :func:`read` offers
``radius_scale`` to shrink the disks by such a fraction; for exact restarts use
:mod:`edmd2d.checkpoint`, which keeps float64.
"""

from __future__ import annotations

import math
import os
import string
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .. import measurements as _measurements
from .. import physics as _physics
from .._atomic import replacing_path, umask_mode
from .._operations import Operation, Trigger
from ..geometry import Box, Wall
from ..simulation import Simulation

__all__ = ["Writer", "WriteGSD", "record", "read", "describe", "copy_until"]


def _gsd_hoomd():
    try:
        import gsd.hoomd
    except ImportError:  # pragma: no cover - gsd is a dependency
        raise ImportError("GSD files need the gsd package, a dependency of edmd2d that "
                          "is missing here: pip install gsd") from None
    return gsd.hoomd


def _type_names(n: int) -> list[str]:
    letters = string.ascii_uppercase
    return [letters[k] if k < 26 else f"T{k}" for k in range(n)]


class Writer:
    """Append frames of a simulation to a GSD file.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    mode : {"w", "a"}, default "w"
        ``"w"`` creates the file (replacing one that exists), ``"a"`` appends to it.

    Examples
    --------
    >>> import os, tempfile
    >>> import edmd2d as ed
    >>> from edmd2d.io import gsd
    >>> sim = ed.make_gas(100, 0.3, seed=1)
    >>> path = os.path.join(tempfile.mkdtemp(), "gas.gsd")
    >>> with gsd.Writer(path) as out:
    ...     for t in (1.0, 2.0, 3.0):
    ...         _ = sim.advance(until=t)
    ...         out.write(sim)
    >>> gsd.read(path, frame=-1).time
    3.0
    """

    def __init__(self, path: str | os.PathLike[str], mode: str = "w") -> None:
        if mode not in ("w", "a"):
            raise ValueError(f"mode must be 'w' or 'a', got {mode!r}")
        new = mode == "w" or not os.path.exists(path)
        self._file = _gsd_hoomd().open(str(path), mode)
        if new:  # (the gsd library creates files with mode 0640 whatever the umask)
            os.chmod(path, umask_mode())
        # (time, accumulators) at the first frame written
        self._start: tuple[float, dict] | None = None
        self._temperatures: list[float] = []

    def write(self, sim: Simulation) -> None:
        """Append the state of ``sim`` at its current time as a frame.

        Parameters
        ----------
        sim : Simulation
            The simulation to write; it is read, not advanced.

        Raises
        ------
        TypeError
            For anything but a :class:`~edmd2d.Simulation`.
        """
        if not isinstance(sim, Simulation):
            raise TypeError(f"write() needs an edmd2d.Simulation, got {type(sim).__name__}")
        self._file.append(_frame(sim, self))

    def close(self) -> None:
        """Close the file (also on leaving a ``with`` block)."""
        self._file.close()

    def __enter__(self) -> Writer:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _frame(sim, writer: Writer):
    hoomd = _gsd_hoomd()
    box = sim.box
    width, height = box.width, box.height
    centre = np.array([width / 2.0, height / 2.0])
    pos = sim.positions - centre
    unwrapped = sim.unwrapped_positions - centre
    # A sheared box is the parallelogram whose second side is (offset, height): its
    # tilt, taken between -width/2 and width/2, and the centres wrapped into it.
    tilt = sim.shear_offset
    if tilt >= 0.5 * width:
        tilt -= width
    if tilt != 0.0:
        pos[:, 0] -= width * np.floor((pos[:, 0] - tilt / height * pos[:, 1]) / width + 0.5)
    image = np.zeros((len(sim), 3), np.int32)
    if box.periodic[1]:
        image[:, 1] = np.round((unwrapped[:, 1] - pos[:, 1]) / height)
    if box.periodic[0]:
        image[:, 0] = np.round((unwrapped[:, 0] - pos[:, 0] - image[:, 1] * tilt) / width)
    species = sim.species
    frame = hoomd.Frame()
    frame.configuration.box = [width, height, 0.0, tilt / height, 0.0, 0.0]
    frame.configuration.dimensions = 2
    frame.configuration.step = sim.counts.events
    p = frame.particles
    p.N = len(sim)
    p.types = _type_names(int(species.max()) + 1)
    p.typeid = species.astype(np.uint32)
    p.position = np.c_[pos, np.zeros(len(sim))].astype(np.float32)
    p.image = image
    p.diameter = (2.0 * sim.radii).astype(np.float32)
    masses = sim.masses
    p.mass = np.where(np.isfinite(masses), masses, 0.0).astype(np.float32)
    p.velocity = np.c_[sim.velocities, np.zeros(len(sim))].astype(np.float32)

    acc = sim._accumulators()
    temperature = _measurements.kinetic_temperature(sim)
    if writer._start is None:
        writer._start = (sim.time, acc)
    writer._temperatures.append(temperature)
    t0, acc0 = writer._start
    elapsed = sim.time - t0
    pressure = wall_pressure = math.nan
    if elapsed > 0.0:
        n = int(np.isfinite(masses).sum())
        kt = float(np.nanmean(writer._temperatures))
        area = _measurements.container_area(sim)
        pressure = (n * kt + (acc["virial"] - acc0["virial"]) / (2.0 * elapsed)) / area
        lengths = np.array([height, height, width, width])
        wall_pressure = (acc["box_impulse"] - acc0["box_impulse"]) / (elapsed * lengths)
    walls = np.array([[*np.subtract(w.start, centre), *np.subtract(w.end, centre)]
                      for w in sim.walls], np.float64).reshape(-1, 4)
    counts = sim.counts
    frame.log = {
        "edmd2d/time": np.array([sim.time]),
        "edmd2d/box": np.array([width, height]),  # (float64: the box above is float32)
        "edmd2d/periodic": np.array(box.periodic, np.uint8),
        "edmd2d/walls": walls,
        "edmd2d/open_walls": np.asarray(sim.open_walls, np.uint8),
        # (Where the segments are at the frame's time: moving segments move.)
        "edmd2d/wall_positions": (np.asarray(sim.wall_positions, np.float64)
                                  - np.asarray(centre, np.float64)).reshape(-1, 4),
        "edmd2d/gravity": np.asarray(sim.gravity, np.float64),
        "edmd2d/immovable": (~np.isfinite(masses)).astype(np.uint8),
        "edmd2d/collisions": np.array([counts.collisions], np.int64),
        "edmd2d/wall_collisions": np.array([counts.wall_collisions], np.int64),
        "edmd2d/events": np.array([counts.events], np.int64),
        "edmd2d/kinetic_energy": np.array([sim.kinetic_energy()]),
        "edmd2d/total_energy": np.array([sim.total_energy()]),
        "edmd2d/pressure": np.array([pressure]),
        "edmd2d/wall_pressure": np.broadcast_to(wall_pressure, (4,)).astype(np.float64),
    }
    for name, family in sim.families.items():
        for key, value in family.log().items():
            frame.log[f"edmd2d/{name}/{key}"] = np.asarray(value, np.float64)
    if "resting" in sim.families:  # (a per-particle quantity, as HOOMD logs them)
        frame.log["particles/edmd2d/resting"] = sim.resting.astype(np.uint8)
    if "rough" in sim.families:
        # HOOMD's orientation (a rotation by the angle about z), principal moments of
        # inertia and angular momentum quaternion P = 2 q (0, 0, 0, I w) (Kamberaj's
        # form, HOOMD's convention: (-2 s L, 0, 0, 2 c L) for q = (c, 0, 0, s)); the
        # angle and angular velocity in float64 as per-particle quantities.
        angles = sim.angles
        c, s = np.cos(0.5 * angles), np.sin(0.5 * angles)
        orientation = np.zeros((sim.n, 4), np.float32)
        orientation[:, 0] = c
        orientation[:, 3] = s
        frame.particles.orientation = orientation
        inertia = np.zeros((sim.n, 3), np.float32)
        q = sim.families["rough"].inertia
        moment = np.where(np.isfinite(masses), q * masses * sim.radii ** 2, 0.0)
        inertia[:, 2] = moment
        frame.particles.moment_inertia = inertia
        spin = sim.angular_velocities
        angmom = np.zeros((sim.n, 4), np.float32)
        angmom[:, 0] = -2.0 * s * moment * spin
        angmom[:, 3] = 2.0 * c * moment * spin
        frame.particles.angmom = angmom
        frame.log["particles/edmd2d/angular_velocity"] = np.asarray(spin, np.float64)
        frame.log["particles/edmd2d/angle"] = np.asarray(angles, np.float64)
    return frame


def record(sim: Simulation, path: str | os.PathLike[str], times: ArrayLike,
           mode: str = "w") -> None:
    """Advance ``sim`` to each of ``times`` (increasing, not before ``sim.time``) and
    write a frame there.

    Parameters
    ----------
    sim : Simulation
    path : str or os.PathLike
    times : array_like of float
    mode : {"w", "a"}, default "w"
    """
    times = np.asarray(times, np.float64)
    if times.ndim != 1 or not np.all(np.isfinite(times)):
        raise ValueError("times must be a 1-D array of finite times")
    if np.any(np.diff(times) < 0) or (len(times) and times[0] < sim.time):
        raise ValueError(f"times must increase from the simulation's time {sim.time}")
    with Writer(path, mode) as out:
        for t in times:
            sim.advance(until=float(t))
            out.write(sim)


def read(path: str | os.PathLike[str], frame: int = -1, *, radius_scale: float = 1.0,
         **physics: Any) -> Simulation:
    """A :class:`~edmd2d.Simulation` from a frame of a GSD file.

    Parameters
    ----------
    path : str or os.PathLike
    frame : int, default -1
        Which frame (negative counts from the end).
    radius_scale : float, default 1.0
        Factor on the radii read (in ``(0, 1]``): float32 positions of a dense frame
        can overlap by ``~1e-7`` of the box (see the module notes).
    **physics
        Keywords passed to the Simulation (``restitution=``, ``gravity=``, ...);
        ``gravity`` and the wall segments default to those logged by edmd2d.

    Returns
    -------
    Simulation
        At the frame's logged time (0 for a frame without one).  Only the state is
        read: counts, tallies and random numbers start afresh (restart exactly from a
        checkpoint instead).

    Raises
    ------
    ValueError
        For a frame that is not two-dimensional, a tilted box, a missing frame, or a
        state that is not a valid hard-disk state (overlaps, disks outside the box):
        the Simulation's own error, naming the disks.
    """
    hoomd = _gsd_hoomd()
    if not 0.0 < radius_scale <= 1.0:
        raise ValueError(f"radius_scale must lie in (0, 1], got {radius_scale}")
    with hoomd.open(str(path), "r") as traj:
        if not -len(traj) <= frame < len(traj):
            raise ValueError(f"{path} has {len(traj)} frames; frame {frame} does not exist")
        f = traj[frame]
        log = {k: np.asarray(v) for k, v in f.log.items()}
    if f.configuration.dimensions != 2:
        raise ValueError(f"frame {frame} of {path} is {f.configuration.dimensions}-"
                         "dimensional; edmd2d reads 2-dimensional frames")
    lx, ly, _, xy, _, _ = (float(v) for v in f.configuration.box)
    if "edmd2d/box" in log:
        lx, ly = (float(v) for v in log["edmd2d/box"])
    if xy != 0.0:
        if "edmd2d/shear/shear_rate" not in log:
            raise ValueError(f"frame {frame} of {path} has a tilted box (xy = {xy}) and "
                             "no shear rate: edmd2d boxes are rectangles, or sheared")
        # (Sheared: the tilt is the images' offset; the centres, wrapped into the
        # parallelogram, are wrapped back into the rectangle below.)
        physics.setdefault("shear_offset", xy * ly)
    px, py = log.get("edmd2d/periodic", np.array([1, 1]))
    periodic = (bool(px), bool(py))
    box = Box(lx, ly, periodic=periodic)
    centre = np.array([lx / 2.0, ly / 2.0])
    n = int(f.particles.N)
    pos = np.asarray(f.particles.position, np.float64)[:, :2] + centre
    diameter = (np.ones(n) if f.particles.diameter is None
                else np.asarray(f.particles.diameter, np.float64))
    radius = 0.5 * diameter * radius_scale
    for axis in range(2):  # (float32 rounding can put a centre a hair outside)
        length = box.size[axis]
        if periodic[axis]:
            pos[:, axis] %= length
        else:
            # A disk touching a box wall is stored a rounding of float32 away from it,
            # perhaps beyond: put it back, by no more than a few such roundings.
            rounding = 4.0 * float(np.spacing(np.float32(length)))
            low, high = radius, length - radius
            pos[:, axis] = np.where((pos[:, axis] < low) & (pos[:, axis] > low - rounding),
                                    low, pos[:, axis])
            pos[:, axis] = np.where((pos[:, axis] > high) & (pos[:, axis] < high + rounding),
                                    high, pos[:, axis])
    vel = (np.zeros((n, 2)) if f.particles.velocity is None
           else np.asarray(f.particles.velocity, np.float64)[:, :2])
    mass = (np.ones(n) if f.particles.mass is None
            else np.asarray(f.particles.mass, np.float64))
    if "edmd2d/immovable" in log:
        mass = np.where(log["edmd2d/immovable"].astype(bool), np.inf, mass)
    physics.setdefault("species", None if f.particles.typeid is None
                       else np.asarray(f.particles.typeid, np.int64))
    if "edmd2d/gravity" in log:
        physics.setdefault("gravity", log["edmd2d/gravity"])
    if "particles/edmd2d/angular_velocity" in log:
        physics.setdefault("angular_velocities", log["particles/edmd2d/angular_velocity"])
    if "particles/edmd2d/angle" in log:
        physics.setdefault("angles", log["particles/edmd2d/angle"])
    elif "edmd2d/rough/inertia" in log and f.particles.orientation is not None:
        # (Rough disks written before the angle was logged: from the orientation.)
        quat = np.asarray(f.particles.orientation, np.float64)
        physics.setdefault("angles", 2.0 * np.arctan2(quat[:, 3], quat[:, 0]))
    for name, family in _physics.FAMILIES.items():
        prefix = f"edmd2d/{name}/"
        logged = {key[len(prefix):]: value for key, value in log.items()
                  if key.startswith(prefix)}
        if logged:
            for key, value in family.keywords_from_log(logged).items():
                physics.setdefault(key, value)
    walls = [Wall(tuple(row[:2] + centre), tuple(row[2:] + centre))
             for row in log.get("edmd2d/walls", np.zeros((0, 4))).reshape(-1, 4)]
    time = float(log["edmd2d/time"][0]) if "edmd2d/time" in log else 0.0
    try:
        open_walls = np.flatnonzero(log.get("edmd2d/open_walls", np.zeros(0, np.uint8)))
        return Simulation(pos, vel, radius, mass, box=box, walls=walls,
                          open_walls=open_walls.tolist(), time=time, **physics)
    except ValueError as error:
        if "overlap" not in str(error):
            raise
        raise ValueError(
            f"frame {frame} of {path}: {error}.  GSD stores float32, so touching disks of "
            "a dense frame can overlap by about 1e-7 of a diameter when read back: "
            "read(..., radius_scale=1 - 1e-6) shrinks them by that much (exact restarts "
            "go through edmd2d.checkpoint)") from None


class WriteGSD(Operation):
    """Append a frame to the GSD file ``path`` when ``trigger`` fires (see
    :class:`~edmd2d.io.gsd.Writer`).

    Parameters
    ----------
    path : str or os.PathLike
    trigger : Trigger
    mode : {"w", "a"}, default "w"
        Create the file (replacing one that exists) or append to it.
    """

    def __init__(self, path: str | os.PathLike[str], trigger: Trigger, mode: str = "w") -> None:
        super().__init__(trigger)
        self.writer = Writer(path, mode)

    def __call__(self, sim) -> None:
        """Append a frame of ``sim``."""
        self.writer.write(sim)

    def close(self) -> None:
        """Close the file."""
        self.writer.close()


def describe(path: str | os.PathLike[str]) -> dict:
    """What a GSD file holds: its frames, the times they span, and the disks, box,
    species and walls of its last frame.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    dict
        ``frames``; ``times``, the first and last frames' ``(t0, t1)`` (``None``
        without edmd2d's time log); ``n``; ``box``, ``(W, H)``; ``periodic``, two
        bools (both true without edmd2d's log); ``species``, a list of dicts with
        ``name``, ``count``, ``diameters`` and ``masses`` (each the ``(min, max)``
        over the species); ``walls``, the number of wall segments; ``collisions``
        at the last frame (``None`` without edmd2d's log).  With no frames, only
        ``frames`` (0).

    Raises
    ------
    ValueError
        If ``path`` is not a GSD file.

    Examples
    --------
    >>> import os, tempfile
    >>> import edmd2d as ed
    >>> from edmd2d.io import gsd
    >>> path = os.path.join(tempfile.mkdtemp(), "gas.gsd")
    >>> gsd.record(ed.make_gas(50, 0.3, seed=1), path, times=[0.0, 1.0])
    >>> info = gsd.describe(path)
    >>> info["frames"], info["times"], info["n"], info["species"][0]["diameters"]
    (2, (0.0, 1.0), 50, (1.0, 1.0))
    """
    try:
        traj = _gsd_hoomd().open(str(path), "r")
    except Exception as exc:  # (gsd raises several kinds for a file that is not GSD)
        raise ValueError(f"{path} is not a GSD file ({exc})") from None
    with traj:
        frames = len(traj)
        if frames == 0:
            return {"frames": 0}
        first, last = traj[0], traj[frames - 1]
    log = {k: np.asarray(v) for k, v in last.log.items()}
    times = None
    if "edmd2d/time" in first.log and "edmd2d/time" in log:
        times = (float(np.asarray(first.log["edmd2d/time"])[0]),
                 float(log["edmd2d/time"][0]))
    p = last.particles
    typeid = np.zeros(p.N, int) if p.typeid is None else np.asarray(p.typeid)
    diameter = np.ones(p.N) if p.diameter is None else np.asarray(p.diameter, float)
    mass = np.ones(p.N) if p.mass is None else np.asarray(p.mass, float)
    types = list(p.types) if p.types is not None else ["A"]
    species = []
    for t in np.unique(typeid):
        sel = typeid == t
        species.append({"name": types[t] if t < len(types) else str(t),
                        "count": int(sel.sum()),
                        "diameters": (float(diameter[sel].min()), float(diameter[sel].max())),
                        "masses": (float(mass[sel].min()), float(mass[sel].max()))})
    walls = log.get("edmd2d/walls")
    collisions = log.get("edmd2d/collisions")
    return {
        "frames": frames, "times": times, "n": int(p.N),
        "box": tuple(float(v) for v in last.configuration.box[:2]),
        "periodic": tuple(bool(v) for v in log.get("edmd2d/periodic", np.array([1, 1]))),
        "species": species,
        "walls": 0 if walls is None else len(walls.reshape(-1, 4)),
        "collisions": None if collisions is None else int(collisions[0]),
    }


def copy_until(source: str | os.PathLike[str], target: str | os.PathLike[str], time: float) -> None:
    """Make ``target`` hold the frames of ``source`` up to the time ``time``, those a
    run continued from a checkpoint at ``time`` goes on from (later ones were written
    after the checkpoint).  ``target`` is replaced atomically; it may be ``source``.

    Parameters
    ----------
    source, target : str or os.PathLike
    time : float

    Raises
    ------
    ValueError
        If ``source`` is not a GSD file, or a frame of it has no time (it was not
        written by edmd2d); ``target`` is then left as it was.
    """
    hoomd = _gsd_hoomd()
    try:
        old = hoomd.open(str(source), "r")
    except Exception as exc:  # (gsd raises several kinds for a file that is not GSD)
        raise ValueError(f"{source} is not a GSD file ({exc})") from None
    with old, replacing_path(target) as tmp, hoomd.open(tmp, "w") as new:
        for k, frame in enumerate(old):
            if "edmd2d/time" not in frame.log:
                raise ValueError(f"frame {k} of {source} has no edmd2d/time: it was not "
                                 "written by edmd2d")
            if float(frame.log["edmd2d/time"][0]) <= time:
                new.append(frame)
