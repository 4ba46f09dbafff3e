"""The physics families beyond elastic hard disks, each checked in one place.

A family is a small class that validates its keywords once and holds the result:
:class:`Restitution` (with the TC model), :class:`Gravity`, :class:`HeatedWalls`,
:class:`Thermostat` and :class:`Growth`.  Each declares the keywords it takes
(:class:`Keyword`: name, default, the kind of value a configuration file gives, one line
of description) and is registered (:func:`register`, :data:`FAMILIES`).
:class:`~edmd2d.Simulation` takes these keywords and builds each family from them; the
``[model]`` table of a run configuration (:mod:`edmd2d.config`) is derived from the
same declarations.  A family registered later (see :class:`Family`) is kept by the
simulation in :attr:`Simulation.families <edmd2d.Simulation.families>`, stored in its
checkpoints and logged in its GSD frames, with no other file changed; the families
above came before the registry, and :class:`~edmd2d.Simulation` keeps them in
attributes of its own (``built_in``).

An error about a keyword's value carries that keyword (a family's check raises it
inside ``with about(keyword):``, :func:`about`), so that the configuration loader points
at the right key of a file without reading the message.

Examples
--------
>>> from edmd2d import physics
>>> list(physics.FAMILIES)  # doctest: +NORMALIZE_WHITESPACE
['restitution', 'gravity', 'heated_walls', 'thermostat', 'growth', 'resting', 'shear',
 'rough', 'moving_walls']
>>> physics.Thermostat.check(thermostat=(1.0, 0.5))
Thermostat(temperature=1.0, rate=0.5)
>>> physics.Gravity.check(gravity=(0.0, 0.0)) is None   # (no gravity: straight flights)
True
>>> physics.KEYWORDS["tc"].doc
"the TC model's duration (default 1e-5 of a diameter's crossing time)"
"""

from __future__ import annotations

import dataclasses
import difflib
import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from . import models as _models
from ._engine import layout as _layout
from ._validate import about, as_count, as_float_array, per_disk
from .geometry import BOX_WALL_EQUATIONS, BOX_WALLS, Box, Oscillation, Translation

__all__ = ["Keyword", "System", "Family", "FAMILIES", "KEYWORDS", "register", "unregister",
           "owner", "about",
           "Restitution", "Gravity", "HeatedWalls", "Thermostat", "Growth", "Resting",
           "Shear", "Rough", "MovingWalls"]


@dataclass(frozen=True)
class Keyword:
    """One keyword of a physics family, as :class:`~edmd2d.Simulation` and a
    configuration file take it.

    Attributes
    ----------
    name : str
        The keyword (and the key of the ``[model]`` table).
    default : object
        Its value when not given.
    kind : str
        What a configuration file gives: ``"coefficient"`` (a number in ``(0, 1]``),
        ``"coefficients"`` (one, or a square table per pair of species),
        ``"duration"`` (a number ``>= 0``), ``"vector"`` (two numbers),
        ``"switch"`` (true or false), ``"length"`` (a number ``> 0``),
        ``"nonnegative"`` (a number ``>= 0``), ``"rate"`` (a number of either sign) or
        ``"walls"``
        (a table ``{wall = kT}``); ``""`` for a keyword that configuration files do not
        take.
    doc : str
        One line on what it sets.
    """

    name: str
    default: object
    kind: str
    doc: str


@dataclass(frozen=True, eq=False)
class System:
    """What a family's :meth:`Family.check` may need to know of the system it joins.

    Attributes
    ----------
    box : Box
    n_segments : int
        The number of wall segments.
    radii, masses : ndarray, shape (N,)
    velocities : ndarray, shape (N, 2)
    species : ndarray of int32, shape (N,)
    time : float
    gravity : ndarray, shape (2,), or None
        The acceleration of gravity (``None``: none), for the families checked after
        the built-in ones (the registered families).
    inelastic : bool
        Whether some coefficient of restitution is below 1 (as ``gravity``).
    walls : tuple of Wall
        The wall segments.
    """

    box: Box
    n_segments: int
    radii: np.ndarray
    velocities: np.ndarray
    masses: np.ndarray
    species: np.ndarray
    time: float
    gravity: np.ndarray | None = None
    inelastic: bool = False
    walls: tuple = ()


class Family:
    """A physics family: its name, its keywords, and the check that builds it from them.

    A subclass sets :attr:`name` and :attr:`keywords` and implements :meth:`check`;
    :func:`register` adds it to :data:`FAMILIES`.  A registered family's keywords are
    then keywords of :class:`~edmd2d.Simulation` and keys of a configuration's
    ``[model]`` table; the simulation keeps the family (:attr:`Simulation.families
    <edmd2d.Simulation.families>`), its checkpoints store it (:meth:`state`,
    :meth:`from_state`) and its GSD frames log it (:meth:`log`,
    :meth:`keywords_from_log`).  The defaults of those four serve a family that is a
    dataclass of numbers and arrays.
    """

    #: The family's name.
    name: ClassVar[str] = ""
    #: The keywords it takes.
    keywords: ClassVar[tuple[Keyword, ...]] = ()
    #: Whether :class:`~edmd2d.Simulation` takes the family's keywords by name and keeps
    #: it in attributes of its own (the families that came before the registry);
    #: otherwise it keeps the family in :attr:`Simulation.families
    #: <edmd2d.Simulation.families>`.
    built_in: ClassVar[bool] = False
    #: Whether the family is checked even when none of its keywords is given (a
    #: family on by default where the system calls for it).
    always: ClassVar[bool] = False

    @classmethod
    def check(cls, system: System | None = None, **values: Any) -> Family | None:
        """The family built from its keywords' values (and what a family needs to know
        of the system, where it needs it), or ``None`` where they leave hard disks as
        they are.

        Parameters
        ----------
        system : System, optional
            What the family may need to know of the system (a family that needs
            nothing of it is checked without).
        **values
            The family's keywords that were given.

        Returns
        -------
        Family or None

        Raises
        ------
        TypeError, ValueError
            For a value the family refuses, about the keyword that gave it.
        """
        raise NotImplementedError

    def state(self) -> dict:
        """What a checkpoint stores of the family: its fields, numbers and arrays.

        Returns
        -------
        dict
        """
        if not dataclasses.is_dataclass(self):
            raise TypeError(f"{type(self).__name__} is not a dataclass: it must define state()")
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    @classmethod
    def from_state(cls, state: dict) -> Family:
        """The family a checkpoint stored (:meth:`state`).

        Parameters
        ----------
        state : dict

        Returns
        -------
        Family
        """
        return cls(**state)

    def log(self) -> dict:
        """What a GSD frame logs of the family (under ``edmd2d/<name>/<key>``): its
        keywords' values as float64 arrays, by default each keyword's field.

        Returns
        -------
        dict of str to ndarray
        """
        return {kw.name: np.asarray(getattr(self, kw.name), np.float64)
                for kw in self.keywords}

    @classmethod
    def keywords_from_log(cls, log: dict) -> dict:
        """The keywords that rebuild the family from what a GSD frame logged
        (:meth:`log`).

        Parameters
        ----------
        log : dict of str to ndarray
            The family's entries, by key.

        Returns
        -------
        dict
        """
        return {key: (float(value[0]) if value.size == 1 else value)
                for key, value in log.items()}


