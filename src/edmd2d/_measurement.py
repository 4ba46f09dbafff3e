"""The record of a measurement over a window: :class:`Measurement`, what
:func:`edmd2d.measurements.measure` and a :class:`~edmd2d.measurements.Measure` return,
with its values, their error bars and a printed summary."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Measurement"]


@dataclass(frozen=True)
class Measurement:
    """Results of :func:`measure` over one time window (``k_B = 1``, 2D).

    Each ``*_error`` is the standard error of the mean over the window's blocks
    (``std(block values, ddof=1) / sqrt(blocks)``), ``nan`` with a single block.  It is
    an honest error bar when each block is much longer than the correlation time of the
    quantity (a few mean free times for the virial of a fluid; in 2D the stress
    autocorrelation has a slow ``1/t`` tail, so very short blocks underestimate it).

    Attributes
    ----------
    duration : float
        Length of the window.
    collisions : int
        Disk-disk collisions in the window.
    wall_collisions : int
        Collisions with box walls and wall segments in the window.
    blocks : int
        Number of equal sub-windows used for the error bars.
    n : int
        Number of movable disks (``mass < inf``): the ``N`` of every formula below.
    area : float
        The area ``A`` of the pressure and of ``Z``: the box's area, the area of the
        container of wall segments that holds the disks, or the one given (see
        :func:`measure` and :func:`container_area`).
    area_source : str
        Where ``area`` comes from: ``"box"``, ``"walls"`` (closed polygons of wall
        segments) or ``"given"`` (the ``area`` argument).
    degrees_of_freedom : int
        ``f = 2N`` minus one for every Cartesian component of the total momentum that
        the dynamics conserves (see :func:`degrees_of_freedom`).
    temperature : float
        ``kT = (sum m v^2 - P_c^2 / M) / f`` averaged over the block boundaries, where
        ``P_c`` is the conserved part of the total momentum and ``M`` the total mass
        (constant in an elastic run, so this is the window's temperature).
    temperature_error : float
        Standard error of the blocks' temperatures (each the mean of its two
        boundaries): rounding only in an elastic run, the fluctuation of the
        temperature with a thermostat, heated walls or inelastic collisions.
    pressure, pressure_error : float
        Virial pressure ``P = (N kT + sum J |r_ij| / (2 t)) / A``: the sum runs over the
        disk-disk collisions of the window, ``J`` is the impulse magnitude and ``|r_ij|``
        the centre distance at contact.  (This is the 2D virial theorem: the
        ``1/(2t)`` is ``1/(d t)`` with ``d = 2`` dimensions.)  In a fully periodic box
        this is the bulk pressure.  In a box or container with walls it is the virial
        pressure of the container, which differs from the force per length on its
        walls by a surface term (see :func:`measure`).
    pressure_xx, pressure_yy : float
        Diagonal of the pressure tensor, ``P_aa A = N kT_a + sum J |r_ij| n_a^2 / t``
        with ``n`` the unit contact normal and ``kT_a`` the kinetic temperature of the
        ``a`` components alone (``(sum m v_a^2 - P_a^2 / M) / (N - c_a)``, ``c_a = 1`` if
        that momentum component is conserved).  Their mean is ``pressure`` (up to the
        split of the kinetic part); they differ in anisotropic systems such as a channel.
    pressure_xy : float
        The off-diagonal of the pressure tensor, ``P_xy A = N kT_xy + sum J |r_ij| n_x
        n_y / t``, ``kT_xy = (sum m v_x v_y - P_x P_y / M) / (N - c)`` (``c = 1`` if
        both momentum components are conserved): 0 in equilibrium, ``-eta`` times the
        shear rate in a sheared fluid.
    pressure_tensor : ndarray, shape (2, 2)
        ``[[pressure_xx, pressure_xy], [pressure_xy, pressure_yy]]`` (a property).
    pressure_tensor_error : ndarray, shape (2, 2)
        Standard errors of its components over the blocks (each block's kinetic part
        the mean of its two boundaries).
    compressibility_factor, compressibility_factor_error : float
        ``Z = P A / (N kT) = 1 + sum J |r_ij| / (2 t N kT)``.
    collision_rate, collision_rate_error : float
        Collisions per disk per unit time, ``2 C / (N_all t)`` (every disk-disk
        collision involves two disks; ``N_all`` counts all disks).
    mean_free_time, mean_free_time_error : float
        ``1 / collision_rate`` (time between disk-disk collisions of one disk).
    mean_speed : float
        Mean of ``|v|`` over the movable disks, averaged over the block boundaries.
    mean_free_path : float
        ``mean_speed * mean_free_time``.
    wall_pressure, wall_pressure_error : float
        Impulse delivered to the box walls (on walled axes) per unit time and per unit
        wall length: a mechanical pressure.  ``nan`` in a fully periodic box.  Wall
        segments are not included (see ``segment_pressure``).
    box_wall_pressures : tuple of 4 float
        The same for each box wall, in the order x=0, x=width, y=0, y=height (``nan``
        on periodic axes).
    segment_force : float
        Sum of the impulse magnitudes delivered to all wall segments, per unit time
        (0.0 without segments).  A total over every direction, not a force vector: see
        ``segment_forces``.
    segment_contacts : ndarray of int, shape (S,)
        Contacts of disks with each wall segment (``sim.walls[k]``) in the window.
    segment_forces, segment_forces_error : ndarray, shape (S, 2)
        Mean force ``(F_x, F_y)`` on each segment: the impulse it received (sides and
        end points, each contact pushing along its normal, away from the disk) per
        unit time.
    segment_pressures, segment_pressures_error : ndarray, shape (S, 2)
        Normal force per unit length on each side of each segment, left then right
        (the left side lies to the left going from ``start`` to ``end``: the inside
        of a counterclockwise ``Wall.polygon``): the normal impulse of the contacts on
        that side per unit time, divided by the segment's length.  Contacts with the
        end points are left out (they push along other directions; they are in
        ``segment_forces``).  0 on a side no disk touched.
    segment_pressure, segment_pressure_error : float
        The mean normal force per unit length over the segment sides that the disks
        reach (those touched since the simulation was created): their normal impulse
        in the window over their total length, per unit time.  The mechanical pressure
        on a container of segments.  ``nan`` if no side was ever touched.
    shear_rate : float
        The shear rate of a sheared box (:class:`edmd2d.physics.Shear`); 0.0 without
        shear.  Under shear the temperatures come from the peculiar velocities
        (relative to the flow), and the kinetic part of the pressure tensor is the
        exact time integral over the window of ``sum m u_a u_b`` (``u`` the peculiar
        velocity) rather than the mean of the block boundaries; ``pressure`` is half
        the tensor's trace.
    viscosity, viscosity_error : float
        Under shear, the shear viscosity ``eta = -pressure_xy / shear_rate`` and its
        error (``nan`` without shear).  In 2D it depends on the system size and on
        the shear rate (the long-time tail of the stress autocorrelation): quote them
        with it.
    rotational_temperature, rotational_temperature_error : float
        Rough disks (:class:`edmd2d.physics.Rough`): the rotational temperature
        ``kT_rot = sum I w^2 / N`` (:func:`rotational_temperature`) averaged over the
        block boundaries, as ``temperature``; ``nan`` for smooth disks.
    """

    duration: float
    collisions: int
    wall_collisions: int
    blocks: int
    n: int
    area: float
    degrees_of_freedom: int
    temperature: float
    pressure: float
    pressure_error: float
    pressure_xx: float
    pressure_yy: float
    compressibility_factor: float
    compressibility_factor_error: float
    collision_rate: float
    collision_rate_error: float
    mean_free_time: float
    mean_free_time_error: float
    mean_speed: float
    mean_free_path: float
    wall_pressure: float
    wall_pressure_error: float
    box_wall_pressures: tuple
    segment_force: float
    area_source: str
    segment_contacts: np.ndarray
    segment_forces: np.ndarray
    segment_forces_error: np.ndarray
    segment_pressures: np.ndarray
    segment_pressures_error: np.ndarray
    segment_pressure: float
    segment_pressure_error: float
    temperature_error: float = math.nan
    pressure_xy: float = math.nan
    pressure_tensor_error: np.ndarray = field(
        default_factory=lambda: _frozen(np.full((2, 2), math.nan)))
    shear_rate: float = 0.0
    viscosity: float = math.nan
    viscosity_error: float = math.nan
    rotational_temperature: float = math.nan
    rotational_temperature_error: float = math.nan

    @property
    def pressure_tensor(self) -> np.ndarray:
        """``[[pressure_xx, pressure_xy], [pressure_xy, pressure_yy]]``."""
        return _frozen(np.array([[self.pressure_xx, self.pressure_xy],
                                 [self.pressure_xy, self.pressure_yy]]))

    def summary(self) -> str:
        """A few lines with the main values and their error bars.

        Box walls are listed when they were touched (or when no segment was); wall
        segments by their mean pressure and, for up to 8 touched sides, one line each
        with the segment's mean force (``walls[k]`` is ``sim.walls[k]``).

        Returns
        -------
        str
            The lines, joined by newlines, ready to print.
        """

        def pm(value, err):
            return f"{value:.6g} +- {err:.2g}" if np.isfinite(err) else f"{value:.6g}"

        segment_hits = int(self.segment_contacts.sum())
        box_hits = self.wall_collisions - segment_hits
        head = (f"window {self.duration:g} ({self.blocks} blocks), N={self.n}, "
                f"{self.collisions} collisions")
        if segment_hits:
            head += (f", {box_hits} box wall and" if box_hits else ",")
            head += f" {segment_hits} segment contacts"
        elif box_hits:
            head += f", {box_hits} wall contacts"
        lines = [head, f"temperature            {self.temperature:.6g}"]
        if np.isfinite(self.rotational_temperature):
            lines.append(f"rotational temperature "
                         f"{pm(self.rotational_temperature, self.rotational_temperature_error)}"
                         f" (ratio {self.rotational_temperature / self.temperature:.4g})")
        if self.area_source != "box":
            where = ("inside closed polygons of wall segments"
                     if self.area_source == "walls" else "given")
            lines.append(f"area                   {self.area:.6g} ({where})")
        lines += [
            f"pressure               {pm(self.pressure, self.pressure_error)}",
            f"  tensor xx, yy, xy    "
            f"{pm(self.pressure_xx, self.pressure_tensor_error[0, 0])}, "
            f"{pm(self.pressure_yy, self.pressure_tensor_error[1, 1])}, "
            f"{pm(self.pressure_xy, self.pressure_tensor_error[0, 1])}",
            f"compressibility Z      "
            f"{pm(self.compressibility_factor, self.compressibility_factor_error)}",
            f"collision rate / disk  {pm(self.collision_rate, self.collision_rate_error)}",
            f"mean free time         {pm(self.mean_free_time, self.mean_free_time_error)}",
            f"mean free path         {self.mean_free_path:.6g}",
        ]
        if self.shear_rate != 0.0:
            lines.append(f"shear rate             {self.shear_rate:.6g}")
            lines.append(f"viscosity              {pm(self.viscosity, self.viscosity_error)}")
        if np.isfinite(self.wall_pressure) and (box_hits > 0 or segment_hits == 0):
            label = "box wall pressure" if segment_hits else "wall pressure"
            lines.append(f"{label:<23}{pm(self.wall_pressure, self.wall_pressure_error)}")
        if np.isfinite(self.segment_pressure):
            touched = np.argwhere(self.segment_pressures > 0.0)
            lines.append(f"segment pressure       "
                         f"{pm(self.segment_pressure, self.segment_pressure_error)} "
                         f"(force per length; {len(touched)} sides touched)")
            for k, side in touched[:_SUMMARY_SIDES]:
                fx, fy = self.segment_forces[k]
                lines.append(
                    f"  walls[{k}] {('left', 'right')[side]:<5}       "
                    f"{pm(self.segment_pressures[k, side], self.segment_pressures_error[k, side])}"
                    f"   force ({fx:.4g}, {fy:.4g})")
            if len(touched) > _SUMMARY_SIDES:
                lines.append(f"  ... {len(touched) - _SUMMARY_SIDES} more sides in "
                             "segment_pressures and segment_forces")
        elif segment_hits:
            lines.append(f"segment force          {self.segment_force:.6g} "
                         f"(end points only, see segment_forces)")
        return "\n".join(lines)


# Touched segment sides listed one per line by Measurement.summary.
_SUMMARY_SIDES = 8


def _stderr(values: np.ndarray):
    """Standard error of the mean of independent block values (nan for fewer than 2):
    along the first axis, a float for 1-D ``values``, else an array."""
    values = np.asarray(values, dtype=float)
    if len(values) < 2:
        return math.nan if values.ndim == 1 else np.full(values.shape[1:], math.nan)
    err = np.std(values, axis=0, ddof=1) / math.sqrt(len(values))
    return float(err) if values.ndim == 1 else err


def _frozen(values: np.ndarray) -> np.ndarray:
    out = np.array(values)
    out.flags.writeable = False
    return out
