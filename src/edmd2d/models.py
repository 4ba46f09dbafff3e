"""Physics models beyond elastic hard disks.

A model changes what a contact does to the disks' velocities.
:class:`edmd2d.Simulation` builds its model from its keywords (``restitution=``,
``wall_restitution=``, ``tc=``); elastic disks need none and run the engine's default
(fastest) path.  A model holds its parameters and any per-disk state it needs (kept in
the engine's internal row order: :meth:`Model.permuted` follows the engine's
re-sorts), and hands the compiled engine its physics families as named tuples
(:meth:`Model.engine_families`), whose functions are in ``_engine/response.py``.

Restitution and the TC model
----------------------------
In a collision the normal relative velocity ``vn`` of the two disks (or of a disk and a
wall) is reversed and multiplied by the coefficient of normal restitution ``e``
(``0 < e <= 1``); the tangential velocity is unchanged (smooth disks).  A pair of disks
loses ``(1 - e^2) mu vn^2 / 2`` of kinetic energy, ``mu`` the reduced mass.

With ``e < 1`` a group of disks can undergo *inelastic collapse*: infinitely many
collisions in a finite time (for example a row of disks squeezed together), which no
event-driven simulation can process.  The TC model of Luding and McNamara (Granular
Matter 1, 113 (1998)) prevents it: a collision is elastic when one of the (movable)
disks involved already collided less than ``tc`` ago.  ``tc`` is read as the duration
of a contact; it should be much shorter than the mean free time, so that the gas's
dissipation is unaffected, yet long enough to end every collapse: the default is
``1e-5`` of the time a disk of mean diameter needs to cross that diameter at the
initial root-mean-square speed.  Immovable disks act as walls for this rule.

With ``tc = 0`` a collapse is not prevented: the engine then stops the run with a
``RuntimeError`` naming the disks involved once a disk has collided
``STALL_COLLISIONS`` times in a row at the same time to within rounding (the state
stays as it was before that event; a larger ``tc`` lets the run go on).

Examples
--------
Two disks meet head-on at unit speeds with ``e = 0.5``: each leaves at half its speed,
and of the kinetic energy 1, 0.75 is dissipated.

>>> import edmd2d as ed
>>> sim = ed.Simulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]], 1.0,
...                     box=ed.Box(10.0, 10.0, periodic=False), restitution=0.5)
>>> sim.advance(collisions=1).velocities.tolist()
[[-0.5, 0.0], [0.5, 0.0]]
>>> sim.dissipated_energy()
0.75
"""

from __future__ import annotations

import copy
import math

import numpy as np
from numpy.typing import ArrayLike

from ._engine import layout as _layout
from ._engine import response as _response

__all__ = ["Model", "STALL_COLLISIONS", "default_tc"]

#: Collisions of one disk in a row at the same time (to within rounding) after which a
#: run without the TC model (``tc = 0``) stops with a ``RuntimeError``: an inelastic
#: collapse.
STALL_COLLISIONS = _response.STALL_COLLISIONS
# Largest species id: a table of coefficients has one row per species up to the largest.
MAX_SPECIES = 1023


def default_tc(radii: np.ndarray, velocities: np.ndarray, movable: np.ndarray) -> float:
    """The default TC-model duration: ``1e-5 * d / v_rms`` (``d`` the mean diameter
    and ``v_rms`` the root-mean-square speed of the ``movable`` disks; ``1e-5 * d``
    time units if they all rest, or over all disks if none can move).

    Parameters
    ----------
    radii : ndarray, shape (N,)
        The radii.
    velocities : ndarray, shape (N, 2)
        The velocities.
    movable : ndarray of bool, shape (N,)
        Which disks can move (finite mass).

    Returns
    -------
    float
        The duration ``tc``, > 0.
    """
    if movable.any():
        radii, velocities = radii[movable], velocities[movable]
    d = 2.0 * float(np.mean(radii))
    v = math.sqrt(float(np.mean(np.einsum("ij,ij->i", velocities, velocities))))
    return 1e-5 * d / v if v > 0.0 else 1e-5 * d


