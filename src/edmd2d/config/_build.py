"""Building the simulation a checked configuration describes (:func:`build`)."""

from __future__ import annotations

import numpy as np

from .. import builders, physics
from .._validate import argument_of, as_generator
from ..builders import make_gas, random_gas
from ..geometry import Oscillation, Translation, Wall
from ..simulation import Simulation
from ._schema import _KINDS, ConfigError, RunConfig

# Keyword of make_gas or Simulation -> the key of the configuration it comes from.
_ARGUMENT_KEYS = {
    "n": ("gas", "n"), "packing_fraction": ("gas", "packing_fraction"),
    "temperature": ("gas", "temperature"), "radius": ("gas", "radius"),
    "radii": ("gas", "species"), "masses": ("gas", "mass"), "aspect": ("gas", "aspect"),
    "periodic": ("gas", "periodic"), "species": ("gas", "species"),
    "walls": ("walls",), "positions": ("walls",), "velocities": ("walls",),
    "wall_motions": ("walls",),
    "seed": ("model", "seed"),
}


def _key_of_argument(exc: BaseException) -> tuple:
    """The configuration key of the argument a library error is about, or ``()``."""
    name = argument_of(exc)
    if name is None:
        return ()
    if name in physics.KEYWORDS and physics.KEYWORDS[name].kind:
        return ("model", name)
    return _ARGUMENT_KEYS.get(name, ())


def wall_openings(walls: list) -> tuple[list[int], list[tuple[float, list[int]]]]:
    """The segments of the checked ``[[walls]]`` tables ``walls`` that start open, and
    when the others open: ``(open_at_start, [(time, segments), ...])``, the segments
    by their index in the simulation (a polygon's sides in order, table after table).
    """
    start, later = [], []
    k = 0
    for w in walls:
        count = len(w["polygon"]) if w["polygon"] is not None else 1
        segments = list(range(k, k + count))
        k += count
        if w["open"]:
            start.extend(segments)
        elif w["opens_at"] is not None:
            later.append((float(w["opens_at"]), segments))
    return start, later