# --------------------------------------------------------------------------- families
@dataclass(frozen=True, eq=False)
class Restitution(Family):
    """Normal restitution between disks and against walls, and the TC model that keeps
    an inelastic collapse from stopping a run (see :mod:`edmd2d.models`).

    Attributes
    ----------
    table : ndarray, shape (S, S)
        The coefficient of each pair of species (``1 x 1`` for one coefficient).
    wall : float
        The coefficient against walls that are not heated.
    tc : float
        The TC model's duration.
    species : ndarray of int32, shape (N,)
        The species each disk reads its coefficients with (all 0 for one coefficient).
    """

    name: ClassVar[str] = "restitution"
    built_in: ClassVar[bool] = True
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("restitution", 1.0, "coefficients",
                "the coefficient of normal restitution, or a table per pair of species"),
        Keyword("wall_restitution", 1.0, "coefficient",
                "the coefficient against box walls and wall segments"),
        Keyword("tc", None, "duration",
                "the TC model's duration (default 1e-5 of a diameter's crossing time)"),
    )

    table: np.ndarray
    wall: float
    tc: float
    species: np.ndarray

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *, restitution: ArrayLike = 1.0,
            wall_restitution: float = 1.0, tc: float | None = None) -> Restitution:
        """Check the coefficients for the species of the ``system``'s disks and take
        the default ``tc`` from their radii, velocities and masses.

        Parameters
        ----------
        system : System
            The disks' species, radii, velocities and masses.
        restitution : float or array_like, shape (S, S), default 1.0
        wall_restitution : float, default 1.0
        tc : float, optional

        Returns
        -------
        Restitution
            Elastic (all coefficients 1) included: :attr:`elastic` tells.
        """
        assert system is not None  # (checked with the system, which it needs)
        species = system.species
        scalar = np.ndim(restitution) == 0
        with about("restitution"):
            # (One coefficient for every pair: a 1x1 table that every disk reads as
            # species 0.)
            table = _restitution_table(restitution,
                                              1 if scalar else int(species.max()) + 1)
        with about("wall_restitution"):
            wall = _wall_coefficient(wall_restitution)
        with about("tc"):
            tc = (_models.default_tc(system.radii, system.velocities,
                                     np.isfinite(system.masses)) if tc is None
                  else _tc_value(tc))
        return cls(table, wall, tc, np.zeros_like(species) if scalar else species)

    @property
    def elastic(self) -> bool:
        """Whether every coefficient is 1."""
        return bool((self.table == 1.0).all()) and self.wall == 1.0


def _restitution_table(value, n_species: int) -> np.ndarray:
    """Validate ``restitution``: a scalar or an ``(S, S)`` symmetric table (``S`` at
    least ``n_species``), each entry in ``(0, 1]``; returns the table."""
    arr = np.asarray(value, dtype=object)
    if arr.ndim == 0:  # (as_float_array names the argument for any bad scalar)
        e = float(as_float_array("restitution", value, ()))
        if not 0.0 < e <= 1.0:
            raise ValueError(f"restitution must lie in (0, 1], got {e}")
        return np.full((n_species, n_species), e)
    table = as_float_array("restitution", value, (None, None)) if arr.ndim == 2 else None
    if table is None or table.shape[0] != table.shape[1]:
        raise ValueError(f"restitution must be a scalar or a square (S, S) table, got "
                         f"shape {arr.shape}")
    if table.shape[0] < n_species:
        raise ValueError(f"restitution is a table for {table.shape[0]} species, but the "
                         f"disks have {n_species} species (0 to {n_species - 1})")
    table = as_float_array("restitution", table, table.shape)
    bad = ~((table > 0.0) & (table <= 1.0))
    if bad.any():
        a, b = np.argwhere(bad)[0]
        raise ValueError(f"restitution[{a}, {b}] = {table[a, b]} is outside (0, 1]")
    if not np.array_equal(table, table.T):
        a, b = np.argwhere(table != table.T)[0]
        raise ValueError(
            f"restitution must be symmetric: restitution[{a}, {b}] = {table[a, b]} but "
            f"restitution[{b}, {a}] = {table[b, a]}"
        )
    return table


def _wall_coefficient(value) -> float:
    """Validate ``wall_restitution``: a scalar in ``(0, 1]``."""
    e = float(as_float_array("wall_restitution", value, ()))
    if not 0.0 < e <= 1.0:
        raise ValueError(f"wall_restitution must lie in (0, 1], got {e}")
    return e


