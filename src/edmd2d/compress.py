"""Compression by growing disks: dense fluids, crystals and jammed packings.

:func:`compress` grows every disk of a simulation at a constant speed proportional to
its radius (the Lubachevsky-Stillinger algorithm: Lubachevsky and Stillinger, J. Stat.
Phys. 60, 561 (1990)), so that the packing fraction rises while the events stay
exact (:meth:`edmd2d.Simulation.set_growth`).  The contacts of growing disks heat the
system; the temperature is rescaled at short intervals, with the total momentum kept
at zero.  Along the way the reduced pressure ``Z = P A / (N kT)`` is measured from the
collision virial of each interval.  The compression stops at a target packing
fraction, or once ``Z`` passes a threshold: the disks have jammed.

Slowly compressed, equal disks follow the equilibrium equation of state and freeze
into a crystal that approaches close packing (``pi / (2 sqrt 3) = 0.9069``); fast
compressions, and mixtures, jam in disordered packings (for the 50:50 mixture of
diameter ratio 1.4, near 0.84: O'Hern, Silbert, Liu and Nagel, Phys. Rev. E 68,
011306 (2003)).  :func:`edmd2d.contacts.contact_network` analyses the contacts of a
jammed packing.

Examples
--------
>>> import edmd2d as ed
>>> gas = ed.random_gas(200, 0.3, seed=1)
>>> result = ed.compress(gas, 0.6, rate=0.01)
>>> result.reached
'target'
>>> round(result.packing_fraction, 12)
0.6
>>> result.simulation.growth is None  # an ordinary simulation again
True
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from . import progress as _progress
from ._sums import weighted_sum
from ._validate import as_positive_float
from .measurements import container_area, kinetic_temperature
from .simulation import Simulation
from .theory import ETA_CLOSE_PACKED

__all__ = ["compress", "Compression", "packing_fraction", "CLOSE_PACKING", "DEFAULT_MAX_PRESSURE"]

#: The densest packing of equal disks, the triangular lattice: ``pi / (2 sqrt 3)``
#: (:data:`edmd2d.theory.ETA_CLOSE_PACKED`).
CLOSE_PACKING = ETA_CLOSE_PACKED

#: The reduced pressure at which :func:`compress` counts the disks as jammed unless
#: told otherwise (its ``max_pressure``).  Touching disks are then about ``1 / Z`` of
#: their diameter apart, and :func:`edmd2d.contact_network`'s default tolerance is
#: ``100 / DEFAULT_MAX_PRESSURE`` (its contacts' gaps lie below it).
DEFAULT_MAX_PRESSURE = 1e9


def packing_fraction(sim: Simulation) -> float:
    """The fraction of the container's area the disks cover now:
    ``sum(pi r^2) / A``, with ``A`` from :func:`edmd2d.measurements.container_area`.

    Parameters
    ----------
    sim : Simulation

    Returns
    -------
    float
    """
    return float(np.pi * np.sum(sim.radii ** 2)) / container_area(sim)


@dataclass(frozen=True, repr=False)
class Compression:
    """What :func:`compress` did, and the simulation it ended with.

    Attributes
    ----------
    simulation : Simulation
        An elastic simulation of fixed radii at the final packing (at the temperature
        of the compression), ready to run or measure.
    reached : str
        ``"target"`` if the target packing fraction was reached, ``"jammed"`` if the
        reduced pressure passed ``max_pressure`` first.
    target : float or None
        The target packing fraction asked for.
    packing_fraction : float
        The final packing fraction.
    reduced_pressure : float
        ``Z`` over the last interval.
    rate : float
        The compression rate: the growth speed of the mean diameter in units of the
        thermal speed ``sqrt(kT / m)`` (``m`` the mean mass).
    growth : float
        The growth rate of the radii per unit time (:attr:`Simulation.growth`).
    temperature : float
        The ``kT`` the temperature was kept at.
    times, packing_fractions, reduced_pressures : numpy.ndarray
        At the end of each interval: the time, the packing fraction, and ``Z`` over
        the interval.
    temperatures : numpy.ndarray
        The kinetic temperature at the end of each interval, before it was rescaled
        to ``temperature`` (the heating by the growth).
    collisions : numpy.ndarray
        The disk-disk collisions since the start of the compression, at the end of
        each interval.
    """

    simulation: object
    reached: str
    target: float | None
    packing_fraction: float
    reduced_pressure: float
    rate: float
    growth: float
    temperature: float
    times: np.ndarray
    packing_fractions: np.ndarray
    reduced_pressures: np.ndarray
    temperatures: np.ndarray
    collisions: np.ndarray

    @property
    def jammed(self) -> bool:
        """Whether the compression stopped because the pressure passed its threshold."""
        return self.reached == "jammed"

    def __repr__(self) -> str:
        return (f"Compression(reached={self.reached!r}, packing_fraction="
                f"{self.packing_fraction:.6f}, reduced_pressure={self.reduced_pressure:.4g}, "
                f"rate={self.rate:g}, intervals={len(self.times)}, "
                f"collisions={int(self.collisions[-1]) if len(self.collisions) else 0})")


def compress(system: Simulation, target: float | None = None, *, rate: float = 1e-3,
             max_pressure: float = DEFAULT_MAX_PRESSURE, temperature: float | None = None,
             rescale_every: float = 2.0,
             progress: _progress.ProgressArg = False) -> Compression:
    """Compress a hard-disk system by growing its disks, to a packing fraction or until
    it jams.

    Every radius grows at a constant speed proportional to its value at the start
    (a mixture keeps its size ratios).  After every ``rescale_every`` times N
    collisions (N disks) the velocities are rescaled to ``temperature`` about the
    centre of mass
    (whose velocity is set to zero at the start), and the reduced pressure of the
    interval is recorded: ``Z = 1 + W / (2 N kT t)``, with ``W`` the collision virial
    (the sum of impulse times contact distance) over the interval of length ``t``,
    and ``kT`` the mean of the temperatures at its ends (the virial pressure of
    :func:`edmd2d.measure`).  Near jamming ``Z`` grows as ``2 / (1 - phi / phi_J)``
    (the free-volume law of hard disks) and the collision rate with it, so the
    compression stops when ``Z`` passes ``max_pressure``: the gaps between touching
    disks are then of order ``1 / Z`` of their diameter.

    Parameters
    ----------
    system : Simulation
        The disks to compress; it is not changed (the compression runs on a copy).
        Elastic disks in free flight, all movable.  Build one with
        :func:`edmd2d.random_gas` (a random start at low density) or
        :func:`edmd2d.make_gas`.
    target : float, optional
        The packing fraction to reach (above the present one; at most
        :data:`CLOSE_PACKING` for equal disks, below 1 for a mixture).  Default:
        compress until jammed.
    rate : float, default 1e-3
        The growth speed of the mean diameter in units of the thermal speed
        ``sqrt(kT / m)``, > 0.  ``1e-3`` is slow enough for equal disks to follow the
        equilibrium equation of state through the fluid; ``1e-1`` is fast.
    max_pressure : float, default 1e9
        The reduced pressure at which the disks count as jammed, > 1
        (:data:`DEFAULT_MAX_PRESSURE`).  :func:`edmd2d.contact_network`'s default
        tolerance, ``1e-7``, suits the packings of this default; for a lower
        ``max_pressure``, pass it ``tol=100 / result.reduced_pressure``.
    temperature : float, optional
        The ``kT`` to keep, > 0.  Default: the system's kinetic temperature.
    rescale_every : float, default 2.0
        Disk-disk collisions between rescalings (and records), in units of the number
        of disks, > 0 (each disk takes part in twice as many on average).
    progress : bool or tqdm bar, default False
        ``True`` shows a progress bar of the packing fraction (with ``Z``).

    Returns
    -------
    Compression
        The final simulation and the record of the compression.  If the disks jam
        before the target, ``reached`` is ``"jammed"`` and a ``UserWarning`` says so.

    Raises
    ------
    TypeError, ValueError
        For a system that is not a Simulation or cannot grow (gravity, restitution
        below 1, heated walls, a thermostat, immovable disks, disks at rest), a target
        not above the present packing fraction, above close packing for equal disks,
        or at which the largest disk would not fit the box, and non-positive rates,
        pressures, temperatures or intervals.  Nothing is changed.

    Examples
    --------
    A small mixture compressed quickly jams in a disordered packing:

    >>> import numpy as np
    >>> import edmd2d as ed
    >>> radii = np.where(np.arange(100) % 2, 0.5, 0.7)
    >>> jam = ed.compress(ed.random_gas(100, 0.4, radii=radii, seed=2), rate=0.1,
    ...                   max_pressure=1e6)
    >>> jam.reached, 0.78 < jam.packing_fraction < 0.86
    ('jammed', True)
    """
    if not isinstance(system, Simulation):
        raise TypeError(f"compress() needs an edmd2d.Simulation, got {type(system).__name__}")
    rate = as_positive_float("rate", rate)
    max_pressure = as_positive_float("max_pressure", max_pressure)
    if not max_pressure > 1.0:
        raise ValueError(f"max_pressure must be > 1 (the ideal gas's Z), got {max_pressure}")
    rescale_every = as_positive_float("rescale_every", rescale_every)
    masses = system.masses
    if not np.isfinite(masses).all():
        raise ValueError("compress() needs movable disks: immovable ones would grow too, "
                         "and two of them meeting cannot be resolved")
    kt = kinetic_temperature(system) if temperature is None else as_positive_float(
        "temperature", temperature)
    if not kt > 0.0:
        raise ValueError("the disks are at rest (kT = 0): give them velocities first "
                         "(e.g. with set_velocities), which compress() then rescales")
    radii = system.radii
    phi0 = packing_fraction(system)
    if target is not None:
        target = as_positive_float("target", target)
        _check_target(system, target, phi0, radii)

    sim = system.__copy__()
    sim.set_growth(None)  # (its own growth, if any, ends: radii fixed at their values now)
    vel = sim.velocities
    sim.set_velocities(vel - weighted_sum(masses, vel) / masses.sum())
    sim.rescale_temperature(kt)
    growth = rate * math.sqrt(kt / float(masses.mean())) / (2.0 * float(radii.mean()))
    sim.set_growth(growth)  # (refuses physics that cannot grow)
    t_start = sim.time
    # The time at which the target is reached: the packing fraction grows as the
    # square of the radii's growth factor 1 + growth (t - t_start).
    t_end = (t_start + (math.sqrt(target / phi0) - 1.0) / growth if target is not None
             else None)
    n = len(sim)
    step = max(1, round(rescale_every * n))
    c_start = sim.counts.collisions
    record: dict[str, list] = {k: [] for k in ("t", "phi", "z", "kt", "coll")}
    total = round((target or CLOSE_PACKING) - phi0, 6)
    bar, owned = _progress.bar(progress, total=total, unit="phi", desc="compress")
    shown = 0.0
    reached = "jammed"
    sums = (0.0, 0.0)  # the previous interval's virial and integral of kT over time
    try:
        while True:
            t_a = sim.time
            w_a = sim._state.accumulators()["virial"]
            c_a = sim.counts.collisions
            sim.advance(until=t_end, collisions=step)
            kt_b = kinetic_temperature(sim)
            # Z = 1 + W / (2 N int kT dt), kT taken as linear over the interval.
            virial = sim._state.accumulators()["virial"] - w_a
            kt_time = 0.5 * (kt + kt_b) * (sim.time - t_a)
            if sim.counts.collisions - c_a < step // 2 and record["z"]:
                # The interval the target cut short joins the one before it, so that
                # no Z comes from a handful of collisions.
                virial += sums[0]
                kt_time += sums[1]
                for values in record.values():
                    values.pop()
            sums = (virial, kt_time)
            z = 1.0 + virial / (2.0 * n * kt_time) if kt_time > 0.0 else math.inf
            phi = phi0 * (1.0 + growth * (sim.time - t_start)) ** 2
            for key, value in zip(record, (sim.time, phi, z, kt_b,
                                           sim.counts.collisions - c_start)):
                record[key].append(value)
            sim.rescale_temperature(kt)
            if bar is not None:
                # (by what it shows, capped at its total: a merged interval's growth is
                # not counted twice, and rounding never takes the bar past its end)
                now = min(phi - phi0, total)
                bar.update(now - shown)
                shown = now
                bar.set_postfix_str(f"Z={z:.4g}", refresh=False)
            if t_end is not None and sim.time >= t_end:
                reached = "target"
                break
            if z >= max_pressure:
                break
    finally:
        if owned:
            bar.close()
    sim.set_growth(None)
    if reached == "jammed":
        final = packing_fraction(sim)
    else:
        assert target is not None  # (a target is reached only where one was given)
        final = target
    if reached == "jammed" and target is not None:
        warnings.warn(f"the disks jammed at packing fraction {final:.6f} (Z = "
                      f"{record['z'][-1]:.3g}) before the target {target}: returning the "
                      "jammed packing", UserWarning, stacklevel=2)
    arrays = {key: np.array(values) for key, values in record.items()}
    for a in arrays.values():
        a.flags.writeable = False
    return Compression(
        simulation=sim, reached=reached, target=target, packing_fraction=float(final),
        reduced_pressure=float(record["z"][-1]), rate=rate, growth=growth,
        temperature=kt, times=arrays["t"], packing_fractions=arrays["phi"],
        reduced_pressures=arrays["z"], temperatures=arrays["kt"],
        collisions=arrays["coll"].astype(np.int64))


def _check_target(sim, target: float, phi0: float, radii: np.ndarray) -> None:
    """Refuse a target packing fraction that cannot be reached by growing ``sim``."""
    if not target > phi0:
        raise ValueError(f"target {target} is not above the present packing fraction "
                         f"{phi0:.6g}: compress() only grows the disks")
    if np.all(radii == radii[0]) and target > CLOSE_PACKING:
        raise ValueError(f"target {target} is above close packing of equal disks, "
                         f"pi / (2 sqrt 3) = {CLOSE_PACKING:.6f}")
    if target >= 1.0:
        raise ValueError(f"target {target} must be below 1 (disks cannot cover the area)")
    largest = 2.0 * float(radii.max()) * math.sqrt(target / phi0)
    room = sim._outgrow_diameter()  # (where the engine stops a growing disk)
    if largest >= room:
        raise ValueError(f"at packing fraction {target} the largest disk would be "
                         f"{largest:.6g} wide, as wide as the box ({room:.6g}): use more "
                         "disks or a lower target")
