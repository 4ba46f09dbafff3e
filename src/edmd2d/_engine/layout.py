"""The engine's state layout, declared once: row tables, event codes, counters, statuses,
and the named bundles in which the event loop receives its arrays and its physics.

Per-disk data sits in two tables of 64-byte rows (64-byte aligned, so that a row is one
cache line):

``S[i]``, what other disks read of disk ``i`` when they predict against it: its state
``(x, y, vx, vy, t_local, radius)`` (float64), its invalidation counter ``stamp`` and its
links in its grid cell's list (int32).

``E[i]``, what only disk ``i``'s own events use: its cell, its kept candidate (the best
event that is not a cell crossing: kind, partner, aux, the partner's stamp and its time
``tcand``), its links and scheduled time ``qt`` in the calendar queue,
``1/mass``, and the lookahead's notes of the prefetch stages given to its event (a
hint).

Every column is declared below with the table, dtype and index in that dtype's view of
the table (``S``, ``S.view(np.int32)``, ``E``, ``E.view(np.float64)``); :func:`check`
(run at import) verifies that no two columns share a byte and that each row holds 64.

Event codes are packed into the int32 columns by the named helpers below: a kind and,
for a cell crossing, its direction; a periodic image shift; a wall segment's part and
image shift; a box wall's side.

The bundles (:class:`typing.NamedTuple`, read by field name in the compiled code) are
declared at the end: the loop's own state (:class:`Control`, :class:`Particles`,
:class:`Grid`, :class:`Walls`, :class:`Calendar`, :class:`Tallies`, :class:`Log`) and
one per physics family (:class:`Contact`, :class:`HeatedWalls`, :class:`Thermostat`,
:class:`Uniforms`, :class:`Gravity`, :class:`Growth`, :class:`Rest`,
:class:`Shear`, :class:`Motion`).  A family that a
system does not use is passed as ``None``: numba prunes its branches from the loop
compiled for it.
"""

from __future__ import annotations

from enum import IntEnum
from typing import NamedTuple

import numpy as np

from .._jit import njit

ROW_BYTES = 64

# (table, dtype of the view, index in that view) for every column; the names are the
# module's constants below.
COLUMNS: dict[str, tuple[str, type, int]] = {}


def _col(name: str, table: str, dtype, index: int) -> int:
    COLUMNS[name] = (table, np.dtype(dtype), index)
    return index


# --- S: the state row (S is float64; its int32 columns are those of S.view(np.int32))
X = _col("X", "S", np.float64, 0)
Y = _col("Y", "S", np.float64, 1)
VX = _col("VX", "S", np.float64, 2)
VY = _col("VY", "S", np.float64, 3)
T = _col("T", "S", np.float64, 4)  # the disk's local time: x, y are valid at T
R = _col("R", "S", np.float64, 5)
S_STAMP = _col("S_STAMP", "S", np.int32, 12)  # invalidation counter
S_NEXT = _col("S_NEXT", "S", np.int32, 13)  # next disk in the cell's list (-1: none)
S_PREV = _col("S_PREV", "S", np.int32, 14)  # previous disk in the cell's list
# Under gravity: the box walls a disk slides on, one bit per side (1 << side; 0: none),
# and RESTING for a disk at rest (see resting.py).
S_SUPPORT = _col("S_SUPPORT", "S", np.int32, 15)
RESTING = 16
N_STATE = ROW_BYTES // 8  # float64 columns per S row

# --- E: the bookkeeping row (E is int32; its float64 columns are those of
# E.view(np.float64))
CELL = _col("CELL", "E", np.int32, 0)
KIND = _col("KIND", "E", np.int32, 1)  # kept candidate's kind; crossing direction above
PARTNER = _col("PARTNER", "E", np.int32, 2)  # disk, wall segment or box side
AUX = _col("AUX", "E", np.int32, 3)  # image shift (disk) or part and shift (segment)
PSTAMP = _col("PSTAMP", "E", np.int32, 4)  # the partner's stamp when predicted
NEXT = _col("NEXT", "E", np.int32, 5)  # calendar queue: next in the bucket list
PREV = _col("PREV", "E", np.int32, 6)  # calendar queue: previous in the bucket list
LOC = _col("LOC", "E", np.int32, 7)  # calendar queue: heap slot, list, or -1
QT = _col("QT", "E", np.float64, 4)  # scheduled event time (inf: none)
E_TCAND = _col("E_TCAND", "E", np.float64, 5)  # time of the kept candidate
E_INVM = _col("E_INVM", "E", np.float64, 6)  # 1 / mass (0: immovable)
STAGED = _col("STAGED", "E", np.int32, 15)  # lookahead stages given, as bits (a hint)
N_E = ROW_BYTES // 4  # int32 columns per E row
STAGE_BITS = 0b1110  # the bits of STAGED in use: stages 1-3


