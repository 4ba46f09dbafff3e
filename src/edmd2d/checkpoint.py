"""Checkpoints: a simulation's complete state in a file, for exact restarts.

:func:`save` writes everything a :class:`~edmd2d.Simulation` holds -- the disks' rows
at their own local times, the event queue, the grid, the counts, the accumulated
impulses and energies, the physics model with its per-disk state, and the state of
its random number generator -- in float64 and int exactly as in memory, so that
:func:`load` in another process continues the run bit for bit as if it had never
stopped.

The format (``FORMAT`` and ``VERSION`` below) is a NumPy ``.npz`` archive (a zip
file, every member with its CRC-32): one ``.npy`` member per array, and a member
``header.json`` holding the format name, the version, the edmd2d version that wrote
it, and every value that is not an array (the box, the wall segments, scalars, the
generator's state) with the array members it refers to, and the caller's
``metadata`` (what a program needs to go on with the run: its configuration, the time
it runs to, the state of its measurements; read back with :func:`read_metadata`).
Nothing is pickled: loading a checkpoint runs no code from the file.

Writing goes to a temporary file beside the target, flushed to disk, then renamed over
it: a write interrupted half-way leaves the previous checkpoint intact.  Loading
refuses, with a ``ValueError`` that says why, a file that is not a checkpoint, one of
another format version, a truncated or corrupted one (a zip or CRC error, a missing
member), and a state whose arrays do not fit together.

Examples
--------
>>> import os, tempfile
>>> import edmd2d as ed
>>> sim = ed.make_gas(100, 0.3, seed=1).advance(until=2.0)
>>> path = os.path.join(tempfile.mkdtemp(), "gas.edmd2d")
>>> ed.checkpoint.save(sim, path)
>>> again = ed.checkpoint.load(path)
>>> bool((again.advance(until=4.0).positions == sim.advance(until=4.0).positions).all())
True
"""

from __future__ import annotations

import io
import json
import os
import zipfile
from collections.abc import Callable
from pathlib import Path

import numpy as np

from . import models as _models
from . import physics as _physics
from ._atomic import replacing
from ._engine.layout import Wide
from ._operations import Operation, Trigger
from ._state import EngineState
from ._version import __version__
from .geometry import Box, Wall
from .simulation import Simulation

__all__ = ["FORMAT", "VERSION", "save", "load", "read_metadata", "Checkpoint"]

#: The format name in every checkpoint's header; :func:`load` refuses other files.
FORMAT = "edmd2d-checkpoint"
#: The format version, bumped when what a checkpoint holds changes incompatibly;
#: :func:`load` refuses other versions.
VERSION = 2

_HEADER = "header.json"


def save(sim: Simulation, path: str | os.PathLike[str], *, metadata: dict | None = None) -> None:
    """Write the complete state of ``sim`` to ``path`` (atomically: see the module).

    Parameters
    ----------
    sim : Simulation
        The simulation, unchanged by the call.
    path : str or os.PathLike
        The file; its directory must exist.  An existing file is replaced only once
        the new one is complete.
    metadata : dict, optional
        Anything JSON can hold (strings, numbers, lists, dicts), stored with the
        state and returned by :func:`read_metadata`; floats are kept exactly.

    Raises
    ------
    TypeError
        If ``sim`` is not a Simulation, holds a value this format cannot store, or
        ``metadata`` is not a dict JSON can hold (nothing is then written).
    OSError
        If the file cannot be written (the previous file, if any, is left as it was).
    """
    if not isinstance(sim, Simulation):
        raise TypeError(f"save() needs an edmd2d.Simulation, got {type(sim).__name__}")
    arrays: dict[str, np.ndarray] = {}
    state = {key: _encode(key, value, arrays)
             for key, value in sim._state.__getstate__().items()}
    header = {"format": FORMAT, "version": VERSION, "edmd2d": __version__, "state": state}
    if metadata is not None:
        if not isinstance(metadata, dict):
            raise TypeError(f"metadata must be a dict, got {type(metadata).__name__}")
        try:
            json.dumps(metadata)
        except (TypeError, ValueError) as exc:
            raise TypeError(f"metadata must hold only what JSON can store ({exc})") from None
        header["metadata"] = metadata
    with replacing(path) as f, zipfile.ZipFile(f, "w", zipfile.ZIP_STORED) as z:
        z.writestr(_HEADER, json.dumps(header, indent=1))
        for name, arr in arrays.items():
            buf = io.BytesIO()
            np.lib.format.write_array(buf, np.ascontiguousarray(arr), allow_pickle=False)
            z.writestr(name + ".npy", buf.getvalue())