class Model:
    """What contacts and the thermostat do, for the compiled engine: restitution and
    the TC model, heated walls, and an Andersen thermostat.

    Parameters
    ----------
    table : array_like, shape (S, S)
        Coefficient for each pair of species, symmetric, each in ``(0, 1]``.
    wall : float
        Coefficient against box walls and wall segments that are not heated, in
        ``(0, 1]``.
    tc : float
        TC-model duration, ``>= 0`` (see the module notes).
    species : array_like of int, shape (N,)
        Each disk's species, in the engine's internal row order.
    wall_temperatures : array_like, shape (4 + n_segments,)
        ``kT`` of each box wall (x=0, x=width, y=0, y=height) and each wall segment;
        0 for a wall that is not heated.
    thermostat : (float, float), optional
        ``(kT, rate)`` of the Andersen thermostat: each movable disk's velocity is
        redrawn from the Maxwell-Boltzmann distribution at ``kT`` at the events of a
        Poisson process of ``rate`` per disk.  Default: none.
    rng : numpy.random.Generator, optional
        The source of the random numbers (heated walls, thermostat).
    time : float
        The clock, from which the thermostat's first redraw is drawn.

    Attributes
    ----------
    t_last : ndarray, shape (N,)
        Time of each disk's last collision (``-inf`` before its first).
    streak : ndarray, shape (N,)
        Each disk's collisions in a row at the same time to within rounding.
    hold : float
        The ``tc`` with which walls hold disks at rest under gravity: ``tc`` if some
        coefficient is below 1, else 0 (elastic disks never come to rest).
    """

    # Uniform random numbers handed to the engine at a time; it returns for more
    # when fewer than layout's per-event need are left.
    BUFFER = 1 << 14

    def __init__(self, table: np.ndarray, wall: float, tc: float, species: np.ndarray,
                 wall_temperatures: ArrayLike, thermostat: tuple[float, float] | None = None,
                 rng: np.random.Generator | None = None, time: float = 0.0) -> None:
        self.table = np.ascontiguousarray(table, np.float64)
        self.wall = float(wall)
        self.tc = float(tc)
        self.species = np.ascontiguousarray(species, np.int32)
        n = len(self.species)
        self.t_last = np.full(n, -np.inf)
        self.streak = np.zeros(n, np.int64)
        inelastic = bool((self.table < 1.0).any()) or self.wall < 1.0
        self.hold = self.tc if inelastic else 0.0
        # (One entry per box wall and segment: the engine reads it at every contact.)
        self.wall_kt = np.ascontiguousarray(wall_temperatures, np.float64)
        kt, rate = (0.0, 0.0) if thermostat is None else thermostat
        self.rng = np.random.default_rng() if rng is None else rng
        # (kT, total rate over all rows, time of the next redraw)
        self.thermo = np.array([kt, rate * n, math.inf])
        random = rate > 0.0 or bool((self.wall_kt > 0.0).any())
        self.buffer = np.zeros(self.BUFFER if random else 0)
        self.cursor = np.array([len(self.buffer)], np.int64)
        if rate > 0.0:
            # (Every draw comes from the one stream of uniforms u: the first waiting
            # time is -ln(1 - u) / rate, as the engine draws the next ones.)
            self.thermo[2] = time - math.log(1.0 - self.rng.random()) / float(self.thermo[1])
        self.refill()

    def refill(self) -> None:
        """Top the buffer of uniform random numbers up from the model's generator
        ``rng`` (the ones left move to its front, so the draws follow one stream
        whatever the refills)."""
        left = self.buffer[self.cursor[0]:].copy()
        self.buffer[:len(left)] = left
        self.buffer[len(left):] = self.rng.random(len(self.buffer) - len(left))
        self.cursor[0] = 0

    @property
    def thermostat(self) -> tuple[float, float] | None:
        """``(kT, rate per disk)`` of the Andersen thermostat, or ``None``."""
        if self.thermo[1] == 0.0:
            return None
        return float(self.thermo[0]), float(self.thermo[1]) / len(self.species)

    def engine_families(self) -> _layout.ModelFamilies:
        """The physics families the compiled engine reads (see ``_engine/response.py``),
        each ``None`` when the model does not use it.

        Returns
        -------
        edmd2d._engine.layout.ModelFamilies
            ``(contact, heated, thermostat, uniforms)``: restitution and the TC model
            (always present), the heated walls (if any wall is heated), the thermostat
            (if it redraws) and the random numbers (if either of those draws).  They
            hold the model's own arrays, not copies, so that the engine's updates of the
            per-disk state, the clock of the next redraw and the cursor are the model's.
        """
        contact = _layout.Contact(self.table, self.species, float(self.wall), float(self.tc),
                                  self.t_last, self.streak, float(self.hold))
        heated = (_layout.HeatedWalls(self.wall_kt) if bool((self.wall_kt > 0.0).any())
                  else None)
        thermostat = (_layout.Thermostat(float(self.thermo[0]), float(self.thermo[1]),
                                         self.thermo[2:]) if self.thermo[1] > 0.0 else None)
        uniforms = _layout.Uniforms(self.buffer, self.cursor) if len(self.buffer) else None
        return _layout.ModelFamilies(contact, heated, thermostat, uniforms)

    def permuted(self, perm: np.ndarray) -> Model:
        """A copy that follows a re-sort of the engine's rows; ``self`` is left as it
        was.

        Parameters
        ----------
        perm : ndarray of int, shape (N,)
            The re-sort: new row ``k`` is old row ``perm[k]``.

        Returns
        -------
        Model
            The copy, its per-disk arrays (species, last collision times, streaks)
            in the new order.
        """
        new = copy.copy(self)
        new.species = np.ascontiguousarray(self.species[perm])
        new.t_last = np.ascontiguousarray(self.t_last[perm])
        new.streak = np.ascontiguousarray(self.streak[perm])
        return new

    def __setstate__(self, state: dict) -> None:
        """For pickles and checkpoints: the fields as :func:`vars` gave them."""
        vars(self).update(state)

    def __repr__(self) -> str:
        coeff = (f"{self.table[0, 0]:g}" if self.table.size == 1
                 else f"table of {self.table.shape[0]} species")
        text = f"Model(e={coeff}, wall={self.wall:g}, tc={self.tc:g}"
        if (self.wall_kt > 0.0).any():
            text += f", heated walls={np.flatnonzero(self.wall_kt).tolist()}"
        if self.thermostat is not None:
            text += f", thermostat=(kT={self.thermostat[0]:g}, rate={self.thermostat[1]:g})"
        return text + ")"


def as_species(value, n: int) -> np.ndarray:
    """Validate ``species``: ``None`` (all 0) or ``n`` integers ``>= 0``."""
    if value is None:
        return np.zeros(n, np.int32)
    arr = np.asarray(value)
    if arr.shape != (n,):
        raise ValueError(f"species must have shape ({n},) (one per disk), got {arr.shape}")
    if arr.dtype.kind not in "iu":
        if arr.dtype.kind != "f" or not np.all(np.isfinite(arr)) or np.any(arr != np.round(arr)):
            raise TypeError(f"species must be integers, got dtype {arr.dtype}")
    bad = (arr < 0) | (arr > MAX_SPECIES)
    if bad.any():
        k = int(np.argmax(bad))
        raise ValueError(f"species must lie in 0..{MAX_SPECIES}; disk {k} has {arr[k]}")
    return arr.astype(np.int32)