def check() -> None:
    """Raise ``RuntimeError`` if two columns share a byte or one leaves its 64-byte row
    (a programming error in this file, caught at import)."""
    used: dict[str, dict[int, str]] = {"S": {}, "E": {}}
    for name, (table, dtype, index) in COLUMNS.items():
        start = index * dtype.itemsize
        for byte in range(start, start + dtype.itemsize):
            if byte >= ROW_BYTES:
                raise RuntimeError(f"column {name} leaves its {ROW_BYTES}-byte row")
            if byte in used[table]:
                raise RuntimeError(f"columns {used[table][byte]} and {name} share byte "
                                   f"{byte} of table {table}")
            used[table][byte] = name


check()


def row_views(S, E):
    """The per-disk columns kept inside the rows of ``S`` and ``E``, as 1-D views
    (writable, strided): ``(stamp, nxt, prv, qt, tcand, invm)``."""
    si = S.view(np.int32)
    ef = E.view(np.float64)
    return (si[:, S_STAMP], si[:, S_NEXT], si[:, S_PREV], ef[:, QT], ef[:, E_TCAND],
            ef[:, E_INVM])


def support_view(S):
    """The column of the box walls each disk rests on (``S_SUPPORT``), a 1-D view."""
    return S.view(np.int32)[:, S_SUPPORT]


class Kind(IntEnum):
    """Event kinds (the low bits of ``E[:, KIND]`` and the event log's kind column)."""

    NONE = 0
    DISK = 1
    SEGMENT = 2
    BOX = 3
    CROSS = 4
    KICK = 5  # a thermostat's velocity redraw (never a kept candidate)
    REST = 6  # a disk put to rest (logged only; see .resting)
    WAKE = 7  # a disk at rest woken (logged only)
    SLIDE = 8  # the sliding images of a sheared box step by a cell (never logged)


# (Plain ints for the compiled code.)
NONE = int(Kind.NONE)
DISK = int(Kind.DISK)
SEGMENT = int(Kind.SEGMENT)
BOX = int(Kind.BOX)
CROSS = int(Kind.CROSS)
KICK = int(Kind.KICK)
REST = int(Kind.REST)
WAKE = int(Kind.WAKE)
SLIDE = int(Kind.SLIDE)
KIND_MASK = 15  # low bits of E[:, KIND]; the bits above hold a crossing's direction


@njit
def pack_kind(kind, direction):
    """``E[:, KIND]`` for a kept candidate of ``kind`` and a scheduled cell crossing in
    ``direction`` (0-3: +x, -x, +y, -y)."""
    return kind | (direction << 4)


@njit
def kind_of(code):
    """The kept candidate's kind in ``E[:, KIND]``."""
    return code & KIND_MASK


@njit
def direction_of(code):
    """The scheduled cell crossing's direction (0-3: +x, -x, +y, -y) in ``E[:, KIND]``."""
    return code >> 4


@njit
def pack_shift(sx, sy):
    """A periodic image shift ``(sx, sy)``, each -1, 0 or +1 box lengths, as 0-8."""
    return (sx + 1) * 3 + (sy + 1)


@njit
def unpack_shift(code):
    """The image shift ``(sx, sy)`` of :func:`pack_shift`."""
    return code // 3 - 1, code % 3 - 1


@njit
def pack_segment(part, shift):
    """A wall-segment contact: ``part`` 0 (side), 1 (start) or 2 (end point), and the
    packed image shift of the segment."""
    return part + 3 * shift


@njit
def unpack_segment(aux):
    """``(part, shift)`` of :func:`pack_segment`."""
    return aux % 3, aux // 3


# Box walls (the partner of a BOX event) are numbered 2 * axis + (1 at the far wall):
# x=0, x=width, y=0, y=height (their names: edmd2d.geometry.BOX_WALLS).