def load(path: str | os.PathLike[str]) -> Simulation:
    """Read a checkpoint written by :func:`save`: a Simulation that continues exactly.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    Simulation

    Raises
    ------
    ValueError
        If the file is not an edmd2d checkpoint, is of another format version, or is
        truncated or corrupted.
    OSError
        If it cannot be read.
    """
    header, arrays = _read(path, arrays=True)
    try:
        state = {key: _decode(value, arrays) for key, value in header["state"].items()}
        engine = EngineState.__new__(EngineState)
        engine.__setstate__(state)
        _check_consistent(engine)
        sim = Simulation.__new__(Simulation)
        sim.__setstate__({"_state": engine})
    except (KeyError, TypeError, ValueError, IndexError) as exc:
        raise ValueError(f"{path} holds an inconsistent state ({exc})") from None
    return sim


def read_metadata(path: str | os.PathLike[str]) -> dict:
    """The ``metadata`` saved with a checkpoint (an empty dict if none was given).

    Only the file's header is read, so this is quick for any size of state.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    dict

    Raises
    ------
    ValueError
        As for :func:`load`.
    OSError
        If it cannot be read.
    """
    header, _ = _read(path, arrays=False)
    meta = header.get("metadata", {})
    return meta if isinstance(meta, dict) else {}


def _read(path, *, arrays: bool):
    """``(header, arrays)`` of a checkpoint file, checked as :func:`load` describes
    (``arrays`` empty unless asked for)."""
    path = Path(path)
    out = {}
    try:
        with zipfile.ZipFile(path) as z:
            names = set(z.namelist())
            if _HEADER not in names:
                raise ValueError(f"{path} is not an edmd2d checkpoint (no {_HEADER})")
            header = json.loads(z.read(_HEADER))
            if not isinstance(header, dict) or header.get("format") != FORMAT:
                raise ValueError(f"{path} is not an edmd2d checkpoint")
            if header.get("version") != VERSION:
                raise ValueError(
                    f"{path} is a checkpoint of format version {header.get('version')} "
                    f"(written by edmd2d {header.get('edmd2d')}); this edmd2d "
                    f"{__version__} reads version {VERSION}")
            if arrays:
                for name in names - {_HEADER}:
                    with z.open(name) as member:
                        out[name[:-4]] = np.lib.format.read_array(
                            io.BytesIO(member.read()), allow_pickle=False)
    except zipfile.BadZipFile as exc:
        raise ValueError(f"{path} is truncated or corrupted ({exc})") from None
    except (KeyError, json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path} is corrupted ({exc})") from None
    return header, out


# ---------------------------------------------------------------- encoding
def _encode(name, value, arrays):
    """A JSON-able description of ``value``; arrays go into ``arrays`` by name."""
    if isinstance(value, np.ndarray):
        arrays[name] = value
        return {"array": name}
    if value is None or isinstance(value, (bool, int, float, str)):
        return {"value": value}
    if isinstance(value, np.generic):
        return {"value": value.item()}
    if isinstance(value, Box):
        return {"box": [value.width, value.height, list(value.periodic)]}
    if isinstance(value, tuple) and all(isinstance(w, Wall) for w in value):
        return {"walls": [[list(w.start), list(w.end)] for w in value]}
    if isinstance(value, _models.Model):
        fields = {}
        for key, item in vars(value).items():
            if key == "rng":
                bit = item.bit_generator
                fields[key] = {"generator": type(bit).__name__,
                               "state": _encode_json(bit.state)}
            else:
                fields[key] = _encode(f"{name}.{key}", item, arrays)
        return {"model": fields}
    if isinstance(value, Wide):  # (the grid's wide disks: arrays and a float)
        return {"wide": {key: _encode(f"{name}.{key}", item, arrays)
                         for key, item in value._asdict().items()}}
    if isinstance(value, dict) and all(isinstance(f, _physics.Family) for f in value.values()):
        return {"families": {key: {k: _encode(f"{name}.{key}.{k}", v, arrays)
                                   for k, v in family.state().items()}
                             for key, family in value.items()}}
    raise TypeError(f"a checkpoint cannot store {name} of type {type(value).__name__}")