def _tc_value(value) -> float:
    """Validate ``tc``: a finite scalar ``>= 0``."""
    tc = float(as_float_array("tc", value, ()))
    if not tc >= 0.0:
        raise ValueError(f"tc must be >= 0, got {tc}")
    return tc


@dataclass(frozen=True, eq=False)
class Gravity(Family):
    """A uniform acceleration: disks fly on parabolas between events.

    Attributes
    ----------
    g : ndarray, shape (2,)
        The acceleration, not zero.
    """

    name: ClassVar[str] = "gravity"
    built_in: ClassVar[bool] = True
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("gravity", None, "vector", "the acceleration (gx, gy) of every disk"),
    )

    g: np.ndarray

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *,
            gravity: ArrayLike | None = None) -> Gravity | None:
        """``None`` (or zero: the straight-line engine, the same flights, faster) or a
        finite 2-vector.

        Parameters
        ----------
        system : System, optional
            Not needed.
        gravity : array_like, shape (2,), optional

        Returns
        -------
        Gravity or None
        """
        if gravity is None:
            return None
        with about("gravity"):
            g = np.array(as_float_array("gravity", gravity, (2,)))
        return cls(g) if (g != 0.0).any() else None


_BOX_WALL_ALIASES = {**{name: k for k, name in enumerate(BOX_WALLS)},
                     **{name: k for k, name in enumerate(BOX_WALL_EQUATIONS)}}


@dataclass(frozen=True, eq=False)
class HeatedWalls(Family):
    """Walls that send each disk that hits them back with a velocity drawn afresh at
    their temperature.

    Attributes
    ----------
    kt : ndarray, shape (4 + S,)
        ``kT`` of each box wall (in the order of :data:`edmd2d.geometry.BOX_WALLS`) and
        each wall segment; 0 where not heated.
    """

    name: ClassVar[str] = "heated_walls"
    built_in: ClassVar[bool] = True
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("wall_temperatures", None, "walls",
                "kT of heated walls: box walls by name, segments by index"),
    )

    kt: np.ndarray

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *,
            wall_temperatures: dict | None = None) -> HeatedWalls:
        """Check ``{wall: kT}`` for the ``system``'s box and wall segments.

        Parameters
        ----------
        system : System
            The box and the number of wall segments.
        wall_temperatures : dict, optional

        Returns
        -------
        HeatedWalls
            With no wall heated when ``wall_temperatures`` is ``None``.
        """
        assert system is not None  # (checked with the system, which it needs)
        with about("wall_temperatures"):
            return cls(_wall_temperatures(wall_temperatures, system.box, system.n_segments))

    @property
    def active(self) -> bool:
        """Whether a wall is heated."""
        return bool((self.kt > 0.0).any())


def _wall_temperatures(value, box: Box, n_segments: int) -> np.ndarray:
    if value is None:
        return np.zeros(4 + n_segments)
    if not isinstance(value, dict):
        raise TypeError("wall_temperatures must be a dict {wall: kT} (wall: 'left', "
                        f"'right', 'bottom', 'top' or a segment index), got {value!r}")
    kt = np.zeros(4 + n_segments)
    for key, temperature in value.items():
        label = f"wall_temperatures[{key!r}]"
        if isinstance(key, str):
            if key not in _BOX_WALL_ALIASES:
                raise ValueError(f"{label}: no box wall is called {key!r}; use one of "
                                 f"{sorted(_BOX_WALL_ALIASES)}")
            k = _BOX_WALL_ALIASES[key]
            if box.periodic[k // 2]:
                raise ValueError(f"{label}: the {'xy'[k // 2]} axis of the box is "
                                 "periodic, so it has no wall to heat")
        elif isinstance(key, (int, np.integer)) and not isinstance(key, bool):
            if not 0 <= key < n_segments:
                raise ValueError(f"{label}: there are {n_segments} wall segments "
                                 f"(indices 0 to {n_segments - 1})")
            k = 4 + int(key)
        else:
            raise TypeError(f"{label}: a wall is a box wall's name or a segment index, "
                            f"got {type(key).__name__}")
        t = float(as_float_array(label, temperature, ()))
        if not t > 0.0:
            raise ValueError(f"{label} must be a temperature kT > 0, got {t}")
        if kt[k] > 0.0:
            raise ValueError(f"{label}: that wall was given a temperature already "
                             "(under another of its names)")
        kt[k] = t
    return kt


@dataclass(frozen=True)
class Thermostat(Family):
    """An Andersen thermostat: a random disk's velocity redrawn at the events of a
    Poisson process.

    Attributes
    ----------
    temperature : float
        ``kT`` of the redrawn velocities, > 0.
    rate : float
        Redraws per disk per unit time, > 0.
    """

    name: ClassVar[str] = "thermostat"
    built_in: ClassVar[bool] = True
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("thermostat", None, "vector",
                "(kT, rate): redraws of a disk's velocity at kT, rate per disk"),
    )

    temperature: float
    rate: float

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *,
            thermostat: tuple[float, float] | None = None) -> Thermostat | None:
        """``None`` (also for a zero rate) or ``(kT > 0, rate >= 0)``.

        Parameters
        ----------
        system : System, optional
            Not needed.
        thermostat : (float, float), optional

        Returns
        -------
        Thermostat or None
        """
        if thermostat is None:
            return None
        with about("thermostat"):
            arr = as_float_array("thermostat", thermostat, (2,))
            kt, rate = float(arr[0]), float(arr[1])
            if not kt > 0.0:
                raise ValueError(f"thermostat temperature kT must be > 0, got {kt}")
            if not rate >= 0.0:
                raise ValueError(f"thermostat rate must be >= 0, got {rate}")
        return None if rate == 0.0 else cls(kt, rate)