def build(cfg: RunConfig,
          seed: int | np.random.SeedSequence | None) -> tuple[Simulation, int]:
    """The simulation a configuration describes, at time 0.

    Without wall segments or a mixture of masses this is
    ``edmd2d.make_gas(n, packing_fraction, ..., seed=seed)`` with the ``[model]``
    keywords (``edmd2d.random_gas`` with ``start = "random"``).  A mixture's species
    are laid on the lattice at random (species of equal radius told apart by a further
    random draw) and, if their masses differ,
    their velocities are drawn for their masses; disks that a wall segment crosses are
    left out (by :func:`edmd2d.builders.clear_of_walls`, the rule of ``make_gas(...,
    walls=...)``).

    Parameters
    ----------
    cfg : RunConfig
    seed : int or numpy.random.SeedSequence
        The seed of all random numbers (``[model] seed``, or one drawn by the caller).

    Returns
    -------
    sim : Simulation
    removed : int
        Disks left out because a wall segment crossed them.

    Raises
    ------
    ConfigError
        If the library refuses a value (the message is the library's, with the key
        and line it comes from).
    """
    gas, model = cfg.data["gas"], cfg.data["model"]
    rng = as_generator("seed", seed)
    species = gas["species"]
    try:
        if species is None:
            radii, masses, radius = None, gas["mass"], gas["radius"]
        else:
            radii = np.repeat([s["radius"] for s in species], [s["count"] for s in species])
            species_masses = np.array([s["mass"] for s in species])
            masses = float(species_masses[0]) if (species_masses == species_masses[0]).all() \
                else 1.0
            radius = 0.5
        start = (random_gas if gas["start"] == "random" else make_gas)(
            gas["n"], gas["packing_fraction"], radius=radius, radii=radii, masses=masses,
            aspect=gas["aspect"], periodic=_box_kind(gas), temperature=gas["temperature"],
            seed=rng)
        pos, vel, rad, mass = (start.positions, start.velocities, start.radii,
                               start.masses.copy())
        labels = None
        if species is not None:
            labels = _species_labels(rad, species, rng)
            mass = species_masses[labels]
            if not (species_masses == species_masses[0]).all():
                vel = builders._maxwell_boltzmann(rng, mass, gas["temperature"],
                                                  sum(start.box.periodic))
        walls: list[Wall] = []
        motions = {}
        for w in cfg.data["walls"]:
            first = len(walls)
            if w["polygon"] is not None:
                walls.extend(Wall.polygon(w["polygon"]))
            else:
                walls.append(Wall(tuple(w["start"]), tuple(w["end"])))
            motion = _motion(w)
            if motion is not None:
                motions.update({k: motion for k in range(first, len(walls))})
        open_at_start, _ = wall_openings(cfg.data["walls"])
        # (The rule of make_gas(walls=...), for the segments where they are at the
        # start; the species are labelled before, on the whole lattice, so that each
        # keeps its count there.)
        placed = [Wall(np.add(w.start, motions[k].shift(0.0)),
                       np.add(w.end, motions[k].shift(0.0))) if k in motions else w
                  for k, w in enumerate(walls)]
        keep = builders.clear_of_walls(pos, rad, placed, start.box)
        if not keep.any():
            raise cfg.error(("walls",), "the wall segments cross every disk of the gas")
        # (Sheared: the velocities drawn are the peculiar ones, in the flow.)
        vel = builders._with_shear_flow(vel, pos, start.box, model.get("shear_rate"))
        sim = Simulation(
            pos[keep], vel[keep], rad[keep], mass[keep], box=start.box, walls=walls,
            open_walls=open_at_start,
            species=None if labels is None else labels[keep], seed=rng,
            **_physics_keywords(model, motions))
    except (TypeError, ValueError) as exc:
        if isinstance(exc, ConfigError):
            raise
        raise cfg.error(_key_of_argument(exc), str(exc)) from None
    return sim, int((~keep).sum())


def _motion(row: dict) -> Translation | Oscillation | None:
    """The motion a checked [[walls]] table gives its segments, or ``None``."""
    if row["velocity"] is not None:
        return Translation(row["velocity"], row["distance"],
                           0.0 if row["begin"] is None else row["begin"])
    if row["amplitude"] is not None:
        return Oscillation(row["amplitude"], row["omega"],
                           (0.0, 1.0) if row["direction"] is None else row["direction"],
                           0.0 if row["phase"] is None else row["phase"])
    return None


def _physics_keywords(model: dict, motions: dict) -> dict:
    """The values ``[model]`` gives the keywords of the registered physics families, as
    the library takes them: a table of coefficients as an array, the index of a heated
    wall segment as an integer; and the ``motions`` of the ``[[walls]]`` tables."""
    out: dict = {"wall_motions": motions} if motions else {}
    for name, kw in physics.KEYWORDS.items():
        value = model.get(name)
        if value is None or not (kw.kind in _KINDS or kw.kind == "walls"):
            continue
        if kw.kind == "coefficients" and isinstance(value, list):
            value = np.array(value)
        elif kw.kind == "walls":
            value = {(int(k) if k.isdigit() else k): v for k, v in value.items()}
        out[name] = value
    return out


def _box_kind(gas: dict):
    periodic = gas["periodic"]
    return tuple(periodic) if isinstance(periodic, list) else periodic


def _species_labels(radii: np.ndarray, species: list, rng) -> np.ndarray:
    """Each disk's species, from its radius (``make_gas`` shuffles the radii over the
    lattice); among species of equal radius, a random permutation decides."""
    labels = np.empty(len(radii), np.int64)
    species_radii = np.array([s["radius"] for s in species])
    for r in np.unique(species_radii):
        ids = np.flatnonzero(species_radii == r)
        members = np.repeat(ids, [species[k]["count"] for k in ids])
        where = np.flatnonzero(radii == r)
        labels[where] = members if len(ids) == 1 else rng.permutation(members)
    return labels