def _encode_json(value):
    """The generator's state (nested dicts of ints and strings) with the numpy
    integers of some bit generators made plain."""
    if isinstance(value, dict):
        return {k: _encode_json(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return {"ndarray": value.tolist(), "dtype": str(value.dtype)}
    if isinstance(value, np.generic):
        return value.item()
    return value


def _decode_json(value):
    if isinstance(value, dict):
        if set(value) == {"ndarray", "dtype"}:
            return np.array(value["ndarray"], dtype=value["dtype"])
        return {k: _decode_json(v) for k, v in value.items()}
    return value


def _decode(value, arrays):
    (kind, item), = value.items()
    if kind == "array":
        return arrays[item]
    if kind == "value":
        return item
    if kind == "box":
        width, height, periodic = item
        return Box(width, height, periodic=tuple(periodic))
    if kind == "walls":
        return tuple(Wall(tuple(a), tuple(b)) for a, b in item)
    if kind == "model":
        model = _models.Model.__new__(_models.Model)
        fields = {}
        for key, entry in item.items():
            if key == "rng":
                bit = getattr(np.random, entry["generator"])()
                bit.state = _decode_json(entry["state"])
                fields[key] = np.random.Generator(bit)
            else:
                fields[key] = _decode(entry, arrays)
        model.__setstate__(fields)
        return model
    if kind == "wide":
        return Wide(**{key: _decode(entry, arrays) for key, entry in item.items()})
    if kind == "families":
        out = {}
        for key, fields in item.items():
            if key not in _physics.FAMILIES:
                raise ValueError(f"this checkpoint holds the physics family {key!r}, which "
                                 "is not registered here (edmd2d.physics.register it before "
                                 "loading)")
            out[key] = _physics.FAMILIES[key].from_state(
                {k: _decode(v, arrays) for k, v in fields.items()})
        return out
    raise ValueError(f"unknown entry {kind!r}")


def _check_consistent(state) -> None:
    """The tables and per-disk arrays of the engine's ``state`` fit together (a file
    assembled from parts of two checkpoints would not)."""
    n = len(state.S)
    for name in ("E", "mass", "image", "order", "hv"):
        if len(getattr(state, name)) != n:
            raise ValueError(f"{name} has {len(getattr(state, name))} rows, not {n}")
    if sorted(state.order.tolist()) != list(range(n)):
        raise ValueError("the disk order is not a permutation")


class Checkpoint(Operation):
    """Write a checkpoint to ``path`` when ``trigger`` fires, replacing the previous
    one atomically (see :func:`~edmd2d.checkpoint.save`).

    Parameters
    ----------
    path : str or os.PathLike
    trigger : Trigger
    metadata : dict or callable, optional
        Stored in the checkpoint (:func:`~edmd2d.checkpoint.save`); a callable is called with the
        simulation at each firing and returns the dict, e.g. the state of a
        :class:`~edmd2d.measurements.Measure` of the same run (list the Checkpoint
        after the operations whose state it saves, so that it sees them at the same
        stop).
    """

    def __init__(self, path: str | os.PathLike[str], trigger: Trigger, *,
                 metadata: dict | Callable[[Simulation], dict] | None = None) -> None:
        super().__init__(trigger)
        if metadata is not None and not (callable(metadata) or isinstance(metadata, dict)):
            raise TypeError(f"metadata must be a dict or a callable, got {metadata!r}")
        self.path = path
        self.metadata = metadata

    def __call__(self, sim) -> None:
        """Save ``sim`` with the metadata, replacing the file."""
        meta = self.metadata(sim) if callable(self.metadata) else self.metadata
        save(sim, self.path, metadata=meta)
