"""Profiles along an axis: density, packing fraction, flow velocity and granular
temperature in slabs, with error bars (:class:`Profile`, :func:`profiles`); and the
height and packing fraction of a bed of disks at rest (:func:`bed`).

Public through :mod:`edmd2d.measurements` (and the operation through
:mod:`edmd2d.operations`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from . import progress as _progress
from ._measurement import _frozen, _stderr
from ._operations import Every, Operation, Trigger, run
from ._validate import as_count, as_float_array, as_positive_float
from .geometry import Box

if TYPE_CHECKING:  # (for the annotations only: simulation imports this module)
    from .simulation import Simulation

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
        Disk visits over all samples.
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
    bar, owned = _progress.bar(progress, total=duration, unit="time", desc="profiles")
    try:
        run(sim, until=sim.time + duration, operations=[op],
            progress=bar if bar is not None else False)
    finally:
        if owned:
            bar.close()
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
    part of it.

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