# Counters (counts[...])
C_COLLISIONS = 0
C_WALL = 1
C_CROSSINGS = 2
C_STALE = 3
C_KICKS = 4  # thermostat velocity redraws
C_RESTS = 5  # disks put to rest
C_WAKES = 6  # resting disks woken
N_COUNTS = 7

# Accumulators (acc[...]): sum of J*|r_ij| over disk collisions (collision virial), the
# impulse delivered to each box wall (x=0, x=W, y=0, y=H) and to all wall segments, the
# diagonal of the virial tensor, sum J |r_ij| n_x^2 and sum J |r_ij| n_y^2, the
# kinetic energy lost in inelastic collisions, the kinetic energy each box wall gave
# to the disks (heated walls: x=0, x=W, y=0, y=H), the kinetic energy the
# thermostat's redraws gave, and the off-diagonal of the virial tensor, sum J |r_ij|
# n_x n_y.
A_VIRIAL = 0
A_BOX = 1  # 1..4
A_SEGMENTS = 5
A_VIRIAL_XX = 6
A_VIRIAL_YY = 7
A_DISSIPATED = 8
A_HEAT_BOX = 9  # 9..12
A_THERMOSTAT = 13
A_GRAVITY = 14  # potential energy given by changes of gravity (Python side only)
A_VIRIAL_XY = 15
A_WORK = 16  # the work of the moving wall segments on the disks (all segments)
N_ACC = 17

# Per-segment tallies (wacc[k, ...], one row per wall segment k, beside acc[A_SEGMENTS],
# their total): the impulse vector the segment received, the sum of -J n over its
# contacts (n the unit normal from the segment to the disk, J the impulse magnitude);
# J summed over the contacts on each side (left: the side that (-(by - ay), bx - ax)
# points to, on the left going from start a to end b) and at the two end points; and
# the number of contact events (counted like counts[C_WALL], impulse or not); and the
# kinetic energy the segment gave to the disks (a heated segment), and the work it did
# on them (a moving segment: J.u over its contacts, u its velocity).
W_FX = 0
W_FY = 1
W_LEFT = 2
W_RIGHT = 3
W_ENDS = 4
W_CONTACTS = 5
W_HEAT = 6
W_WORK = 7
N_WACC = 8

# Modes of run(): process events, or predict every disk afresh and rebuild the queue
RUN_EVENTS = 0
PREDICT_ALL = 1

# Status codes returned by run()
REACHED_TIME = 0
REACHED_COLLISIONS = 1
REACHED_EVENT_LIMIT = 2
NO_EVENTS = 3
NEED_RANDOM = 4  # the random numbers left are too few for the next event: refill
LOG_FULL = 5  # the event log is full: empty it and call again
ERR_IMMOVABLE_PAIR = 10
ERR_IMMOVABLE_WALL = 11
ERR_STALLED = 12  # inelastic collapse: unboundedly many collisions in no time
# Disks wedged with no room to move: unboundedly many events in no time.  Found by the
# Python driver between calls of the loop (it costs the loop nothing), not by the loop.
ERR_WEDGED = 13


# ------------------------------------------------------------------------- bundles
# What the event loop receives (loop.run), by name.  (The compiled code reads the
# fields by name; a bundle's type is part of the compiled loop's signature.)


class Control(NamedTuple):
    """What a call of the loop is to do, and where it reports."""

    #: Stop before the first event later than this time.
    t_end: float
    #: Stop right after this many disk-disk collisions of the call.
    max_collisions: int
    #: Stop after this many processed events.
    max_events: int
    #: ``RUN_EVENTS`` (process events) or ``PREDICT_ALL`` (predict every disk afresh and
    #: rebuild the queue).
    mode: int
    #: float64, shape (1,): the time of the last processed event (in: the clock).
    out: np.ndarray
    #: int64, shape (2,): the disks (or disk and wall) an error status names.
    info: np.ndarray