@dataclass(frozen=True)
class Growth(Family):
    """Radii that grow linearly in time (compression, :mod:`edmd2d.compress`), for
    elastic disks in straight flight.

    Attributes
    ----------
    rate : float
        Growth per unit time of each radius, relative to its value at the start, > 0.
    """

    name: ClassVar[str] = "growth"
    built_in: ClassVar[bool] = True
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("growth", None, "", "the rate at which every radius grows"),
    )

    rate: float

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *,
            growth: float | None = None) -> Growth | None:
        """``None`` (fixed radii, also for 0) or a rate > 0.

        Parameters
        ----------
        system : System, optional
            Not needed.
        growth : float, optional

        Returns
        -------
        Growth or None
        """
        if growth is None:
            return None
        with about("growth"):
            value = float(as_float_array("growth", growth, ()))
            if value < 0.0:
                raise ValueError(f"growth must be >= 0 (a rate per unit time), got {value}")
        return cls(value) if value > 0.0 else None

    def check_combination(self, model: _models.Model | None,
                          gravity: np.ndarray | None) -> None:
        """Refuse growth with a ``model`` (restitution below 1, heated walls, a
        thermostat) or with ``gravity``: it is for elastic disks in straight flight.

        Parameters
        ----------
        model : edmd2d.models.Model or None
        gravity : ndarray or None

        Raises
        ------
        ValueError
        """
        with about("growth"):
            if gravity is not None:
                raise ValueError("growth does not combine with gravity: growing disks fly "
                                 "on straight lines")
            if model is not None:
                raise ValueError("growth works with elastic disks between reflecting walls: "
                                 "not with restitution below 1, heated walls or a thermostat")


#: The registered families by name, in the order :class:`~edmd2d.Simulation` builds
#: them (see :func:`register`).
FAMILIES: dict[str, type[Family]] = {}
#: Every registered family's keywords by name.
KEYWORDS: dict[str, Keyword] = {}
#: The family each keyword belongs to.
_OWNER: dict[str, type[Family]] = {}
# (Keywords of Simulation that are no family's: a family cannot take them.)
_RESERVED = ("positions", "velocities", "radii", "masses", "box", "walls", "open_walls", "time",
             "cell_size", "species", "seed")


def register(family: type[Family]) -> type[Family]:
    """Add ``family`` to the registry (usable as a class decorator).

    Its keywords become keywords of :class:`~edmd2d.Simulation` and keys of a
    configuration's ``[model]`` table, and the simulation keeps, checkpoints and logs
    it (see :class:`Family`).

    Parameters
    ----------
    family : type
        A subclass of :class:`Family` with a new name and keywords no other family takes.

    Returns
    -------
    type
        ``family``.

    Raises
    ------
    TypeError
        If ``family`` is not a subclass of :class:`Family`.
    ValueError
        If its name or one of its keywords is taken.
    """
    if not (isinstance(family, type) and issubclass(family, Family)):
        raise TypeError(f"register() needs a subclass of edmd2d.physics.Family, got "
                        f"{family!r}")
    if not family.name or family.name in FAMILIES:
        raise ValueError(f"a physics family needs a name of its own, got {family.name!r}")
    for kw in family.keywords:
        if kw.name in KEYWORDS or kw.name in _RESERVED:
            raise ValueError(f"the keyword {kw.name!r} of the family {family.name!r} is "
                             "taken")
    FAMILIES[family.name] = family
    for kw in family.keywords:
        KEYWORDS[kw.name] = kw
        _OWNER[kw.name] = family
    return family


def owner(keyword: str) -> type[Family]:
    """The registered family that takes ``keyword``.

    Parameters
    ----------
    keyword : str

    Returns
    -------
    type

    Raises
    ------
    KeyError
        If no registered family takes it.
    """
    return _OWNER[keyword]


def unregister(name: str) -> None:
    """Remove the family ``name`` from the registry (a family registered for a while,
    as in a test).

    Parameters
    ----------
    name : str

    Raises
    ------
    KeyError
        If no family has that name.
    """
    family = FAMILIES.pop(name)
    for kw in family.keywords:
        del KEYWORDS[kw.name], _OWNER[kw.name]


