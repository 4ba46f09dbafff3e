"""The engine's state, owned in one place: :class:`EngineState`.

It holds the row tables and their column views, the grid and the wall segments listed
per cell, the calendar queue, the tallies, the event log, the Z-order re-sorting, the
regridding of growing disks, the calls of the event loop and the translation of its
status codes into exceptions.  ``Simulation`` (the facade) checks its input, builds
one and reads it; checkpoints save and load one field by field.
"""

from __future__ import annotations

import math
import time as _time

import numpy as np

from . import _balance, _checks, _gaps, _impacts
from . import models as _models
from . import progress as _progress
from ._checks import OVERLAP_TOL
from ._engine import aligned_rows
from ._engine import flight as _flight
from ._engine import grid as _grid
from ._engine import helfand as _helfand
from ._engine import layout as _layout
from ._engine import loop as _loop
from ._engine import overlap as _overlap
from ._engine import queue as _queue
from ._engine import response as _response
from ._engine import resting as _resting
from ._engine import sheared as _sheared
from ._engine import wide as _wide
from ._sums import dot
from ._validate import about, as_generator, indices_where
from .geometry import BOX_WALL_EQUATIONS, MAX_LENGTH, Translation, Wall

__all__ = ["EngineState", "build_model", "EVENT_KINDS", "EVENT_DTYPE", "VERSION"]

#: The version of the state's layout: pickles and checkpoints of another are refused.
VERSION = 2

# Margin by which a cell exceeds the largest diameter, so that a centre that is a
# rounding error outside its logical cell is still seen by its neighbours.
_CELL_MARGIN = 1e-9
# Events per engine call; between calls Python regains control, so that Ctrl-C stops a
# run within a fraction of a second (2^18 events: 0.1-0.5 s at 0.5-2 M events/s),
# leaving it at the last event processed.
_CHUNK_EVENTS = 1 << 18
# Events in a row at one instant after which disks count as wedged (no configuration
# needs more: a row of simultaneous contacts, a lattice crossing its cells together):
# per disk, and at least as many as this minimum.
_WEDGED_EVENTS_PER_DISK = 64
_WEDGED_EVENTS_MIN = 1 << 20
# Impacts (``_impacts.py``) at one instant after which a stall stops the run.
_IMPACTS_AT_ONCE = 8


def _resting_instant(t: float) -> float:
    """Stalls this close to ``t`` come at one instant, for the count of impacts: a few
    units of rounding of the clock, as for the streaks of collisions."""
    return _response.INSTANT * abs(t)
# Events per engine call when a progress bar is shown (a few ms at 10^6 coll/s).
_PROGRESS_EVENTS = 1 << 16
# Systems at least this large are kept sorted in memory along a Z-order curve over the
# grid cells, re-sorted every _REORDER_EVENTS_PER_DISK * N events: disks near in space
# then sit near in memory, which matters once the state no longer fits in the caches.
_REORDER_MIN_DISKS = 1024
_REORDER_EVENTS_PER_DISK = 20
# Under growth the grid is built for a largest diameter this much above the current one,
# and rebuilt when the disks reach it (an O(N) rebuild every 10% of growth).
_GROWTH_GRID_SLACK = 1.1
# The engine's physics families of elastic disks between reflecting walls: none.
_NO_MODEL = _layout.ModelFamilies(None, None, None, None)

_KIND_NAMES = {_layout.DISK: "disk", _layout.SEGMENT: "wall", _layout.BOX: "box",
               _layout.KICK: "thermostat", _layout.REST: "rest", _layout.WAKE: "wake"}
_KIND_CODES = np.array(sorted(_KIND_NAMES))
EVENT_KINDS = tuple(_KIND_NAMES[k] for k in _KIND_CODES)
EVENT_DTYPE = np.dtype([("time", "f8"), ("kind", "U10"), ("disk", "i8"),
                        ("partner", "i8"), ("impulse", "f8")])


def build_model(system, seed, contact, heated, thermostat):
    """The :class:`~edmd2d.models.Model` of the checked families, or ``None`` for
    elastic disks between reflecting walls without a thermostat (the engine's default
    path)."""
    if contact.elastic and not heated.active and thermostat is None:
        return None
    rng = None
    if heated.active or thermostat is not None:
        rng = as_generator("seed", seed)
    return _models.Model(
        contact.table, contact.wall, contact.tc, contact.species, heated.kt,
        None if thermostat is None else (thermostat.temperature, thermostat.rate), rng,
        system.time)