class Particles(NamedTuple):
    """The per-disk state: the row tables and the columns viewed inside them
    (:func:`row_views`)."""

    #: The state rows (float64, ``N_STATE`` columns).
    S: np.ndarray
    #: The bookkeeping rows (int32, ``N_E`` columns).
    E: np.ndarray
    #: Each disk's invalidation counter (``S_STAMP``).
    stamp: np.ndarray
    #: The next disk in the disk's cell list (``S_NEXT``; -1: none).
    nxt: np.ndarray
    #: The previous disk in the disk's cell list (``S_PREV``).
    prv: np.ndarray
    #: The time of the disk's scheduled event (``QT``; inf: none).
    qt: np.ndarray
    #: The time of the disk's kept candidate (``E_TCAND``).
    tcand: np.ndarray
    #: 1 / mass (``E_INVM``; 0: immovable).
    invm: np.ndarray
    #: int64, shape (N, 2): the periodic images crossed.
    image: np.ndarray
    #: int64: the user's index of each internal row.
    order: np.ndarray


class Grid(NamedTuple):
    """The cell grid (see :mod:`.grid`)."""

    #: int64 ``(ncx, ncy, periodic x, periodic y)``.
    gi: np.ndarray
    #: float64 ``(width, height, cell width, cell height)``.
    gf: np.ndarray
    #: int32: the first disk of each cell's list (-1: empty).
    head: np.ndarray


class Walls(NamedTuple):
    """The wall segments and their lists per cell (``grid.bucket_walls``)."""

    #: Shape (S, 2): the start points.
    wa: np.ndarray
    #: Shape (S, 2): the end points.
    wb: np.ndarray
    #: Where each cell's list starts in ``wwall`` (one more entry than cells).
    wstart: np.ndarray
    #: The segments listed per cell.
    wwall: np.ndarray
    #: The periodic image shift in x of each listed segment.
    wsx: np.ndarray
    #: The periodic image shift in y of each listed segment.
    wsy: np.ndarray


class Calendar(NamedTuple):
    """The calendar queue's arrays besides the times and links in ``E`` (see
    :mod:`.queue`)."""

    #: int32: the heap of the current bucket, the disk at each slot.
    hv: np.ndarray
    #: int32, shape (nb + 1,): the first disk of each bucket list and of the overflow.
    qhead: np.ndarray
    #: int64 scalars (``queue.CUR``, ``queue.NHEAP``, ..., ``queue.LOOKAHEAD``).
    qs: np.ndarray
    #: float64 scalars (``queue.ORIGIN``, ``queue.INVW``).
    qf: np.ndarray


class Tallies(NamedTuple):
    """Counters and accumulated impulses and energies."""

    #: int64 event counters (``C_*``).
    counts: np.ndarray
    #: float64 accumulators (``A_*``).
    acc: np.ndarray
    #: Shape (S, ``N_WACC``): each wall segment's tallies (``W_*``).
    wacc: np.ndarray


class Log(NamedTuple):
    """The event log.

    The loop returns ``LOG_FULL`` once ``capacity`` events are logged (0: no log).
    Where disks come to rest the arrays are longer than ``capacity`` by more than the
    number of disks: one event may log the rests and wakes it causes besides itself
    (at most every disk once), and none may be lost."""

    #: float64: each logged event's time.
    times: np.ndarray
    #: int64, shape (capacity, 3): kind, disk (user index), partner.
    events: np.ndarray
    #: int64, shape (1,): events logged (may pass the capacity: see ``loop.run``).
    count: np.ndarray
    #: float64: each logged event's impulse.
    impulses: np.ndarray
    #: The events after which the log is emptied (0: no log).
    capacity: int


# --- the physics families (each None when unused)


class Contact(NamedTuple):
    """Restitution and the TC model (see :mod:`.response`)."""

    #: float64, shape (S, S): the coefficient for each pair of species.
    table: np.ndarray
    #: int32: each row's species.
    species: np.ndarray
    #: The coefficient against box walls and segments.
    wall: float
    #: The TC model's duration: a collision within ``tc`` of a disk's last is elastic.
    tc: float
    #: float64: each row's last collision time (-inf before the first).
    t_last: np.ndarray
    #: int64: each row's collisions in a row at the same time.
    streak: np.ndarray
    #: The ``tc`` with which box walls hold disks at rest under gravity (0: never).
    hold: float
    #: Impacts with a normal speed below this are elastic (0: none; set where disks
    #: come to rest, see :mod:`.resting`).
    soft: float = 0.0


class HeatedWalls(NamedTuple):
    """Walls that send disks back with velocities drawn at their temperature."""

    #: float64, shape (4 + S,): ``kT`` of each box wall and segment (0: not heated).
    kt: np.ndarray