@dataclass(frozen=True, eq=False)
class Resting(Family):
    """Disks that come to rest under gravity: a settled bed stops being simulated.

    After each collision a disk whose speed is at most ``speed`` is put to rest if
    it is held: its supports, the static bodies within ``gap`` of it (disks at
    rest, immovable disks, wall segments and their end points, box walls; not heated
    walls), can hold it without friction (the direction against gravity lies strictly
    inside the cone of their normals, or one of them is a flat wall whose normal points
    against gravity).  Its kinetic energy then counts as dissipated, and it holds no
    event until it wakes: when a flying disk hits it with a normal speed above
    ``wake`` (above ``press``, if its static contacts can take the impact: the impact
    pushes it into the cone of their normals), when a support of its wakes (a cascade
    upwards), when the thermostat redraws its velocity, or when the velocities,
    positions, gravity or walls are set.  A softer impact bounces off it as off a fixed
    body: the bed below it is taken as rigid, and takes the momentum, as a wall does.
    A bounce on a box wall that gravity presses a disk into, slower than ``speed``,
    leaves it sliding along the wall.

    Disks can also hold one another up (an arch: two disks side by side, each leaning
    on a peg outside it), which the test of each disk's static supports cannot see.
    Every ``every`` time units (at its multiples) the slow flying disks are therefore
    examined as groups: the disks no faster than ``speed`` that touch to within
    ``gap`` (each other or static bodies) come to rest together when they are held:
    non-negative contact forces along their contact normals balance every member's
    weight, to within a millionth of it, and no motion that keeps the loaded contacts
    closed lowers the group (an arch of two frictionless disks balances, but swings
    down: it is not held; a crystal free to slide along a frictionless floor is).  Of
    a group not held, the parts that hold themselves once the members that nothing
    balances are left out come to rest.

    On by default under gravity with an inelastic model (a coefficient of restitution
    below 1): the bounces of a disk settling on others would otherwise shrink without
    end (an inelastic collapse).  Elastic disks never come to rest.

    Attributes
    ----------
    height : float
        The criteria's length ``h``: a disk comes to rest when its kinetic energy
        could lift it by at most ``h``, on supports at most ``h`` away.
    speed : float
        ``sqrt(2 |g| h)``: the fastest a disk comes to rest.
    gap : float
        ``h``: the widest gap to a support.
    wake : float
        ``sqrt(2 |g| h)``: the slowest impact that wakes a resting disk.
    press : float
        ``sqrt(2 |g| d)``, ``d`` the smallest diameter: the slowest impact that wakes
        a resting disk whose static contacts can take it (an impact that could lift it
        by its diameter).  Slower ones are the endless small bounces of disks settling
        on a bed; waking the disk they hit, and in cascade all it holds, would set the
        bed in flight again and again.
    soft : float
        ``speed / 10``: impacts with a normal speed below it are elastic (the
        coefficient of restitution of real grains tends to 1 at small impact speeds);
        without it a disk riding on one that slides along the floor would bounce ever
        lower, without end.
    instant : float
        ``1e-6 soft / |g|``: two contacts of a disk this close in time (besides a few
        units of rounding of the clock) come at one instant, for the rules above (a
        disk wedged between two static bodies loses the velocity that drives it into
        them; one pushed into a box wall by a disk bounces off it rather than slide).
    every : float
        ``200 h / speed = 141 sqrt(h / |g|)`` (4.5 ``sqrt(d / |g|)`` at the default
        ``h``, ``d`` the smallest diameter): the interval of the search for groups that
        hold one another up, a few times the time a disk takes to fall its diameter.
    """

    name: ClassVar[str] = "resting"
    always: ClassVar[bool] = True
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("resting", None, "switch",
                "whether slow, held disks come to rest under gravity (default: with an "
                "inelastic model)"),
        Keyword("rest_height", None, "length",
                "the length of the rest criteria (default 1e-3 of the smallest diameter)"),
    )

    height: float
    speed: float
    gap: float
    wake: float
    press: float
    soft: float

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *, resting: bool | None = None,
            rest_height: float | None = None) -> Resting | None:
        """Resting disks where ``resting`` asks for them (``None``: under gravity with
        an inelastic model), with the criteria's length ``rest_height``.

        Parameters
        ----------
        system : System
            Its gravity, whether it is inelastic, and its radii.
        resting : bool, optional
        rest_height : float, optional
            ``> 0``; default ``1e-3`` of the smallest diameter.

        Returns
        -------
        Resting or None

        Raises
        ------
        TypeError
            For a ``resting`` that is not a bool or ``None``.
        ValueError
            For ``resting=True`` without gravity, or a ``rest_height`` that is not a
            finite number ``> 0``.
        """
        assert system is not None  # (checked with the system, which it needs)
        with about("resting"):
            if resting is not None and not isinstance(resting, (bool, np.bool_)):
                raise TypeError(f"resting must be True, False or None (the default), "
                                f"got {resting!r}")
        with about("rest_height"):
            if rest_height is None:
                h = 2e-3 * float(system.radii.min())
            else:
                h = float(as_float_array("rest_height", rest_height, ()))
                if not h > 0.0:
                    raise ValueError(f"rest_height must be > 0 (a length), got {h}")
        if resting is False:
            return None
        if system.gravity is None:
            if resting:
                with about("resting"):
                    raise ValueError("resting=True needs gravity: without it no disk is "
                                     "held anywhere")
            return None
        if resting is None and not system.inelastic:
            return None
        return cls.of(h, float(np.hypot(*system.gravity)), float(system.radii.min()))

    @classmethod
    def of(cls, height: float, g: float, radius: float) -> Resting:
        """The criteria of length ``height`` under gravity of magnitude ``g > 0``, for
        disks whose smallest radius is ``radius``.

        Parameters
        ----------
        height, g, radius : float

        Returns
        -------
        Resting
        """
        v = float(np.sqrt(2.0 * g * height))
        return cls(height, v, height, v, float(np.sqrt(4.0 * g * radius)), 0.1 * v)

    @classmethod
    def from_state(cls, state: dict) -> Resting:
        """The family a checkpoint stored; one saved before ``press`` existed gets it
        from the other fields: ``press = sqrt(2 |g| d) = speed sqrt(d / h)``, with the
        smallest diameter ``d``, which such a checkpoint does not hold, taken as
        ``1000 h`` (exact for the default ``rest_height``).

        Parameters
        ----------
        state : dict
            The fields ``state()`` stored.

        Returns
        -------
        Resting
        """
        state = dict(state)
        if "press" not in state:
            state["press"] = float(state["speed"]) * float(np.sqrt(1000.0))
        return cls(**state)

    @property
    def instant(self) -> float:
        """How far apart two contacts of a disk may lie and still count as one instant
        (wedged between two static bodies, or pushed into a floor), besides a few units
        of rounding of the clock: ``1e-6`` of ``soft / |g|``, the time a disk
        leaving a floor at the soft speed takes to stop rising.  Contact times at one instant
        differ by rounding, measured up to 3e-12 where the approach is slow (g = 1,
        unit diameters, clock ~ 5, where this is 4.5e-9): far below any bounce."""
        return 1e-6 * self.soft * 2.0 * self.height / (self.speed * self.speed)

    @property
    def every(self) -> float:
        """The interval of the search for groups of disks that hold one another up."""
        return 200.0 * self.height / self.speed

    def log(self) -> dict:
        """The criteria's length, as ``rest_height``.

        Returns
        -------
        dict of str to ndarray
        """
        return {"rest_height": np.array([self.height], np.float64)}

    @classmethod
    def keywords_from_log(cls, log: dict) -> dict:
        """``resting=True`` with the logged ``rest_height``.

        Parameters
        ----------
        log : dict of str to ndarray

        Returns
        -------
        dict
        """
        return {"resting": True, "rest_height": float(log["rest_height"][0])}