class EngineState:
    """Everything a simulation holds between two calls of the event loop, in the
    engine's internal row order (row ``k`` holds the user's disk ``order[k]``).

    Parameters
    ----------
    box, walls
        The container and its wall segments (checked).
    pos, vel, rad, mass : numpy.ndarray
        The disks in the user's order (checked, ``pos`` inside the box).
    time : float
        The clock.
    species, model, gravity, growth, cell_size, families
        The checked physics: ``species`` an int array or ``None``, ``model`` a
        :class:`~edmd2d.models.Model` or ``None``, ``gravity`` an array of shape (2,)
        or ``None``, ``growth`` a ``physics.Growth`` or ``None``, ``families`` the
        registered families by name.

    Raises
    ------
    ValueError
        For overlapping disks, or a disk at rest on a wall that gravity presses it
        into.
    """

    # Per-disk columns that are views into the rows of S and E (loop.row_views).
    ROW_VIEWS = ("stamp", "nxt", "prv", "qt", "tcand", "invm")

    # Installed together by one ``vars(self).update`` (see :meth:`tables`): the tables,
    # the queue's other arrays and the per-disk column views into the tables.
    S: np.ndarray
    E: np.ndarray
    hv: np.ndarray
    qhead: np.ndarray
    qs: np.ndarray
    qf: np.ndarray
    stamp: np.ndarray
    nxt: np.ndarray
    prv: np.ndarray
    qt: np.ndarray
    tcand: np.ndarray
    invm: np.ndarray
    # The batches of events that :meth:`record_events` collects.
    recorded: list[np.ndarray]

    def __init__(self, box, walls, pos, vel, rad, mass, time, *, species, model, gravity,
                 growth, cell_size, families, wall_open=None, grid="auto") -> None:
        n = len(pos)
        self.box = box
        self.walls = tuple(walls)
        self.gravity = gravity
        # Per-disk state and bookkeeping, one 64-byte row each in S and E (see
        # _engine/layout.py for the columns).
        state = aligned_rows(n, _layout.N_STATE, np.float64)  # 64-byte rows, aligned
        state[:] = 0.0  # (also the spare bytes: the rows are compared bit for bit)
        state[:, _layout.X:_layout.Y + 1] = pos
        state[:, _layout.VX:_layout.VY + 1] = vel
        state[:, _layout.T] = time
        state[:, _layout.R] = rad
        # E: the bookkeeping table (cell, kept candidate, queue links and time).
        _, table, hv, qhead, qs, qf = _queue.allocate(n)
        self.mass = mass
        self.time = float(time)
        # (The stamps start at 0.)
        vars(self).update(self.tables(state, table, hv, qhead, qs, qf))
        with np.errstate(divide="ignore"):
            self.invm[:] = np.where(np.isinf(mass), 0.0, 1.0 / mass)
        self.tcand[:] = np.inf
        # Image counters stay int64: a fast disk in a small periodic box can wrap more
        # than 2^31 times in a long run.
        self.image = np.zeros((n, 2), np.int64)
        if self.walls:
            self.wa = np.array([w.start for w in self.walls], np.float64)
            self.wb = np.array([w.end for w in self.walls], np.float64)
        else:
            self.wa = np.zeros((0, 2))
            self.wb = np.zeros((0, 2))
        # Each segment's impulses and contacts (layout.W_*), summed by the engine.
        self.wacc = np.zeros((len(self.walls), _layout.N_WACC))
        # Open segments (an outlet's gate opened): kept, with their tallies, but listed
        # in no cell, so that no disk meets them.
        self.wall_open = (np.zeros(len(self.walls), bool) if wall_open is None
                          else np.array(wall_open, bool))
        self.cell_size = cell_size
        # "auto" (wide disks where they pay, see _engine/wide.py), "uniform" or "wide".
        self.grid_mode = grid
        self.growth = None if growth is None else np.array([growth.rate, self.time])
        # Lees-Edwards boundaries (the registered family "shear"): the clock of the
        # images' offset and the integrals of the kinetic stress (see
        # _engine/sheared.py), started once the grid is built.
        self.families = families
        if self.shear is not None and growth is not None:
            with about("shear_rate"):
                raise ValueError("shear_rate does not combine with growth")
        self.shear_clock: np.ndarray | None = None
        self.shear_slides: np.ndarray | None = None
        self.shear_idle: np.ndarray | None = None
        self.shear_flights: np.ndarray | None = None
        # The sums of the Einstein-Helfand moments while they are kept (see
        # _engine/helfand.py; started and stopped by edmd2d.transport).
        self.helfand_sums: np.ndarray | None = None
        # How many times positions or velocities were set from outside (what a
        # measurement that goes on across runs must not miss).
        self.edits = 0
        self.build_grid(pos, self.grid_diameter(2.0 * float(rad.max())), cell_size)
        with about("positions"):
            self.check_overlaps(pos, rad)
        _layout.support_view(state)[:] = _checks.resting(box, self.walls_holding_still(), gravity,
                                                         pos, vel, rad, mass, model)
        self.species = species
        self.model = model
        self.families = families
        # Disks at rest (the registered family "resting"): each one's supports, and room
        # for the cascade of a wake (see _engine/resting.py).
        self.rest_supports = (np.full((n, _resting.MAX_SUPPORTS), -1, np.int32)
                              if "resting" in families else None)
        self.rest_frozen = np.zeros((n, 2)) if "resting" in families else None
        self.rest_t_static = np.full(n, -np.inf) if "resting" in families else None
        # Rough disks (the registered family "rough"): each disk's angular velocity,
        # angle (at its own time) and inverse moment of inertia (see _engine/rough.py).
        rough = families.get("rough")
        self.rough_w = self.rough_angle = self.rough_t = self.rough_inv_inertia = None
        if rough is not None:
            with about("tangential_restitution"):
                others = {"growth": growth, "resting": families.get("resting"),
                          "shear": families.get("shear")}
                for name, other in others.items():
                    if other is None:
                        continue
                    if name == "resting":
                        raise ValueError(
                            "rough disks do not come to rest (yet): under gravity with "
                            "an inelastic model, give resting=False")
                    raise ValueError(f"rough disks do not combine with {name}")
            movable = np.isfinite(mass)
            self.rough_w = np.where(movable, rough.spins, 0.0)
            self.rough_angle = rough.angles.copy()
            self.rough_t = np.full(n, float(time))
            inertia = rough.inertia * np.where(movable, mass, 1.0) * rad * rad
            self.rough_inv_inertia = np.where(movable, 1.0 / inertia, 0.0)
        self.check_motions(families, growth)
        self.rest_check = self.first_rest_check()
        self.counts = np.zeros(_layout.N_COUNTS, np.int64)
        self.acc = np.zeros(_layout.N_ACC, np.float64)
        self.set_log(0)
        self.listener = None  # (see stream; not part of the saved state)
        self.order = np.arange(n, dtype=np.int64)
        self.reorder_every = (
            _REORDER_EVENTS_PER_DISK * n if n >= _REORDER_MIN_DISKS else np.iinfo(np.int64).max
        )
        self.since_reorder = 0
        self.predict_all()
        if n >= _REORDER_MIN_DISKS:
            self.reorder()

    def __len__(self) -> int:
        return len(self.S)

    # ------------------------------------------------------------------ tables
    @classmethod
    def tables(cls, state, table, hv, qhead, qs, qf) -> dict:
        """The attributes for the tables ``S`` and ``E``, the queue's other arrays and
        the per-disk columns that are views into ``S`` and ``E`` (the queue times among
        them): to be installed together, by one ``vars(self).update``."""
        attrs = dict(S=state, E=table, hv=hv, qhead=qhead, qs=qs, qf=qf)
        attrs.update(zip(cls.ROW_VIEWS, _layout.row_views(state, table)))
        return attrs

    def __getstate__(self) -> dict:
        """For pickles, copies and checkpoints: without the views into ``S`` and ``E``,
        which a copy would turn into arrays of their own, detached from the copied
        tables (:meth:`__setstate__` rebuilds them), and without a stream's callback
        and what it collected (a copy does not stream, and its log is empty), nor the
        sums of the Einstein-Helfand moments (no ``Transport`` samples a copy: they
        belong to the one that runs on the original)."""
        state = dict(vars(self))
        state["helfand_sums"] = None
        for name in self.ROW_VIEWS:
            del state[name]
        for name in ("listener", "recorded"):
            state.pop(name, None)
        for name, empty in (("log_t", np.zeros(0)), ("log_e", np.zeros((0, 3), np.int64)),
                            ("log_j", np.zeros(0)), ("log_n", np.zeros(1, np.int64)),
                            ("log_capacity", 0)):
            state[name] = empty
        return state

    def __setstate__(self, state: dict) -> None:
        state = dict(state)
        if len(state["qs"]) != _queue.N_QS:
            raise ValueError(
                f"queue state of {len(state['qs'])} entries, expected {_queue.N_QS}: "
                "written by an incompatible version of edmd2d")
        tables = []
        for name in ("S", "E"):  # (back on 64-byte boundaries: a copy may not be)
            rows, width = state[name].shape
            table = aligned_rows(rows, width, state[name].dtype)
            table[:] = state.pop(name)
            tables.append(table)
        state.update(self.tables(*tables, *(state.pop(name) for name in
                                            ("hv", "qhead", "qs", "qf"))))
        state["listener"] = None
        # (Saved before disks could rest: no supports, and two counters fewer.)
        state.setdefault("rest_supports", None)
        state.setdefault("rest_frozen", None)
        state.setdefault("rest_t_static", None)
        state.setdefault("wall_open", np.zeros(len(state["walls"]), bool))
        for name in ("shear_clock", "shear_slides", "shear_flights", "shear_idle"):
            state.setdefault(name, None)  # (saved before boxes could be sheared)
        state.setdefault("helfand_sums", None)  # (saved before the Helfand moments)
        state.setdefault("edits", 0)
        state.setdefault("wide", None)  # (saved before wide disks: the uniform grid)
        state.setdefault("grid_mode", "auto")
        for name in ("rough_w", "rough_angle", "rough_t", "rough_inv_inertia"):
            state.setdefault(name, None)  # (saved before disks could spin)
        state["log_capacity"] = 0  # (a copy does not stream)
        wacc = state["wacc"]
        if wacc.shape[1] < _layout.N_WACC:  # (saved before segments could move)
            state["wacc"] = np.concatenate(
                [wacc, np.zeros((len(wacc), _layout.N_WACC - wacc.shape[1]))], axis=1)
        acc = state["acc"]
        if len(acc) < _layout.N_ACC:  # (saved before gravity could be changed)
            state["acc"] = np.concatenate([acc, np.zeros(_layout.N_ACC - len(acc))])
        counts = state["counts"]
        if len(counts) < _layout.N_COUNTS:
            state["counts"] = np.concatenate(
                [counts, np.zeros(_layout.N_COUNTS - len(counts), np.int64)])
        vars(self).update(state)
        if "rest_check" not in state:  # (saved before groups of disks could rest)
            self.rest_check = self.first_rest_check()

    # ------------------------------------------------------------------ grid
    def build_grid(self, pos: np.ndarray, dmax: float, cell_size: float | None) -> None:
        """(Re)build the grid for disks of largest diameter ``dmax`` at ``pos`` (stored
        positions, inside the box): the cell geometry, each disk's cell, the cells'
        lists and the wall segments listed per cell.  Cells are at least ``dmax`` wide
        (``cell_size``, if given, is at least that); the default widens them in dilute
        systems to keep at most about two cells per disk.  The kept candidates and the
        queue are not touched: predict every disk afresh after a rebuild.

        Under growth the grid holds until the largest diameter reaches ``dmax``
        (:meth:`time_of_diameter` of it)."""
        self.grid_dmax = float(dmax)
        width, height = self.box.width, self.box.height
        # Under growth the grid holds the disks grown by ``scale`` (their largest to
        # ``dmax``); so does a grid with wide disks, whose cells then hold the narrow
        # disks grown as much, and whose footprints have room for the wide ones.
        grown = self.growth_factor(self.time)
        scale = dmax / (2.0 * float(self.S[:, _layout.R].max()) * grown)
        narrow = self.narrow_diameter(cell_size, self.S[:, _layout.R] * (grown * scale))
        largest = dmax
        if narrow is not None:  # (the cells hold the narrow disks; wider ones are wide)
            dmax = narrow
        side_min = dmax * (1.0 + _CELL_MARGIN)
        if cell_size is None:
            side = max(side_min, math.sqrt(width * height / (2.0 * len(pos))))
        else:
            side = max(cell_size, side_min)
        ncx = max(1, int(width // side))
        ncy = max(1, int(height // side))
        if self.shear is not None:
            # Four columns and three rows at least (see _engine/sheared.py).
            # (With wide disks, so that two disks in contact are nearer than half a
            # width: the collision takes the nearest image across the boundary.)
            ncx = max(ncx, 4)
            ncy = max(ncy, 3)
            if (min(width / ncx, height / ncy) < side_min
                    or min(width / 4.0, height / 3.0) < largest * (1.0 + _CELL_MARGIN)):
                with about("shear_rate"):
                    raise ValueError(
                        f"a sheared box must be more than 4 largest diameters wide and "
                        f"more than 3 high, got {width:g} x {height:g} for diameter "
                        f"{largest:g}")
        periodic = self.box.periodic
        old_ncx = int(vars(self)["gi"][0]) if "gi" in vars(self) else 0
        self.gi = np.array([ncx, ncy, int(periodic[0]), int(periodic[1])], np.int64)
        self.gf = np.array([width, height, width / ncx, height / ncy], np.float64)
        if self.shear is not None and ncx != old_ncx:
            self.start_shear(self.shear.offset if self.shear_clock is None
                             else self.shear_offsets()[1])
        self.head = np.empty(ncx * ncy, np.int32)
        _grid.build_cells(pos, self.gi, self.gf, self.E[:, _layout.CELL], self.head,
                          self.nxt, self.prv)
        reach = 0.5 * dmax + _CELL_MARGIN * (side + dmax)
        closed = np.flatnonzero(~self.wall_open)
        # (A moving segment is listed along its whole path: from one extreme, swept
        # to the other.)
        wa, wb, sweep = self.wa, self.wb, None
        moving = self.families.get("moving_walls")
        if moving is not None:
            low, high = moving.extremes()
            wa, wb, sweep = wa + low, wb + low, high - low
        if len(closed) == len(self.wa):
            self.wstart, self.wwall, self.wsx, self.wsy = _grid.bucket_walls(
                wa, wb, self.gi, self.gf, reach, sweep)
        else:
            # The closed segments alone, listed under their own indices (with every
            # segment open, still one empty list per cell: the engine looks them up
            # wherever there are segments).
            start, wall, sx, sy = _grid.bucket_walls(
                wa[closed], wb[closed], self.gi, self.gf, reach,
                None if sweep is None else sweep[closed])
            if len(closed) == 0:
                start = np.zeros(ncx * ncy + 1, np.int32)
            self.wstart, self.wwall, self.wsx, self.wsy = start, closed[wall], sx, sy
        self.wide = None
        if narrow is not None:
            # (With disks at rest the footprint also holds the supports within the
            # rest's gap, so that the disks near one another on the grid are those
            # that can hold one another up: see _engine/wide.py, ``near``.)
            rest = self.families.get("resting")
            self.wide = _wide.allocate(self.S[:, _layout.R] * (grown * scale), narrow,
                                       self.gi, self.gf,
                                       reach + (0.0 if rest is None else rest.gap),
                                       sheared=self.shear is not None)
            _wide.fill(self.S, self.E, self.gi, self.gf, self.wide, self.head, self.nxt,
                       self.prv, grown, self.column_shift())

    def narrow_diameter(self, cell_size: float | None, radii: np.ndarray) -> float | None:
        """The largest of the diameters ``2 radii`` that the grid's cells are sized
        for, where disks wider than it are listed in their footprints
        (:mod:`._engine.wide`); ``None`` for the uniform grid (a ``cell_size`` given,
        or radii too alike for it to pay)."""
        if self.grid_mode == "uniform" or cell_size is not None:
            return None
        box = self.box
        rest = self.families.get("resting")
        narrow = _wide.choose(radii, box.width, box.height, box.periodic, _CELL_MARGIN,
                              force=self.grid_mode == "wide",
                              extra=0.0 if rest is None else rest.gap,
                              sheared=self.shear is not None)
        if narrow is None and self.grid_mode == "wide" and "gi" not in vars(self):
            # (Refused when the simulation is made; a rebuild later, under growth that
            # made the footprints too wide for the box, falls back to the uniform grid.)
            with about("grid"):
                raise ValueError("grid='wide' needs a periodic box longer than the "
                                 "widest disk's footprint (its diameter, a narrow "
                                 "diameter and two cells)")
        return narrow

    def first_overlap_across(self, pos: np.ndarray, rad: np.ndarray) -> tuple:
        """Under shear: the first pair ``(i, j, distance)`` of a disk of the bottom row
        of cells and one of the top row's images below it (at ``x - offset``) that
        overlap (``(-1, -1, 0.0)``: none), every such pair examined."""
        ncx = int(self.gi[0])
        row = self.E[:, _layout.CELL] // ncx
        low = np.flatnonzero(row == 0)
        high = np.flatnonzero(row == int(self.gi[1]) - 1)
        width = self.box.width
        dx = pos[low, None, 0] - (pos[None, high, 0] - self.shear_offsets()[0])
        dx -= width * np.floor(dx / width + 0.5)
        dy = pos[low, None, 1] - (pos[None, high, 1] - self.box.height)
        dist = np.hypot(dx, dy)
        bad = np.argwhere(dist < (rad[low, None] + rad[None, high]) * (1.0 - OVERLAP_TOL))
        if len(bad) == 0:
            return -1, -1, 0.0
        a, b = bad[0]
        return int(low[a]), int(high[b]), float(dist[a, b])

    def check_overlaps(self, pos: np.ndarray, rad: np.ndarray) -> None:
        """Refuse disks (at ``pos``, in row order, on the grid) that overlap each
        other, their periodic images or a wall segment."""
        i, j, dist = _overlap.first_disk_overlap(
            pos, rad, self.gi, self.gf, self.E[:, _layout.CELL], self.head, self.nxt,
            OVERLAP_TOL, self.shear is None,
        )
        if i < 0 and self.shear is not None:
            i, j, dist = self.first_overlap_across(pos, rad)
        if i < 0 and self.wide is not None:
            offset = 0.0 if self.shear is None else self.shear_offsets()[0]
            i, j, dist = _wide.first_overlap(pos, rad, self.gi, self.gf, self.head,
                                             self.nxt, self.wide, OVERLAP_TOL,
                                             self.column_shift(), offset)
        if i >= 0:
            what = "its own periodic image" if i == j else f"disk {j}"
            contact = rad[i] + rad[j]
            raise ValueError(
                f"positions: disk {i} overlaps {what} (centre distance {dist:.17g} < "
                f"sum of radii {contact:.17g}, by {1.0 - dist / contact:.3g} of it)"
            )
        if not self.walls:
            return
        wa, wb = self.wall_ends()
        i, w, dist = _overlap.first_wall_overlap(
            pos, rad, self.gf, self.E[:, _layout.CELL], wa, wb,
            self.wstart, self.wwall, self.wsx, self.wsy, OVERLAP_TOL,
        )
        if i < 0 and self.wide is not None:
            i, w, dist = self.first_wide_wall_overlap(pos, rad)
        if i >= 0:
            raise ValueError(
                f"positions: disk {i} overlaps walls[{w}] (distance {dist:.17g} < "
                f"radius {rad[i]:.17g}, by {1.0 - dist / rad[i]:.3g} of it)"
            )

    def first_wide_wall_overlap(self, pos: np.ndarray, rad: np.ndarray) -> tuple:
        """The first wide disk and wall segment (or an image of it) that overlap, as
        ``(i, w, distance)`` (``(-1, -1, 0.0)``: none): every pair examined (a wide
        disk reaches beyond the cell whose segments the grid's check reads)."""
        assert self.wide is not None
        wide = self.wide.disk
        starts, ends = self.wall_ends()
        a, b = starts[None, :, :], ends[None, :, :]
        shifts = [(sx, sy) for sx in ((-1, 0, 1) if self.box.periodic[0] else (0,))
                  for sy in ((-1, 0, 1) if self.box.periodic[1] else (0,))]
        for sx, sy in shifts:
            p = pos[wide, None, :] - np.array([sx * self.box.width, sy * self.box.height])
            ab = b - a
            u = np.clip(np.einsum("ijk,ijk->ij", p - a, ab)
                        / np.einsum("ijk,ijk->ij", ab, ab), 0.0, 1.0)
            dist = np.hypot(*np.moveaxis(p - (a + u[..., None] * ab), -1, 0))
            bad = np.argwhere((dist < rad[wide, None] * (1.0 - OVERLAP_TOL))
                              & ~self.wall_open[None, :])
            if len(bad):
                k, w = bad[0]
                return int(wide[k]), int(w), float(dist[k, w])
        return -1, -1, 0.0

    # ------------------------------------------------------------------ growth
    def growth_factor(self, t: float) -> float:
        """The factor by which every radius at ``t`` exceeds its stored value (1 without
        growth; the engine's ``scan.growth_factor``)."""
        growth = self.growth_bundle()
        if growth is None:
            return 1.0
        return 1.0 + growth.rate * (t - growth.t0)

    def grid_diameter(self, dmax: float) -> float:
        """The largest diameter to build the grid for, the current one being ``dmax``:
        that one, or under growth a margin above it (but within the box)."""
        if self.growth is None:
            return dmax
        return min(dmax * _GROWTH_GRID_SLACK, max(dmax, self.outgrow_diameter()))

    def outgrow_diameter(self) -> float:
        """The largest diameter the box holds: a disk that wide would overlap its own
        periodic image, or fill the box between its walls."""
        return min(self.box.width, self.box.height) * (1.0 - OVERLAP_TOL)

    def time_of_diameter(self, diameter: float) -> float:
        """Under growth, the time at which the largest diameter reaches ``diameter``."""
        growth = self.growth_bundle()
        d0 = 2.0 * float(self.S[:, _layout.R].max())
        return growth.t0 + (diameter / d0 - 1.0) / growth.rate  # (rate > 0: physics.Growth)

    def regrid(self) -> None:
        """Bring every disk to the current time, rebuild the grid (under growth: for
        the disks' growth ahead) and predict every disk afresh."""
        self.sync_all()
        dmax = 2.0 * float(self.S[:, _layout.R].max()) * self.growth_factor(self.time)
        self.build_grid(self.S[:, _layout.X:_layout.Y + 1], self.grid_diameter(dmax),
                        self.cell_size)
        self.predict_all()

    def set_growth(self, growth) -> None:
        """Fix the radii at their present values, then let them grow at ``growth``
        (a checked ``physics.Growth``, or ``None``) from now on."""
        self.S[:, _layout.R] = self.S[:, _layout.R] * self.growth_factor(self.time)
        self.growth = None if growth is None else np.array([growth.rate, self.time])
        if growth is None:
            self.predict_all()
        else:
            self.regrid()  # (a grid with room to grow)

    # ------------------------------------------------------------------ editing
    def place(self, pos: np.ndarray, rest: np.ndarray) -> None:
        """Move every disk to ``pos`` (checked, user order) at the current time, with
        the supports ``rest``; rebuild the grid and predict every disk afresh."""
        self.wake_all()
        self.sync_all()
        self.edits += 1
        self.S[:, _layout.X:_layout.Y + 1] = pos[self.order]
        _layout.support_view(self.S)[:] = rest[self.order]
        self.image[:] = 0
        dmax = 2.0 * float(self.S[:, _layout.R].max()) * self.growth_factor(self.time)
        self.build_grid(self.S[:, _layout.X:_layout.Y + 1], self.grid_diameter(dmax),
                        self.cell_size)
        self.predict_all()

    def set_velocities(self, vel: np.ndarray, rest: np.ndarray) -> None:
        """Give every disk the velocity ``vel`` (checked, user order) at the current
        time, with the supports ``rest``, and predict every disk afresh."""
        self.wake_all()
        self.sync_all()
        self.edits += 1
        self.S[:, _layout.VX:_layout.VY + 1] = vel[self.order]
        _layout.support_view(self.S)[:] = rest[self.order]
        self.predict_all()  # every event and kept candidate is recomputed

    # ------------------------------------------------------------------ moving walls
    def check_motions(self, families: dict, growth) -> None:
        """Refuse what moving wall segments do not combine with (yet)."""
        moving = families.get("moving_walls")
        if moving is None:
            return
        with about("wall_motions"):
            others = {"growth": growth, "shear": families.get("shear")}
            for name, other in others.items():
                if other is not None:
                    raise ValueError(f"moving wall segments do not combine with {name}")
            if "resting" in families:
                raise ValueError("moving wall segments do not hold disks at rest (yet): "
                                 "under gravity with an inelastic model, give "
                                 "resting=False")
            if self.model is not None:
                hot = np.flatnonzero((self.model.wall_kt[4:] > 0.0)
                                     & (moving.kind != _layout.FIXED))
                if len(hot):
                    raise ValueError(f"walls[{int(hot[0])}] both moves and is heated: a "
                                     f"moving segment cannot be heated")

    def motion_bundle(self):
        """The engine's family of moving wall segments: ``None`` or a ``layout.Motion``."""
        moving = self.families.get("moving_walls")
        return None if moving is None else _layout.Motion(moving.kind, moving.par)

    def wall_ends(self, t: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The wall segments' start and end points at time ``t`` (default now), each of
        shape (S, 2): where they were given, shifted by their motions."""
        moving = self.families.get("moving_walls")
        if moving is None:
            return self.wa, self.wb
        shift = moving.shifts(self.time if t is None else t)
        return self.wa + shift, self.wb + shift

    def closed_walls(self, oscillating: bool = True) -> tuple:
        """The wall segments that are not open (the bodies a disk can meet), where they
        are now; without the oscillating ones for ``oscillating=False``."""
        walls = self.walls
        skip = np.array(self.wall_open, bool)
        moving = self.families.get("moving_walls")
        if moving is not None:
            walls = tuple(Wall(a, b) for a, b in zip(*self.wall_ends()))
            if not oscillating:
                skip |= moving.kind == _layout.SINE
        return tuple(w for w, out in zip(walls, skip) if not out)

    def walls_holding_still(self) -> tuple:
        """The segments on which a disk at rest, pressed on by gravity, would bounce
        without end at one instant (see :func:`edmd2d._checks.resting`): the closed
        ones except those that oscillate, which throw a disk off at the parting speed
        at least (``_engine/moving.py``)."""
        return self.closed_walls(oscillating=False)

    def set_wall_open(self, k: int, is_open: bool) -> None:
        """Open wall segment ``k`` (no disk meets it any more; every disk at rest
        wakes, since it may have held some) or close it again (checked by the caller:
        no disk overlaps it), and predict every disk afresh."""
        if is_open:
            self.wake_all()
        self.wall_open[k] = is_open
        self.regrid()

    def set_gravity(self, gravity: np.ndarray, rest: np.ndarray, families: dict) -> None:
        """Change gravity to ``gravity`` (checked, not zero) at the current time, with
        the box walls ``rest`` that disks now rest on (user order) and the physics
        ``families`` that depend on it: every disk at rest wakes, and the change of
        the potential energy is booked (``A_GRAVITY``)."""
        self.wake_all()
        self.sync_all()  # (under the old gravity)
        movable = self.invm > 0
        r = self.unwrapped()[movable]
        self.acc[_layout.A_GRAVITY] -= float(dot(self.mass[movable],
                                                 dot(r, gravity - self.gravity)))
        self.gravity = np.array(gravity, np.float64)
        self.families = families
        _layout.support_view(self.S)[:] = rest[self.order]
        self.rest_check = self.first_rest_check()
        self.predict_all()

    def sync_all(self) -> None:
        """Move every stored position to the current time (local clocks all equal);
        under shear, the flights up to now join the integrals of the kinetic stress
        first, as the engine adds each flight when it moves a disk."""
        if self.shear_flights is not None:
            self.shear_flights[:] = self.kinetic_stress_integral()
        if self.helfand_sums is not None:
            self.helfand_sums[:_helfand.H_CX] += _helfand.pending(self.time, self.S,
                                                                  self.invm)
        _flight.drift_all(self.time, self.S, self.gravity_bundle())

    # ------------------------------------------------------------------ readouts
    def to_user(self, internal: np.ndarray) -> np.ndarray:
        """Rows in the user's disk order: a new, read-only array (editing it could not
        change the simulation, so an edit fails instead of passing silently)."""
        out = np.empty_like(internal)
        out[self.order] = internal
        out.flags.writeable = False
        return out

    def positions(self) -> np.ndarray:
        """Centres at :attr:`time`, wrapped into the box, in internal row order."""
        out = np.empty((len(self.S), 2))
        _flight.synchronized_positions(self.time, self.S, self.gi, self.gf, out,
                                       self.gravity_bundle())
        return out

    def unwrapped(self) -> np.ndarray:
        """Unwrapped centres at :attr:`time`, in internal row order; under shear the
        path through the sliding images, ``x + image_x width + image_y D`` with ``D``
        the images' whole offset (:meth:`shear_offsets`)."""
        out = (_flight.positions_at(self.time, self.S, self.gravity_bundle())
               + self.image * self.box.size)
        if self.shear is not None:
            out[:, 0] += self.image[:, 1] * self.shear_offsets()[1]
        return out

    def velocities(self) -> np.ndarray:
        """Velocities at :attr:`time`, in internal row order (a new array)."""
        return _flight.velocities_at(self.time, self.S, self.gravity_bundle())

    def accumulators(self) -> dict:
        """Raw sums since creation: the collision virial ``sum J |r_ij|``, its tensor's
        components ``sum J |r_ij| n_x^2``, ``n_y^2`` and ``n_x n_y`` (``n`` the contact
        normal), and the impulses on the walls (``J`` the impulse magnitude of a
        contact):

        - ``"box_impulse"``, shape (4,): ``sum J`` on each box wall (x=0, x=width, y=0,
          y=height);
        - ``"segment_impulse"``: ``sum J`` over all wall segments;
        - ``"segment_impulses"``, shape (S, 2): the impulse vector each segment received,
          ``sum -J n`` (``n`` the unit normal from the segment to the disk);
        - ``"segment_side_impulses"``, shape (S, 2): ``sum J`` over the contacts on each
          side of each segment, left then right (the left side lies to the left going
          from ``start`` to ``end``: counterclockwise polygons have their inside there);
        - ``"segment_end_impulses"``, shape (S,): ``sum J`` at each segment's end points;
        - ``"segment_contacts"``, shape (S,): contact events of each segment (as counted
          in ``counts.wall_collisions``).

        At a heated wall ``J`` is the normal component of the momentum change (the
        tangential one is in ``"segment_impulses"`` for a segment).

        Over all segments, the side and end-point sums add up to ``"segment_impulse"``
        (to rounding)."""
        a = self.acc
        w = self.wacc
        return {
            "virial": float(a[_layout.A_VIRIAL]),
            "virial_xx": float(a[_layout.A_VIRIAL_XX]),
            "virial_yy": float(a[_layout.A_VIRIAL_YY]),
            "virial_xy": float(a[_layout.A_VIRIAL_XY]),
            "box_impulse": a[_layout.A_BOX:_layout.A_BOX + 4].copy(),
            "segment_impulse": float(a[_layout.A_SEGMENTS]),
            "segment_impulses": w[:, _layout.W_FX:_layout.W_FY + 1].copy(),
            "segment_side_impulses": w[:, _layout.W_LEFT:_layout.W_RIGHT + 1].copy(),
            "segment_end_impulses": w[:, _layout.W_ENDS].copy(),
            "segment_contacts": w[:, _layout.W_CONTACTS].astype(np.int64),
        }

    # ------------------------------------------------------------------ event log
    def stream(self, callback, capacity: int) -> None:
        """Hand every processed event to ``callback`` in batches of up to ``capacity``
        (checked); ``None`` stops the stream.  The events logged so far go to the
        previous callback first."""
        self.drain()
        self.listener = callback
        self.set_log(0 if callback is None else capacity)

    def set_log(self, capacity: int) -> None:
        """An empty log that is handed over after ``capacity`` events (0: none); where
        disks come to rest, with room beyond for the rests and wakes of one event
        (``layout.Log``)."""
        size = capacity
        if capacity > 0 and self.rest_supports is not None:
            size += len(self.S) + 16
        self.log_capacity = capacity
        self.log_t = np.zeros(size)
        self.log_e = np.zeros((size, 3), np.int64)
        self.log_j = np.zeros(size)
        self.log_n = np.zeros(1, np.int64)

    def log_bundle(self):
        return _layout.Log(self.log_t, self.log_e, self.log_n, self.log_j,
                           self.log_capacity)

    def log_changes(self, kind: int, rows: np.ndarray, velocities: np.ndarray) -> None:
        """Log the rests or wakes (``kind``) of the disks ``rows`` at :attr:`time`,
        with the velocities they lose or regain, as the engine does (``resting``),
        and hand the log over."""
        if self.log_capacity == 0 or len(rows) == 0:
            return
        if self.log_n[0] >= self.log_capacity:
            self.drain()
        k = int(self.log_n[0])
        end = k + len(rows)  # (within the room beyond the capacity: at most every disk)
        self.log_t[k:end] = self.time
        self.log_e[k:end, 0] = kind
        self.log_e[k:end, 1] = self.order[rows]
        self.log_e[k:end, 2] = -1
        self.log_j[k:end] = np.hypot(*velocities.T) / self.invm[rows]
        self.log_n[0] = end
        self.drain()  # (changes made from Python are handed over at once)

    def drain(self) -> None:
        """Hand the events in the engine's log to the listener and empty it."""
        n = int(self.log_n[0])
        listener = self.listener
        if n == 0 or listener is None:
            return
        # (The log may hold more than its capacity: the rests and wakes of its last
        # event.  Batches keep to the capacity; all are made before the listener sees
        # any, since it may stop or change the stream.)
        batches = []
        for a in range(0, n, self.log_capacity):
            b = min(a + self.log_capacity, n)
            batch = np.empty(b - a, dtype=EVENT_DTYPE)
            batch["time"] = self.log_t[a:b]
            batch["kind"] = np.array(EVENT_KINDS)[np.searchsorted(_KIND_CODES,
                                                                  self.log_e[a:b, 0])]
            batch["disk"] = self.log_e[a:b, 1]
            batch["partner"] = self.log_e[a:b, 2]
            batch["impulse"] = self.log_j[a:b]
            batches.append(batch)
        self.log_n[0] = 0
        for batch in batches:
            listener(batch)

    def record_events(self, capacity: int = 1 << 16) -> None:
        """Record every disk, wall and thermostat event (for :meth:`recorded_events`)."""
        self.recorded = []
        self.stream(self.recorded.append, capacity)

    def recorded_events(self) -> list[tuple[float, str, int, int]]:
        """Recorded events as ``(time, kind, disk, partner)``; kind is "disk", "wall"
        (partner: wall index), "box" (partner: 0..3 for x=0, x=width, y=0, y=height),
        "thermostat", "rest" or "wake" (partner -1)."""
        self.drain()
        return [(float(e["time"]), str(e["kind"]), int(e["disk"]), int(e["partner"]))
                for batch in self.recorded for e in batch]

    # ------------------------------------------------------------------ engine calls
    def run(self, t_end, max_collisions, max_events, out, info, mode):
        """One call of the event loop, with the state in its bundles (see loop.py).

        The physics families not in use are ``None``; a model hands over restitution
        and the TC model always (a model of heated walls or a thermostat alone runs
        its contacts with ``e = 1`` through them), the others as it uses them."""
        families = self.model_families()
        rest = self.rest_bundle()
        if rest is not None and families.contact is not None:
            # (Where disks come to rest, the box walls hold disks by resting.slide, not by
            # the TC model's hold.)
            families = families._replace(
                contact=families.contact._replace(soft=rest.soft, hold=0.0))
        return _loop.run(
            _layout.Control(t_end, max_collisions, max_events, mode, out, info),
            _layout.Particles(self.S, self.E, self.stamp, self.nxt, self.prv,
                              self.qt, self.tcand, self.invm, self.image, self.order),
            _layout.Grid(self.gi, self.gf, self.head),
            _layout.Walls(self.wa, self.wb, self.wstart, self.wwall, self.wsx,
                          self.wsy),
            _layout.Calendar(self.hv, self.qhead, self.qs, self.qf),
            _layout.Tallies(self.counts, self.acc, self.wacc),
            self.log_bundle(),
            families.contact, families.heated, families.thermostat, families.uniforms,
            self.gravity_bundle(), self.growth_bundle(), rest, self.shear_bundle(),
            None if self.helfand_sums is None else _layout.Helfand(self.helfand_sums),
            self.rough_bundle(), self.wide, self.motion_bundle(),
        )

    def rough_bundle(self):
        """The engine's family of rough disks: ``None`` or a ``layout.Rough``."""
        rough = self.families.get("rough")
        if rough is None:
            return None
        w, angle, t, inv = self.rough_w, self.rough_angle, self.rough_t, self.rough_inv_inertia
        assert w is not None and angle is not None and t is not None and inv is not None
        return _layout.Rough(rough.beta, rough.friction, rough.wall_beta, rough.wall_friction,
                             w, angle, t, inv)

    def angles(self) -> np.ndarray:
        """Rough disks: each disk's angle at :attr:`time`, in internal row order."""
        bundle = self.rough_bundle()
        assert bundle is not None
        return bundle.angle + bundle.w * (self.time - bundle.t_angle)

    def set_angular_velocities(self, w: np.ndarray) -> None:
        """Rough disks: give every movable disk the angular velocity ``w`` (checked,
        user order) at the current time, its angle read forward to now first.  No
        event changes: contact times do not depend on the spins."""
        assert self.rough_w is not None and self.rough_angle is not None
        assert self.rough_t is not None and self.rough_inv_inertia is not None
        self.rough_angle[:] = self.angles()
        self.rough_t[:] = self.time
        self.rough_w[:] = np.where(self.rough_inv_inertia > 0, w[self.order], 0.0)

    def rest_bundle(self):
        """The engine's family of disks at rest: ``None`` or a ``layout.Rest``."""
        supports, frozen, t_static = self.rest_supports, self.rest_frozen, self.rest_t_static
        if supports is None or frozen is None or t_static is None:
            return None
        rest = self.families["resting"]
        radii = self.S[:, _layout.R]
        room = _resting.candidates(float(radii.max()), float(radii.min()))
        return _layout.Rest(rest.speed, rest.gap, rest.wake, rest.press, rest.soft,
                            rest.instant, supports,
                            frozen, t_static,
                            np.empty(len(self.S), np.int32),
                            np.empty(room, np.int64), np.empty(room),
                            np.empty((2, _wide.near_rows(len(self.S), self.gi, self.wide,
                                                         len(self.wa)), 3), np.int32),
                            self.log_bundle(), self.order, self.wide)

    def first_rest_check(self, after: float | None = None) -> float | None:
        """The first time after ``after`` (default :attr:`time`) at which groups of
        disks that hold one another up are looked for: the multiples of
        ``Resting.every`` (``None`` without resting)."""
        rest = self.families.get("resting")
        if rest is None:
            return None
        t = self.time if after is None else after
        check = rest.every * (math.floor(t / rest.every) + 1.0)
        return check if check > t else check + rest.every  # (whatever the rounding)

    def model_families(self):
        """The engine families of the model (``layout.ModelFamilies``, all ``None``
        without a model)."""
        return _NO_MODEL if self.model is None else self.model.engine_families()

    def rest_groups(self) -> int:
        """Put to rest, at :attr:`time`, the groups of slow flying disks that hold one
        another up (``_balance.py``); returns how many disks came to rest."""
        rest = self.families["resting"]
        families = self.model_families()
        cold = np.ones(4 + len(self.wa), bool)
        if families.heated is not None:
            cold = families.heated.kt <= 0.0
        cold[4:] &= ~self.wall_open  # (an open segment holds nothing)
        vel = self.velocities()
        support = _layout.support_view(self.S)
        static = (support & _layout.RESTING != 0) | (
            (self.invm == 0.0) & (vel == 0.0).all(axis=1))
        rows, supports = _balance.held_groups(
            self.positions(), vel, self.S[:, _layout.R], self.mass, static,
            self.invm > 0.0, self.box, list(zip(self.wa, self.wb)), cold[:4], cold[4:],
            self.gravity, rest.speed, rest.gap, _balance.TOL)
        if len(rows) == 0:
            return 0
        if self.log_n[0] >= self.log_capacity > 0:
            self.drain()  # (the log's room beyond its capacity is for these rests)
        bundle = self.rest_bundle()
        bundle.supports[rows] = supports
        bundle.stack[:len(rows)] = rows
        _resting.rest_group(self.time, len(rows), self.S, self.E, self.tcand, self.stamp,
                            self.qt, self.hv, self.qhead, self.qs, self.qf, self.invm,
                            self.gi, self.head, self.nxt, self.acc, self.counts,
                            self.gravity_bundle(), bundle)
        if self.log_n[0] >= self.log_capacity > 0:
            self.drain()
        return len(rows)

    def impact(self, seeds, stop: bool = False) -> bool:
        """Resolve, at :attr:`time`, the contacts of the flying disks joined to the
        internal rows ``seeds`` as one perfectly inelastic impact (``_impacts.py``):
        their velocities change, the impulses count in the virial and the walls'
        tallies, one collision per contact that takes an impulse, and the kinetic
        energy removed is dissipated.  With ``stop`` (the group stalled again at that
        instant) they stop instead.  Then the groups of disks that hold one another
        up come to rest (:meth:`rest_groups`).  Returns whether any velocity changed."""
        vel = self.velocities()
        support = _layout.support_view(self.S)
        static = (support & _layout.RESTING != 0) | (
            (self.invm == 0.0) & (vel == 0.0).all(axis=1))
        flying = ~static & (self.invm > 0.0)
        families = self.model_families()
        cold = np.ones(4 + len(self.wa), bool)
        if families.heated is not None:
            cold = families.heated.kt <= 0.0
        cold[4:] &= ~self.wall_open  # (an open segment holds nothing)
        ends = [(a, b) if cold[4 + k] else (np.full(2, np.nan), np.full(2, np.nan))
                for k, (a, b) in enumerate(zip(self.wa, self.wb))]
        pos = self.positions()
        found = _impacts.group(seeds, pos, self.S[:, _layout.R], flying, static,
                               self.box, ends, cold[:4])
        if found is None:
            return False
        members, a, b, side, segment, normal, distance = found
        if len(a) == 0:
            return False
        if stop:
            # (No impulses are counted: the static bodies took what the members lost,
            # as from a wedged disk.)
            after = np.zeros((len(members), 2))
            impulse = np.zeros(len(a))
            lost = 0.5 * float(np.sum((vel[members] ** 2).sum(axis=1) / self.invm[members]))
        else:
            after, impulse, lost = _impacts.resolve(members, vel, self.invm, a, b, normal)
        loaded = impulse > 0.0
        added = _impacts.lift(members, after, self.invm, a, b, side, normal, self.gravity,
                              self.families["resting"].soft)
        if not loaded.any() and added == 0.0 and not stop:
            return False
        lost -= added
        acc = self.acc
        acc[_layout.A_DISSIPATED] += lost
        disk = b != -1
        j = impulse[disk] * distance[disk]
        nx, ny = normal[disk, 0], normal[disk, 1]
        acc[_layout.A_VIRIAL] += float(j.sum())
        acc[_layout.A_VIRIAL_XX] += float((j * nx * nx).sum())
        acc[_layout.A_VIRIAL_YY] += float((j * ny * ny).sum())
        acc[_layout.A_VIRIAL_XY] += float((j * nx * ny).sum())
        for c in np.flatnonzero((side >= 0) & loaded):
            acc[_layout.A_BOX + side[c]] += impulse[c]
        for c in np.flatnonzero((segment >= 0) & loaded):
            k = int(segment[c])
            acc[_layout.A_SEGMENTS] += impulse[c]
            self.wacc[k, _layout.W_FX] -= impulse[c] * normal[c, 0]
            self.wacc[k, _layout.W_FY] -= impulse[c] * normal[c, 1]
            self.wacc[k, _layout.W_CONTACTS] += 1.0
            # (The side from the normal itself, which the periodic images leave alone:
            # along the segment at an end point, across it on a side.)
            along = np.subtract(self.wb[k], self.wa[k])
            along /= np.hypot(*along)
            n = normal[c]
            if abs(float(n @ along)) > 1e-9:
                col = _layout.W_ENDS
            else:
                col = (_layout.W_LEFT if n[1] * along[0] - n[0] * along[1] >= 0.0
                       else _layout.W_RIGHT)
            self.wacc[k, col] += impulse[c]
        walls = (side >= 0) | (segment >= 0)
        self.counts[_layout.C_COLLISIONS] += int((loaded & ~walls).sum())
        self.counts[_layout.C_WALL] += int((loaded & walls).sum())
        self.log_impact(a[loaded], b[loaded], side[loaded], segment[loaded],
                        impulse[loaded])
        model = self.model
        if model is not None:
            model.streak[members] = 0
            model.t_last[members] = self.time
        bundle = self.rest_bundle()
        bundle.stack[:len(members)] = members
        _resting.impact_group(self.time, len(members), np.ascontiguousarray(after),
                              self.S, self.E, self.tcand, self.stamp, self.qt, self.hv,
                              self.qhead, self.qs, self.qf, self.invm, self.gi, self.head,
                              self.nxt, self.gravity_bundle(), bundle)
        self.rest_groups()
        return True

    def log_impact(self, a, b, side, segment, impulse) -> None:
        """Log the contacts of an impact at :attr:`time` as collisions (a pair, a disk
        at rest), box-wall or segment contacts, each with its impulse."""
        if self.log_capacity == 0 or len(a) == 0:
            return
        if self.log_n[0] >= self.log_capacity:
            self.drain()
        for c in range(len(a)):
            if self.log_n[0] >= len(self.log_t):
                self.drain()
            k = int(self.log_n[0])
            if side[c] >= 0:
                kind, partner = _layout.BOX, int(side[c])
            elif segment[c] >= 0:
                kind, partner = _layout.SEGMENT, int(segment[c])
            else:
                row = int(b[c]) if b[c] >= 0 else -2 - int(b[c])
                kind, partner = _layout.DISK, int(self.order[row])
            self.log_t[k] = self.time
            self.log_e[k, 0] = kind
            self.log_e[k, 1] = self.order[a[c]]
            self.log_e[k, 2] = partner
            self.log_j[k] = impulse[c]
            self.log_n[0] = k + 1
        self.drain()

    def wake_all(self) -> None:
        """Wake every disk at rest (before its velocity, its position or the forces on
        it are set): each resumes the velocity it came to rest with (see
        ``_engine/resting.py``); the caller predicts every disk afresh."""
        supports, frozen_all = self.rest_supports, self.rest_frozen
        if supports is None or frozen_all is None:
            return
        support = _layout.support_view(self.S)
        resting = support & _layout.RESTING != 0
        self.S[resting, _layout.T] = self.time
        frozen = frozen_all[resting]
        self.S[resting, _layout.VX:_layout.VY + 1] = frozen
        self.acc[_layout.A_DISSIPATED] -= float(
            0.5 * ((frozen ** 2).sum(axis=1) / self.invm[resting]).sum())
        support[resting] = 0
        supports[:] = -1
        frozen_all[:] = 0.0
        self.counts[_layout.C_WAKES] += int(resting.sum())
        self.log_changes(_layout.WAKE, np.flatnonzero(resting), frozen)  # (once woken)

    def gravity_bundle(self):
        """The engine's gravity family: ``None`` (straight-line flight) or a
        ``layout.Gravity`` holding this state's inverse masses and supports."""
        g = self.gravity
        return (None if g is None else
                _layout.Gravity(float(g[0]), float(g[1]), self.invm,
                                _layout.support_view(self.S)))

    # ------------------------------------------------------------------ shear
    @property
    def shear(self):
        """The family of Lees-Edwards boundaries (``physics.Shear``), or ``None``."""
        return self.families.get("shear")

    def start_shear(self, unreduced: float) -> None:
        """Start the clock of the images' offset at :attr:`time`, where the offset not
        reduced by box widths is ``unreduced`` (0 when the shear starts): the slides
        since it was 0 (whole cell widths, rounded towards the direction of flow),
        when the next is due, and the offset at the last (see _engine/sheared.py).
        (An offset at a cell's edge counts as the start of the cell the images slide
        into.)"""
        assert self.shear is not None
        w = float(self.gf[2])
        ncx = int(self.gi[0])
        speed = self.shear.rate * self.box.height
        cells = unreduced / w
        m = math.floor(cells)
        if speed < 0.0 and m == cells:
            m -= 1  # (moving down from exactly a cell's edge: in the cell below it)
        reduced = unreduced - self.box.width * (m // ncx)  # (within [k w, (k + 1) w])
        self.shear_slides = np.array([m], np.int64)
        self.shear_idle = np.zeros(1, np.int64)
        self.shear_clock = np.array([self.time, 0.0, reduced, self.time, unreduced])
        self.shear_clock[1] = _sheared.next_slide(m, speed > 0.0, w, self.shear_clock, speed)
        if self.shear_flights is None:
            self.shear_flights = np.zeros(3)

    def column_shift(self) -> int:
        """Under shear the images' offset in whole cells, reduced by the box's columns
        (``_engine/sheared.py``); -1 without shear."""
        if self.shear is None:
            return -1
        assert self.shear_slides is not None
        return int(self.shear_slides[0]) % int(self.gi[0])

    def shear_offsets(self, t: float | None = None) -> tuple[float, float]:
        """The offset of the images above at ``t`` (default :attr:`time`, not before
        the last slide): reduced to the box width, and not reduced (the images'
        whole displacement since the shear started)."""
        assert self.shear_clock is not None and self.shear_slides is not None
        t = self.time if t is None else t
        clock = self.shear_clock
        reduced = clock[2] + self.shear.rate * self.box.height * (t - clock[0])
        whole = int(self.shear_slides[0]) // int(self.gi[0])
        return float(reduced), float(reduced + self.box.width * whole)

    def shear_bundle(self):
        """The engine's shear family: ``None`` or a ``layout.Shear``."""
        if self.shear is None:
            return None
        assert (self.shear_clock is not None and self.shear_slides is not None
                and self.shear_flights is not None
                and self.shear_idle is not None)  # (started with the grid)
        n = len(self.S)
        return _layout.Shear(self.shear.rate, self.shear.rate * self.box.height,
                             0.5 * self.box.height, self.shear_clock, self.shear_slides,
                             np.empty(n, np.int64), np.empty(n), self.shear_flights,
                             self.shear_idle)

    def kinetic_stress_integral(self) -> np.ndarray:
        """Under shear: the time integrals since the shear started of ``sum m u_x^2``,
        ``sum m u_y^2`` and ``sum m u_x u_y`` over the peculiar velocities ``u``, up
        to :attr:`time` (the flights since each disk's last event included, exactly)."""
        assert self.shear is not None and self.shear_flights is not None
        return self.shear_flights + np.array(_sheared.pending(
            self.time, self.S, self.invm, self.shear.rate, 0.5 * self.box.height))

    def helfand_moments(self) -> np.ndarray:
        """The Einstein-Helfand moments at :attr:`time`, kept since they were started
        (:mod:`edmd2d.transport`): the time integrals of the momentum flux
        ``(xx, yy, xy)`` and of the energy flux ``(x, y)``, each the sum of its flight
        integrals (those since each disk's last move included, exactly) and its
        collisional transfers (the momentum part: the collision virial, counted from
        the simulation's start)."""
        assert self.helfand_sums is not None
        sums = self.helfand_sums
        flights = sums[:_helfand.H_CX] + _helfand.pending(self.time, self.S, self.invm)
        acc = self.acc
        return np.array([flights[0] + acc[_layout.A_VIRIAL_XX],
                         flights[1] + acc[_layout.A_VIRIAL_YY],
                         flights[2] + acc[_layout.A_VIRIAL_XY],
                         flights[3] + sums[_helfand.H_CX],
                         flights[4] + sums[_helfand.H_CY]])

    def growth_bundle(self):
        """The engine's growth family: ``None`` (fixed radii) or a ``layout.Growth``."""
        if self.growth is None:
            return None
        rate, t0 = self.growth.tolist()  # (stored as an array, which checkpoints hold)
        return _layout.Growth(rate, t0)

    def queue_args(self):
        return (self.qt, self.E, self.hv, self.qhead, self.qs, self.qf)

    def reorder(self) -> None:
        """Re-sort the internal rows along the Z-order of their cells (see module top).

        Every new array is built first and all are swapped in by one ``dict.update``,
        so an interrupt cannot leave them half permuted.  The queue is rebuilt rather than
        renumbered, which keeps its tie order (time, then internal index) exact.
        """
        # (The cells' Morton ranks are recomputed each time rather than held: a few
        # bytes a disk less for a small cost every 20 N events.)
        rank = _grid.morton_rank(int(self.gi[0]), int(self.gi[1]))
        perm = _grid.order_by_cell(self.E[:, _layout.CELL], rank, len(rank))
        inv = np.empty_like(perm)
        inv[perm] = np.arange(len(perm))
        # (Whole rows move: the stamps with S, the queue times, candidate times and
        # inverse masses with E.  The cell lists and the queue are rebuilt; queue
        # links left in the rows of disks that end up outside the lists go unread.)
        state = aligned_rows(len(perm), _layout.N_STATE, np.float64)
        state[:] = self.S[perm]
        _, table, hv, qhead, qs, qf = _queue.allocate(len(perm))
        qs[_queue.LOOKAHEAD] = self.qs[_queue.LOOKAHEAD]  # (forced on in tests)
        table[:] = self.E[perm]
        table[:, _layout.STAGED] = 0  # (what the lookahead fetched has moved)
        disk = table[:, _layout.KIND] & _layout.KIND_MASK == _layout.DISK
        table[disk, _layout.PARTNER] = inv[table[disk, _layout.PARTNER]]
        _, nxt, prv, times, _, _ = _layout.row_views(state, table)
        head = np.empty_like(self.head)
        _grid.build_lists(table[:, _layout.CELL], head, nxt, prv)
        wide = self.wide
        if wide is not None:  # (its nodes name wide indices, which keep their disks)
            wide = wide._replace(index=wide.index[perm], disk=inv[wide.disk])
            _wide.detach(table, wide, head, nxt, prv)
        # (The queue times are passed twice, as the loop does.)
        _queue.build(self.time, times, times, table, hv, qhead, qs, qf)
        model = None if self.model is None else self.model.permuted(perm)
        supports = self.rest_supports
        if supports is not None:  # (disk rows renumbered, wall codes kept)
            supports = supports[perm]
            disk = supports >= 0
            supports[disk] = inv[supports[disk]]
        vars(self).update(self.tables(state, table, hv, qhead, qs, qf),
                          rest_supports=supports,
                          rest_frozen=(None if self.rest_frozen is None
                                       else self.rest_frozen[perm]),
                          rest_t_static=(None if self.rest_t_static is None
                                         else self.rest_t_static[perm]),
                          mass=self.mass[perm], order=self.order[perm],
                          **{name: getattr(self, name)[perm] for name in
                             ("rough_w", "rough_angle", "rough_t", "rough_inv_inertia")
                             if getattr(self, name) is not None},
                          image=self.image[perm], head=head, model=model, wide=wide,
                          since_reorder=0)

    def predict_all(self) -> None:
        self.run(math.inf, 0, 0, np.array([self.time]), np.full(2, -1, np.int64),
                 _layout.PREDICT_ALL)

    # ------------------------------------------------------------------ advancing
    def advance(self, t_end: float, max_coll: int, until_given: bool, progress) -> None:
        """Run to ``t_end`` (``inf``: none) or ``max_coll`` further collisions (checked),
        with a progress bar if asked; raise what the run's end calls for.

        Raises
        ------
        ValueError
            For a run the float64 clock cannot resolve, or one past the time the
            largest growing disk fills the box (the state is left unchanged).
        RuntimeError
            For an engine error, no further event when collisions were asked for, or
            a growing disk filling the box (the state stands where the run stopped).
        """
        self.check_clock_resolves_crossings(t_end)
        outgrown = math.inf
        if self.growth is not None:
            outgrown = self.time_of_diameter(self.outgrow_diameter())
            if t_end > outgrown and until_given:
                raise ValueError(
                    f"until={t_end} is past t={outgrown:.17g}, when the largest disk "
                    f"grows as wide as the box ({min(self.box.size):.6g}); the "
                    f"simulation is left at t={self.time}")
            t_end = min(t_end, outgrown)
        by_time = until_given
        bar, owned = _progress.bar(
            progress, total=(t_end - self.time) if by_time else max_coll,
            unit="time" if by_time else "coll", desc="advance")
        try:
            try:
                status, info, remaining = self.run_chunks(t_end, max_coll, bar, by_time)
            finally:
                self.drain()  # (also on an error: the events up to it)
            if bar is not None and by_time and status in (_layout.REACHED_TIME,
                                                          _layout.NO_EVENTS):
                bar.update(t_end - self.time)  # (the flight after the last event)
        finally:
            if owned:
                bar.close()
        if status in (_layout.REACHED_TIME, _layout.NO_EVENTS) and until_given:
            self.time = t_end
            if status == _layout.NO_EVENTS and self.shear is not None:
                # (Slides were not processed up to t_end: restart the offset's clock
                # there, list the wide disks' rows across the boundary where the
                # images now are, and predict afresh.)
                before = self.column_shift()
                self.start_shear(self.shear_offsets()[1])
                if self.wide is not None:
                    _wide.slide(0, before, self.column_shift(), self.gi, self.wide,
                                np.empty(len(self.S), np.int64))
                self.predict_all()
            return
        if status == _layout.REACHED_COLLISIONS:
            return
        if (self.growth is not None and t_end == outgrown
                and status in (_layout.REACHED_TIME, _layout.NO_EVENTS)):
            self.time = t_end
            raise RuntimeError(
                f"the largest disk grew as wide as the box at t={t_end} before "
                f"{remaining} of the {max_coll} requested collisions; the simulation "
                f"stands at that time")
        if status == _layout.NO_EVENTS:
            raise RuntimeError(
                f"no further event can ever happen (t={self.time}): "
                f"{remaining} of the {max_coll} requested collisions cannot occur"
            )
        raise self.engine_error(status, int(info[0]), int(info[1]))

    def run_chunks(self, t_end, max_coll, bar, by_time):
        """The engine calls of :meth:`advance`: ``(status, info, remaining)``, the final
        status, the disks it names and the collisions still to go.  With a progress bar
        the calls are shorter (``_PROGRESS_EVENTS``) and the bar is updated after
        each."""
        remaining = max_coll
        out = np.array([self.time])
        info = np.full(2, -1, np.int64)  # (the disks an engine error names)
        same = 0  # events in a row at the present time, over the calls so far
        impacts, impact_time = 0, math.nan  # (the impacts at one time: see below)
        limit = self.wedged_limit()
        chunk = _CHUNK_EVENTS if bar is None else _PROGRESS_EVENTS
        clock = _time.perf_counter()
        while True:
            before = int(self.counts[_layout.C_COLLISIONS])
            events_before = self.events()
            shown = self.time
            budget = min(chunk, self.reorder_every - self.since_reorder)
            # (Under growth: no later than the grid holds; with resting disks: no later
            # than the next search for groups that hold one another up.)
            t_grid = math.inf if self.growth is None else self.time_of_diameter(self.grid_dmax)
            t_check = math.inf if self.rest_check is None else self.rest_check
            t_run = min(t_end, t_grid, t_check)
            try:
                status = self.run(t_run, remaining, budget, out, info, _layout.RUN_EVENTS)
            finally:
                # Also when Ctrl-C arrives as the engine returns: the clock must follow
                # the events the engine has processed, or positions would be read at a
                # time earlier than the disks' own.
                self.time = float(out[0])
                events = self.events() - events_before
                self.since_reorder += events
            done = int(self.counts[_layout.C_COLLISIONS]) - before
            remaining -= done
            # Disks wedged with no room to move (a ring of touching disks around a
            # periodic axis, a disk between a wall and a peg) collide forever at one
            # instant, the clock standing still: count the events of the calls that did
            # not move it (here, between calls, it costs the event loop nothing).
            if self.time == shown:
                same += events
                if same >= limit:
                    i = int(np.argmin(self.qt))  # (the next event: one of the wedged)
                    kind = _layout.kind_of(int(self.E[i, _layout.KIND]))
                    info[0] = i
                    info[1] = (-1 - int(self.E[i, _layout.AUX]) if kind == _layout.BOX
                               else int(self.E[i, _layout.PARTNER]))
                    return _layout.ERR_WEDGED, info, remaining
            else:
                same = 0
            if bar is not None:
                now = _time.perf_counter()
                if by_time:
                    bar.update(self.time - shown)
                    rate = (max_coll - remaining) / max(now - clock, 1e-9)
                    bar.set_postfix_str(f"{rate:.3g} coll/s", refresh=False)
                else:  # (tqdm shows the rate of its own unit, collisions)
                    bar.update(done)
            if status == _layout.NEED_RANDOM:
                self.model.refill()
                continue
            if status == _layout.LOG_FULL:
                self.drain()
                continue
            if status == _layout.ERR_STALLED and self.rest_supports is not None:
                # Disks caught between static bodies: one inelastic impact of the
                # group (``_impacts.py``); a group that stalls again at that instant
                # stops.
                if not self.time - impact_time <= _resting_instant(self.time):
                    impacts = 0
                impact_time = self.time
                i, j = int(info[0]), int(info[1])
                pair = _layout.kind_of(int(self.E[i, _layout.KIND])) == _layout.DISK
                if impacts < _IMPACTS_AT_ONCE and self.impact([i, j] if pair else [i],
                                                              stop=impacts > 0):
                    impacts += 1
                    continue
            reached = status in (_layout.REACHED_TIME, _layout.NO_EVENTS)
            if reached and self.rest_check is not None and t_run == t_check:
                # (An empty queue with no redraw to come: nothing moves until something
                # is changed from outside.  With a thermostat the next redraw may just
                # lie past this search.)
                still = status == _layout.NO_EVENTS and self.model_families().thermostat is None
                if still and t_end == math.inf:
                    return status, info, remaining  # (no event can ever come)
                self.time = t_run
                out[0] = t_run
                rested = self.rest_groups()
                if still and rested == 0:
                    # No search can find anything before the end: skip them.
                    self.rest_check = self.first_rest_check(t_end)
                else:
                    self.rest_check = t_check + self.families["resting"].every
                if t_run < t_end:
                    continue
            if reached and t_run < t_end and t_run == t_grid:
                # The disks have grown as large as the grid's cells allow: rebuild it.
                self.time = t_run
                out[0] = t_run
                self.regrid()
                continue
            if status != _layout.REACHED_EVENT_LIMIT:
                # (No reordering here: an error below names disks by internal index.)
                return status, info, remaining
            if self.since_reorder >= self.reorder_every:
                self.reorder()

    def events(self) -> int:
        """All processed events: collisions, wall contacts, cell crossings, redraws."""
        c = self.counts
        return (int(c[_layout.C_COLLISIONS]) + int(c[_layout.C_WALL])
                + int(c[_layout.C_CROSSINGS]) + int(c[_layout.C_KICKS]))

    def check_clock_resolves_crossings(self, t_end: float) -> None:
        """Refuse a run to ``t_end`` at whose end the float64 clock could no longer
        tell a disk's successive cell crossings, or the thermostat's redraws, apart
        (they are events: the clock would stop, and the run never end), and speeds
        whose product with the box's size the contact times cannot square."""
        horizon = max(abs(self.time), abs(t_end) if math.isfinite(t_end) else 0.0)
        vel = self.velocities()
        v = float(np.hypot(vel[:, 0], vel[:, 1]).max())
        if self.gravity is not None:
            # The fastest a disk can become: gravity's work over the box, if every axis
            # it acts along is walled (energy is conserved or lost), else its push for
            # the whole run.
            g = float(np.hypot(*self.gravity))
            along_periodic = any(p and gk != 0.0 for p, gk in
                                 zip(self.box.periodic, self.gravity))
            if along_periodic:
                if math.isfinite(t_end):
                    v += g * (t_end - self.time)
            else:
                v = math.sqrt(v * v + 2.0 * g * math.hypot(*self.box.size))
        if self.model is not None and self.model.thermo[1] > 0.0:
            interval = 1.0 / float(self.model.thermo[1])  # (mean time between redraws)
            if interval <= 64.0 * np.spacing(horizon):
                raise ValueError(
                    f"the thermostat redraws a velocity every {interval:.3g} on average, "
                    f"which the float64 clock cannot resolve at t={horizon:.6g} (its "
                    f"resolution there is {np.spacing(horizon):.3g}): the run could not "
                    "advance.  Use a smaller thermostat rate.")
        side = float(min(self.gf[2], self.gf[3]))
        if v > 0.0 and side / v <= 64.0 * np.spacing(horizon):
            raise ValueError(
                f"a disk at speed {v:.3g} crosses a grid cell (side {side:.3g}) "
                f"in {side / v:.3g}, which the float64 clock cannot resolve at "
                f"t={horizon:.6g} (its resolution there is {np.spacing(horizon):.3g}): "
                "the run could not advance.  Use smaller speeds (a slower unit of time) "
                "or a shorter run."
            )
        extent = max(self.box.size)
        if v * extent > MAX_LENGTH:
            raise ValueError(
                f"a disk at speed {v:.3g} in a box of side {extent:.3g}: the product, "
                f"{v * extent:.3g}, must be at most {MAX_LENGTH:g} (the contact times "
                "square it).  Use smaller speeds (a slower unit of time).")

    def squeezing(self, i: int) -> tuple[list, list, list[int]]:
        """What internal disk ``i`` touches now: the moving wall segments, as ``(k,
        normal, speed)``; the other bodies, as ``(name, normal, speed)`` (named as in
        errors: segments, box walls, disks in the user's numbering); and the internal
        indices of the disks it touches.  Each ``normal`` is the unit vector from the
        body to the disk's centre, ``speed`` the body's velocity along it (0 but for a
        moving segment).  Nothing without :class:`~edmd2d.physics.MovingWalls`.

        "Touches": within ``1e-6`` of the contact distance, or of the distance the
        disk covers in 16 roundings of the clock (a squeezed disk, fast by then,
        bounces across such a gap in an instant the clock cannot resolve)."""
        moving = self.families.get("moving_walls")
        if moving is None:
            return [], [], []
        pos = self.positions()
        r = float(self.S[i, _layout.R])
        speed = float(np.hypot(*self.velocities()[i]))
        slack = max(1e-6 * r, 16.0 * speed * float(np.spacing(max(abs(self.time), 1.0))))
        reach = r + slack
        starts, ends = self.wall_ends()
        motions = moving.motions()
        segments, others = [], []
        for k in np.flatnonzero(~self.wall_open).tolist():
            off = _gaps._segment_offset(pos[i:i + 1], starts[k], ends[k], self.box)[0]
            dist = float(np.hypot(*off))
            if dist > reach:
                continue
            normal = off / dist if dist > 0.0 else off
            if k in motions:
                segments.append((k, normal,
                                 float(dot(motions[k].velocity_at(self.time), normal))))
            else:
                others.append((f"walls[{k}]", normal, 0.0))
        for side, name in enumerate(BOX_WALL_EQUATIONS):
            axis, far = divmod(side, 2)
            if not self.box.periodic[axis]:
                gap = (self.box.size[axis] - pos[i, axis]) if far else pos[i, axis]
                if gap <= reach:
                    normal = np.zeros(2)
                    normal[axis] = -1.0 if far else 1.0
                    others.append((f"the box wall at {name}", normal, 0.0))
        d = _gaps._min_image(pos[i] - pos, self.box)
        dist = np.hypot(d[:, 0], d[:, 1])
        near = dist <= self.S[:, _layout.R] + reach
        near[i] = False
        touching = np.flatnonzero(near).tolist()
        others += [(f"disk {int(self.order[j])}", d[j] / dist[j], 0.0) for j in touching]
        return segments, others, touching

    def squeeze_error(self, start: list[int], stopped: str) -> RuntimeError | None:
        """The error for a disk squeezed by a moving segment, when the run stalled at
        one of the internal disks ``start``: that disk, or one it presses on through a
        chain of touching disks, touches a moving segment and, on the other side (unit
        normals more than 120 degrees apart), a body or another segment, and the two
        close the gap between them (by more than ``1e-9`` of the fastest motion's
        speed, against rounding at a turning point); ``None`` if none does."""
        moving = self.families.get("moving_walls")
        if moving is None:
            return None
        tol = 1e-9 * max(m.speed if isinstance(m, Translation) else m.amplitude * m.omega
                         for m in moving.motions().values())
        queue, seen = list(start), set(start)
        while queue and len(seen) <= 64:
            c = queue.pop(0)
            segments, others, touching = self.squeezing(c)
            for k, normal, push in segments:
                facing = [name for name, m, u in others
                          if float(dot(normal, m)) < -0.5 and push + u > tol]
                facing += [f"the moving segment walls[{q}]" for q, m, u in segments
                           if q != k and float(dot(normal, m)) < -0.5 and push + u > tol]
                if facing:
                    return RuntimeError(
                        f"disk {int(self.order[c])} squeezed at t={self.time} between the "
                        f"moving segment walls[{k}] and {' and '.join(facing)}: the "
                        "segment's path closes a gap narrower than the disk, which would "
                        "need unboundedly many collisions at one instant.  Stop the "
                        "segment short of it (a shorter distance or amplitude) or give "
                        f"the disk room to leave.  {stopped}")
            queue += [t for t in touching if t not in seen]
            seen.update(touching)
        return None

    def wedged_limit(self) -> int:
        """The events in a row at one time after which disks count as wedged."""
        return max(_WEDGED_EVENTS_PER_DISK * len(self), _WEDGED_EVENTS_MIN)

    def engine_error(self, status: int, i: int, j: int) -> RuntimeError:
        """The exception for an error status of the engine, which stopped before the
        event of internal disk ``i`` with ``j`` (a disk, a wall segment ``>= 0``, or
        ``-1 - side`` for a box wall, as the event's kind says)."""
        t_bad = float(self.qt[i])
        user_i = int(self.order[i])
        stopped = f"The simulation stopped at t={self.time}."
        if status == _layout.ERR_IMMOVABLE_PAIR:
            return RuntimeError(
                f"immovable disks {user_i} and {int(self.order[j])} (mass=inf) meet at "
                f"t={t_bad}: two immovable bodies cannot collide. {stopped}"
            )
        where = (f"walls[{j}]" if j >= 0
                 else f"the box wall at {BOX_WALL_EQUATIONS[-1 - j]}")
        if status == _layout.ERR_IMMOVABLE_WALL:
            return RuntimeError(
                f"immovable disk {user_i} (mass=inf) reaches {where} at t={t_bad}: an "
                f"immovable disk cannot bounce. {stopped}"
            )
        if status == _layout.ERR_STALLED:
            kind = _layout.kind_of(int(self.E[i, _layout.KIND]))
            partner = f"disk {int(self.order[j])}" if kind == _layout.DISK else where
            squeezed = self.squeeze_error([i] + ([j] if kind == _layout.DISK else []),
                                          stopped)
            if squeezed is not None:
                return squeezed
            streak = self.model.streak
            involved = np.sort(self.order[streak >= streak.max() // 10])
            if self.gravity is not None and self.rest_supports is None:
                advice = ("Under gravity this is a disk at rest on another disk, a peg or "
                          "a segment, which no tc ends: let disks come to rest "
                          "(resting=True, the default with restitution below 1; see "
                          "docs/gravity-and-heat.md).")
            elif self.gravity is not None:
                advice = ("Disks coming to rest did not end it: please report the "
                          "system that does this.")
            elif self.model.tc > 0.0:
                advice = (f"The TC model (tc={self.model.tc}) did not end it: a larger tc "
                          "would, unless the disks are confined with no room to move.")
            else:
                advice = "Use the TC model (tc > 0) to end the collapse."
            return RuntimeError(
                f"inelastic collapse at t={t_bad}: disk {user_i} and {partner} would "
                f"collide again at the same time, after {_models.STALL_COLLISIONS} "
                f"collisions in a row that took no time (disks involved: "
                f"{indices_where(np.isin(np.arange(len(self)), involved))}); the run would "
                f"need unboundedly many events. {advice} {stopped}"
            )
        if status == _layout.ERR_WEDGED:
            kind = _layout.kind_of(int(self.E[i, _layout.KIND]))
            other = (f"disk {int(self.order[j])}" if kind == _layout.DISK else
                     where if kind in (_layout.SEGMENT, _layout.BOX) else
                     "a grid cell's edge" if kind == _layout.CROSS else "a redraw")
            squeezed = self.squeeze_error([i] + ([j] if kind == _layout.DISK else []),
                                          stopped)
            if squeezed is not None:
                return squeezed
            return RuntimeError(
                f"disks wedged at t={self.time}: {self.wedged_limit()} or more events in "
                f"a row at this one time, the next of disk {user_i} with {other}, and the "
                "clock cannot advance: "
                "disks that touch with no room to move (a ring of touching disks around a "
                "periodic axis, a disk between a wall and a peg or between two walls) "
                "collide forever at one instant.  Give them room (a larger box, smaller "
                "or fewer disks) or set velocities that do not drive them into each "
                f"other. {stopped}"
            )
        return RuntimeError(f"internal error: engine returned status {status}")  # pragma: no cover