class Thermostat(NamedTuple):
    """The Andersen thermostat: velocity redraws at the events of a Poisson process."""

    #: The temperature of the redrawn velocities.
    kt: float
    #: The rate of redraws over all rows.
    rate: float
    #: float64, shape (1,): the time of the next redraw (advanced by the engine).
    t_next: np.ndarray


class Uniforms(NamedTuple):
    """Uniform random numbers in ``[0, 1)`` for heated walls and the thermostat."""

    #: float64: the numbers.
    buffer: np.ndarray
    #: int64, shape (1,): the next one to use.
    cursor: np.ndarray


class Gravity(NamedTuple):
    """A uniform acceleration of the movable disks (see :mod:`.flight`)."""

    #: The acceleration's x component.
    gx: float
    #: The acceleration's y component.
    gy: float
    #: 1 / mass (0: immovable, feels no gravity).
    invm: np.ndarray
    #: int32: the box walls each disk rests on, one bit per side (``S_SUPPORT``).
    support: np.ndarray


class Growth(NamedTuple):
    """Radii that grow linearly in time: ``S[i, R] (1 + rate (t - t0))``."""

    #: The growth rate per unit time.
    rate: float
    #: The time at which the stored radii hold.
    t0: float


class Rest(NamedTuple):
    """Disks that come to rest under gravity (see :mod:`.resting`)."""

    #: A disk slower than this after a collision comes to rest where it is held.
    speed: float
    #: The largest gap to a body that counts as touching it (a support).
    gap: float
    #: A resting disk hit with a normal speed above this wakes; a softer impact
    #: bounces off it.
    wake: float
    #: A resting disk hit with a normal speed up to this, by an impact its static
    #: contacts can take, stays at rest (the impact bounces off it).
    press: float
    #: Impacts with a normal speed below this are elastic (``Contact.soft``).
    soft: float
    #: Two contacts of a disk less than this apart (besides a few units of rounding of
    #: the clock) came at one instant, for the rules of rest (``resting.at_once``).
    instant: float
    #: int32, shape (N, ``resting.MAX_SUPPORTS``): each resting disk's supports (disk
    #: rows, or walls: see :mod:`.resting`; -1: none).
    supports: np.ndarray
    #: Shape (N, 2): the velocity each resting disk came to rest with (resumed when it
    #: wakes).
    frozen: np.ndarray
    #: Shape (N,): the time each disk last met a static body (a resting disk or a
    #: wall; -inf: never).
    t_static: np.ndarray
    #: int32, shape (N,): room for the cascade of a wake.
    stack: np.ndarray
    #: int64, shape (``resting.candidates(...)``,): room for the supports examined.
    codes: np.ndarray
    #: float64, shape (``resting.candidates(...)``,): their normals' angles from "up".
    angles: np.ndarray
    #: int32, shape (2, M, 3): room for the disks near a disk (``wide.near``): one
    #: for the cascade of a wake and the flying disks to predict afresh, one for the
    #: static bodies examined for a support (and the segment images met before them).
    near: np.ndarray
    #: The event log, where rests and wakes are logged as events (``REST``, ``WAKE``).
    log: Log
    #: int64: each row's user index (for the log).
    order: np.ndarray
    #: The grid's wide disks (``Wide``), or ``None``: where the disks near one are.
    wide: Wide | None


class Shear(NamedTuple):
    """Lees-Edwards boundaries: the images above and below slide along x (see
    :mod:`.sheared`)."""

    #: The shear rate: the flow's x velocity grows by ``rate`` per unit of y.
    rate: float
    #: ``U = rate * height``: the velocity of the images above relative to the box.
    speed: float
    #: ``height / 2``: where the flow's velocity is zero.
    half: float
    #: float64, shape (5,): the time of the last slide, of the next, the offset at the
    #: last, and the time and unreduced offset where the shear started
    #: (``sheared.T_BASE``, ``T_NEXT``, ``DELTA_BASE``, ``T_ORIGIN``, ``D_ORIGIN``).
    clock: np.ndarray
    #: int64, shape (1,): slides since the offset was 0 (negative for ``rate < 0``).
    slides: np.ndarray
    #: int64, shape (N,): room for the disks a slide predicts afresh.
    rows: np.ndarray
    #: float64, shape (N,): room for their predicted times.
    times: np.ndarray
    #: float64, shape (3,): the time integrals over free flights of ``sum m u_x^2``,
    #: ``sum m u_y^2`` and ``sum m u_x u_y`` (``u`` the peculiar velocity).
    flights: np.ndarray
    #: int64, shape (1,): slides in a row with no event of a disk ahead (kept from one
    #: call of the loop to the next, whatever its budget of events).
    idle: np.ndarray