@dataclass(frozen=True, eq=False)
class Shear(Family):
    """Lees-Edwards (sliding-brick) boundaries: a box periodic on both axes whose images
    above slide along x at ``rate * height`` (those below at ``-rate * height``),
    shearing the disks at the shear rate ``rate``.

    The flow's velocity is ``(rate (y - height / 2), 0)``; a disk's velocity relative
    to it is its *peculiar* velocity, which a disk keeps when it leaves through the top
    or the bottom (its x velocity changes by ``-+ rate * height`` and its x by the
    images' offset).  The thermostat draws peculiar velocities.  The offset of the
    images above is ``offset`` at the simulation's ``time`` (0 by default) and grows
    at ``rate * height``, taken modulo the width (:attr:`Simulation.shear_offset
    <edmd2d.Simulation.shear_offset>`).

    Shear needs a box periodic on both axes, at least four largest diameters wide and
    three high (the grid's cells along the boundary; a box too small is refused), and
    does not combine with wall segments, gravity, growth, immovable disks or disks
    that come to rest.

    Attributes
    ----------
    rate : float
        The shear rate (either sign; ``0``: no shear).
    offset : float
        The offset of the images above where the shear started (the ``time`` the
        simulation was made at), in ``[0, width)``; the offset now is
        :attr:`Simulation.shear_offset <edmd2d.Simulation.shear_offset>`.
    """

    name: ClassVar[str] = "shear"
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("shear_rate", None, "rate",
                "the shear rate of Lees-Edwards boundaries (default: none)"),
        Keyword("shear_offset", None, "",
                "the offset of the images above at the start (default 0)"),
    )

    rate: float
    offset: float = 0.0

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *, shear_rate: float | None = None,
            shear_offset: float | None = None) -> Shear | None:
        """``None`` (no shear, also for 0) or Lees-Edwards boundaries at ``shear_rate``.

        Parameters
        ----------
        system : System
            Its box, segments, gravity and masses.
        shear_rate : float, optional
        shear_offset : float, optional
            The offset of the images above at the start, any finite number (taken
            modulo the box width); default 0.

        Returns
        -------
        Shear or None

        Raises
        ------
        ValueError
            For a rate or offset that is not a finite number, an offset without a
            rate, or a system that shear does not combine with.
        """
        assert system is not None  # (checked with the system, which it needs)
        offset = 0.0
        if shear_offset is not None:
            with about("shear_offset"):
                offset = float(as_float_array("shear_offset", shear_offset, ()))
                if shear_rate is None:
                    raise ValueError("shear_offset needs a shear_rate")
                offset %= system.box.width
        if shear_rate is None:
            return None
        with about("shear_rate"):
            rate = float(as_float_array("shear_rate", shear_rate, ()))
            if rate == 0.0:
                return None
            if not all(system.box.periodic):
                raise ValueError("shear_rate needs a box periodic on both axes "
                                 "(Lees-Edwards boundaries slide its images above and "
                                 "below)")
            if system.n_segments:
                raise ValueError("shear_rate does not combine with wall segments")
            if system.gravity is not None:
                raise ValueError("shear_rate does not combine with gravity")
            if np.isinf(system.masses).any():
                raise ValueError("shear_rate does not combine with immovable disks "
                                 "(infinite masses)")
        return cls(rate, offset)

    def log(self) -> dict:
        """The rate, as ``shear_rate`` (the offset at a frame's time is its box's tilt,
        which :mod:`edmd2d.io.gsd` writes).

        Returns
        -------
        dict of str to ndarray
        """
        return {"shear_rate": np.array([self.rate], np.float64)}


@dataclass(frozen=True, eq=False)
class Rough(Family):
    """Rough disks, which spin: a collision turns the tangential velocity of the two
    contact points into ``-beta`` times itself (``beta = tangential_restitution`` in
    ``[-1, 1]``: -1 smooth, +1 perfectly rough), exchanging energy between
    translation and rotation; Coulomb friction caps the tangential impulse at
    ``friction`` times the normal one (Walton's model, the contact sliding beyond).
    Box walls and wall segments have their own coefficients (default the disks').
    Each disk has the moment of inertia ``q m r^2`` (``q = inertia``, ``1/2`` for a
    uniform disk) and starts with the angular velocity ``angular_velocities``
    (counter-clockwise).

    Linear and angular momentum are conserved in every disk-disk collision, and the
    energy for elastic collisions with ``beta = +-1``; what a collision takes is
    dissipated.  Where the TC model makes a contact elastic it is also smooth; the
    thermostat draws the spin with the velocity, at its temperature; a heated wall
    sets the velocity only.  Under gravity the flights are parabolas as for smooth
    disks; rough disks do not combine with growth, shear or disks that come to rest
    (yet: an inelastic rough gas under gravity needs ``resting=False``).

    Attributes
    ----------
    beta, friction, wall_beta, wall_friction : float
    inertia : ndarray, shape (N,)
        ``q`` of each disk, in ``(0, 1]``.
    spins : ndarray, shape (N,)
        The angular velocities at the start.
    angles : ndarray, shape (N,)
        The angles at the start (counter-clockwise, in radians).
    """

    name: ClassVar[str] = "rough"
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("tangential_restitution", None, "rate",
                "beta in [-1, 1]: -1 smooth (default), +1 perfectly rough"),
        Keyword("friction", None, "nonnegative",
                "Coulomb's coefficient of disk-disk contacts, >= 0 (default: no limit)"),
        Keyword("wall_tangential_restitution", None, "rate",
                "beta at walls (default: the disks')"),
        Keyword("wall_friction", None, "nonnegative", "Coulomb's coefficient at walls"),
        Keyword("inertia", None, "coefficient",
                "q in (0, 1], per disk or for all: the moment of inertia q m r^2 "
                "(default 1/2)"),
        Keyword("angular_velocities", None, "rate",
                "the angular velocities at the start, per disk or for all (default 0)"),
        Keyword("angles", None, "rate",
                "the angles at the start, per disk or for all (default 0)"),
    )

    beta: float
    friction: float
    wall_beta: float
    wall_friction: float
    inertia: np.ndarray
    spins: np.ndarray
    angles: np.ndarray

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *,
            tangential_restitution: float | None = None, friction: float | None = None,
            wall_tangential_restitution: float | None = None,
            wall_friction: float | None = None, inertia: Any = None,
            angular_velocities: Any = None, angles: Any = None) -> Rough | None:
        """``None`` (smooth disks) or rough disks.

        Parameters
        ----------
        system : System
            Its number of disks.
        tangential_restitution, friction, wall_tangential_restitution, wall_friction :
            float, optional
        inertia, angular_velocities, angles : float or array_like, optional

        Returns
        -------
        Rough or None

        Raises
        ------
        ValueError
            For a value out of its range, or the other keywords without a
            tangential restitution.
        """
        assert system is not None  # (checked with the system, which it needs)
        n = len(system.radii)
        values = {}
        for name, value, low, high in (
                ("tangential_restitution", tangential_restitution, -1.0, 1.0),
                ("wall_tangential_restitution", wall_tangential_restitution, -1.0, 1.0),
                ("friction", friction, 0.0, math.inf),
                ("wall_friction", wall_friction, 0.0, math.inf)):
            if value is None:
                continue
            with about(name):
                x = float(as_float_array(name, value, (), allow_inf=True))
                if not low <= x <= high:
                    raise ValueError(f"{name} must lie in [{low:g}, {high:g}], got {x!r}")
            values[name] = x
        if "tangential_restitution" not in values and "wall_tangential_restitution" not in \
                values:
            given = [k for k, v in (("friction", friction), ("wall_friction", wall_friction),
                                    ("inertia", inertia),
                                    ("angular_velocities", angular_velocities),
                                    ("angles", angles))
                     if v is not None]
            if given:
                with about(given[0]):
                    raise ValueError(f"{given[0]} needs tangential_restitution (rough "
                                     f"disks)")
            return None
        beta = values.get("tangential_restitution", -1.0)
        q = np.full(n, 0.5)
        if inertia is not None:
            with about("inertia"):
                q = per_disk("inertia", inertia, n)
                if not np.all((q > 0.0) & (q <= 1.0)):
                    raise ValueError(f"inertia must lie in (0, 1], got {inertia!r}")
        spins, turned = (np.zeros(n) if value is None else per_disk(name, value, n)
                         for name, value in (("angular_velocities", angular_velocities),
                                             ("angles", angles)))
        return cls(beta, values.get("friction", math.inf),
                   values.get("wall_tangential_restitution", beta),
                   values.get("wall_friction", values.get("friction", math.inf)), q, spins,
                   turned)

    def log(self) -> dict:
        """The coefficients and each disk's ``inertia`` (a GSD frame holds the angular
        velocities at its time as a per-particle quantity, which :mod:`edmd2d.io.gsd`
        reads back as ``angular_velocities``).

        Returns
        -------
        dict of str to ndarray
        """
        return {"tangential_restitution": np.array([self.beta]),
                "friction": np.array([self.friction]),
                "wall_tangential_restitution": np.array([self.wall_beta]),
                "wall_friction": np.array([self.wall_friction]),
                "inertia": np.asarray(self.inertia, np.float64)}