class Helfand(NamedTuple):
    """The Einstein-Helfand moments' sums (see :mod:`.helfand`)."""

    #: float64, shape (7,): the flight integrals of ``sum m v_x^2``, ``sum m v_y^2``,
    #: ``sum m v_x v_y``, ``sum v_x e`` and ``sum v_y e``, and the collisional
    #: energy transfers ``sum d_x de`` and ``sum d_y de`` (``helfand.H_XX`` ..
    #: ``H_CY``).
    sums: np.ndarray


class Rough(NamedTuple):
    """Rough disks: rotation and tangential restitution (see :mod:`.rough`)."""

    #: The tangential restitution of disk-disk contacts, in ``[-1, 1]``.
    beta: float
    #: Coulomb's coefficient of disk-disk contacts (``inf``: no limit).
    friction: float
    #: The same at walls (box walls and segments).
    wall_beta: float
    wall_friction: float
    #: float64, shape (N,): the angular velocities.
    w: np.ndarray
    #: float64, shape (N,): the angles at ``t_angle``.
    angle: np.ndarray
    t_angle: np.ndarray
    #: float64, shape (N,): ``1 / I``, ``I = q m r^2`` (0 for an immovable disk).
    inv_inertia: np.ndarray


class Wide(NamedTuple):
    """Disks wider than the grid's cells, listed in the cells of their footprints
    (see :mod:`.wide`; ``None`` where the grid's cells hold the largest disk)."""

    #: int64, shape (N,): each disk's index among the wide disks (-1: narrow).
    index: np.ndarray
    #: int64, shape (K,): the disk of each wide index.
    disk: np.ndarray
    #: int64, shape (K, 4): the footprint's cells ``(u0, u1, v0, v1)`` (unwrapped on
    #: periodic axes).
    rect: np.ndarray
    #: int64, shape (K,): the first node of each wide disk.
    base: np.ndarray
    #: int64, shape (K, 2): the nodes per axis of each wide disk (``kw, kh``).
    span: np.ndarray
    #: The footprint's margin ``h`` beyond the radius: at least the largest narrow
    #: radius.
    half: float
    #: int32: the first node of each cell's list of wide disks (-1: none).
    bhead: np.ndarray
    #: int32, shape (M,): the next and previous node in a cell's list.
    nnext: np.ndarray
    nprev: np.ndarray
    #: int32, shape (M,): the wide index each node belongs to.
    nk: np.ndarray
    #: int32, shape (M,): the image shift ``k`` of each listed node (the disk's image
    #: over that cell is at ``x - k L``).
    nsx: np.ndarray
    nsy: np.ndarray
    #: int32, shape (M,): the cell each node is listed in (-1: not listed).
    ncell: np.ndarray


# The columns of Motion.par.  A translation: the unit direction, the speed, the times it
# starts and stops; an oscillation: the unit direction, the amplitude, the angular
# frequency and the phase (shifted by amplitude * sin(omega t + phase) along it).
M_DX = 0
M_DY = 1
M_SPEED = 2
M_AMPLITUDE = 2
M_BEGIN = 3
M_OMEGA = 3
M_END = 4
M_PHASE = 4
N_MOTION = 5
#: Motion.kind: a segment at rest, one translated at a constant velocity for a while,
#: one that oscillates.
FIXED = 0
LINEAR = 1
SINE = 2


class Motion(NamedTuple):
    """Wall segments that move (see :mod:`.moving`; ``None`` where all are fixed).  The
    segments' arrays in :class:`Walls` hold where each was given; at time ``t`` it is
    shifted along its direction by :func:`.moving.shift`."""

    #: int64, shape (S,): ``FIXED``, ``LINEAR`` or ``SINE``.
    kind: np.ndarray
    #: float64, shape (S, N_MOTION): the parameters (``M_*``).
    par: np.ndarray


class ModelFamilies(NamedTuple):
    """The families a ``models.Model`` hands the engine, each ``None`` when unused."""

    contact: Contact | None
    heated: HeatedWalls | None
    thermostat: Thermostat | None
    uniforms: Uniforms | None