@dataclass(frozen=True, eq=False)
class MovingWalls(Family):
    """Wall segments that move: ``wall_motions = {segment: motion}``, each motion a
    :class:`~edmd2d.Translation` (a piston: a constant velocity over a distance) or an
    :class:`~edmd2d.Oscillation` (a shaken floor: ``A sin(omega t + phase)`` along a
    direction).  A segment keeps its orientation; its path must stay inside the box.
    A disk meets a moving segment at the exact time (a translation is a fixed segment
    seen from a moving frame; an oscillation is found by a bracketed search that misses
    no contact deeper than ``2^-40`` of the disk's radius plus the amplitude), and
    leaves it with its normal velocity *relative to the segment* reversed (times the
    wall restitution).  The work the segments do on the disks is tallied
    (:meth:`Simulation.wall_work <edmd2d.Simulation.wall_work>`), so that kinetic and
    potential energy, less the work, plus what is dissipated, stay constant to
    rounding.

    A moving segment cannot be heated; moving walls do not combine with growth,
    shear or disks that come to rest (yet: an inelastic gas under gravity needs
    ``resting=False``).  With rough disks a segment turns the tangential velocity
    relative to its own and does the work of the tangential impulse too.

    Attributes
    ----------
    kind : ndarray of int64, shape (S,)
        Per segment: 0 fixed, 1 a translation, 2 an oscillation.
    par : ndarray, shape (S, 5)
        Per segment: the unit direction, then the speed, the start and the stop time
        of a translation, or the amplitude, the angular frequency and the phase of an
        oscillation.
    """

    name: ClassVar[str] = "moving_walls"
    keywords: ClassVar[tuple[Keyword, ...]] = (
        Keyword("wall_motions", None, "",
                "{segment: Translation or Oscillation}: wall segments that move"),
    )

    kind: np.ndarray
    par: np.ndarray

    @classmethod
    def check(  # type: ignore[override]  # (its own keywords, as Family.check says)
            cls, system: System | None = None, *,
            wall_motions: Any = None) -> MovingWalls | None:
        """``None`` (every segment fixed) or the segments' motions.

        Parameters
        ----------
        system : System
            Its box, wall segments and start time.
        wall_motions : dict of int to Translation or Oscillation

        Returns
        -------
        MovingWalls or None

        Raises
        ------
        TypeError, ValueError
            For a value that is not such a mapping, an index that names no segment,
            or a path that leaves the box.
        """
        assert system is not None  # (checked with the system, which it needs)
        if wall_motions is None:
            return None
        with about("wall_motions"):
            if not isinstance(wall_motions, dict):
                raise TypeError(f"wall_motions must be a dict {{segment index: Translation "
                                f"or Oscillation}}, got {type(wall_motions).__name__}")
            n = len(system.walls)
            kind = np.zeros(n, np.int64)
            par = np.zeros((n, _layout.N_MOTION))
            box = system.box
            for key, motion in wall_motions.items():
                k = as_count("wall_motions segment index", key)
                if k >= n:
                    raise ValueError(f"wall_motions names segment {k}, but there are "
                                     f"{n} wall segments")
                if not isinstance(motion, (Translation, Oscillation)):
                    raise TypeError(f"wall_motions[{k}] must be a Translation or an "
                                    f"Oscillation, got {motion!r}")
                started = motion.starting(system.time)
                wall = system.walls[k]
                for shift in started.extremes():
                    for end in (wall.start, wall.end):
                        x, y = end[0] + shift[0], end[1] + shift[1]
                        if not (0.0 <= x <= box.width and 0.0 <= y <= box.height):
                            raise ValueError(
                                f"wall_motions[{k}] takes walls[{k}] out of the box: its "
                                f"end point reaches ({x:.6g}, {y:.6g}), outside [0, "
                                f"{box.width:g}] x [0, {box.height:g}]")
                if isinstance(started, Translation):
                    assert started.begin is not None
                    speed = started.speed
                    kind[k] = _layout.LINEAR
                    par[k] = (started.velocity[0] / speed, started.velocity[1] / speed,
                              speed, started.begin, started.end)
                else:
                    kind[k] = _layout.SINE
                    par[k] = (*started.direction, started.amplitude, started.omega,
                              started.phase)
        if not np.any(kind != _layout.FIXED):
            return None
        return cls(kind, par)

    def motions(self) -> dict:
        """The motions by segment index, as given (with their start times).

        Returns
        -------
        dict of int to Translation or Oscillation
        """
        out: dict = {}
        for k in np.flatnonzero(self.kind != _layout.FIXED):
            p = self.par[k]
            if self.kind[k] == _layout.LINEAR:
                velocity = p[_layout.M_SPEED] * p[:2]
                distance = p[_layout.M_SPEED] * (p[_layout.M_END] - p[_layout.M_BEGIN])
                out[int(k)] = Translation(velocity, distance, p[_layout.M_BEGIN])
            else:
                out[int(k)] = Oscillation(p[_layout.M_AMPLITUDE], p[_layout.M_OMEGA],
                                          p[:2], p[_layout.M_PHASE])
        return out

    def extremes(self) -> tuple[np.ndarray, np.ndarray]:
        """The two ends of every segment's path as shifts from where it was given (zero
        where fixed): it moves between them.

        Returns
        -------
        tuple of two numpy.ndarray, shape (S, 2)
        """
        low = np.zeros((len(self.kind), 2))
        high = np.zeros((len(self.kind), 2))
        for k, motion in self.motions().items():
            low[k], high[k] = motion.extremes()
        return low, high

    def shifts(self, t: float) -> np.ndarray:
        """Every segment's displacement at time ``t`` (zero where fixed).

        Parameters
        ----------
        t : float

        Returns
        -------
        numpy.ndarray, shape (S, 2)
        """
        out = np.zeros((len(self.kind), 2))
        for k, motion in self.motions().items():
            out[k] = motion.shift(t)
        return out

    def log(self) -> dict:
        """The motions' table (``kind`` and ``par``, as float64).

        Returns
        -------
        dict of str to ndarray
        """
        return {"kind": self.kind.astype(np.float64), "par": self.par.ravel()}

    @classmethod
    def keywords_from_log(cls, log: dict) -> dict:
        """``wall_motions`` rebuilt from what a GSD frame logged.

        Parameters
        ----------
        log : dict of str to ndarray

        Returns
        -------
        dict
        """
        kind = np.asarray(log["kind"]).astype(np.int64)
        par = np.asarray(log["par"], np.float64).reshape(len(kind), _layout.N_MOTION)
        return {"wall_motions": cls(kind, par).motions()}


for _family in (Restitution, Gravity, HeatedWalls, Thermostat, Growth, Resting, Shear,
                Rough, MovingWalls):
    register(_family)


def check_registered(system: System, values: dict) -> dict:
    """The registered families that are not built in, built from the keywords in
    ``values`` (a family none of whose keywords is given is left out, unless it is
    checked :attr:`~Family.always`, as is one whose check gives ``None``).

    Parameters
    ----------
    system : System
    values : dict
        Keywords given to :class:`~edmd2d.Simulation` beyond its own.

    Returns
    -------
    dict of str to Family

    Raises
    ------
    TypeError
        For a keyword that no registered family takes (naming the closest one).
    """
    for key in values:
        if key not in _OWNER or _OWNER[key].built_in:
            known = [k for k, f in _OWNER.items() if not f.built_in]
            close = difflib.get_close_matches(key, list(_OWNER) + list(_RESERVED), n=1)
            hint = f"; did you mean {close[0]!r}?" if close else (
                f"; the registered families take {known}" if known else "")
            raise TypeError(f"Simulation() got an unexpected keyword argument {key!r}{hint}")
    out = {}
    for name, family in FAMILIES.items():
        given = {kw.name: values[kw.name] for kw in family.keywords if kw.name in values}
        if family.built_in or not (given or family.always):
            continue
        built = family.check(system, **given)
        if built is not None:
            out[name] = built
    return out
