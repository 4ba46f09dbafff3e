"""The event loop (seed section 3), one scheduled event per disk.

State layout: two tables of 64-byte rows (64-byte aligned: a row is one cache line).

``S[i]``, what other disks read of disk ``i`` when they predict against it:
float64 columns ``(x, y, vx, vy, t_local, radius)`` and, in its last 16 bytes (int32
columns 12-14 of ``S.view(np.int32)``; 15 is unused, 0), ``stamp[i]`` (the invalidation
counter) and ``nxt[i]``, ``prv[i]`` (its links in its grid cell's list).

``E[i]``, what only disk ``i``'s own events use: int32 columns

``(cell, kind, partner, aux, partner_stamp, next, prev, loc)``

and float64 columns 4-6 (of ``E.view(np.float64)``) ``qt[i], tc[i], invm[i]``: its
scheduled time, the time of its kept candidate, and 1/mass.  Int32 column 15
(``STAGED``) records, as bits, the stages of the lookahead (below) given to its
scheduled event so far (a hint; 0 for an event just predicted); 14 is unused.

``kind, partner, aux, partner_stamp`` (with time ``tc[i]``) is the kept candidate
``nc``: the best event that is *not* a cell crossing; ``next, prev, loc`` are disk
``i``'s links in the calendar queue (queue.py), which holds its scheduled time
``qt[i]``.  The scheduled event is the cell crossing when ``qt[i] < tc[i]`` (its
direction is kept in bits 4-5 of ``kind``), and ``nc`` otherwise.

The kernels see ``stamp, nxt, prv, qt, tc, invm`` as strided 1-D views into the two
tables (:func:`row_views`).  A neighbour scanned in a prediction thus costs one cache
line (its state, stamp and list link), and a disk's own event another: at N = 10^6,
where each is a miss, separate arrays for the stamps, the cell links and the queue
times cost a line each on top.

Why one event per disk is enough: a disk's event is the minimum over its candidates.
When a partner ``j`` changes course it is re-predicted against all its neighbours, so
any new contact with ``j`` is held by ``j``; the other candidates of ``i`` are all later
than ``i``'s stale event, so re-predicting ``i`` when that stale event comes due is
enough.  ``stamp[i]`` grows whenever ``i``'s trajectory changes (a collision) or its
stored coordinates jump by a box length (a periodic wrap).

Why a cell crossing only needs the newly exposed cells: the kept candidate ``nc`` is the
earliest contact with everything in the old neighbourhood (still exact if its partner's
stamp is unchanged); disks that entered the old neighbourhood since then predicted
against ``i`` themselves; so only the row of cells that comes into range must be scanned.
A wrap, or a stale ``nc``, falls back to a full scan.

Positions are "delayed states": ``S[i, 0:2]`` is valid at ``S[i, 4]``; only the disks of
an event are moved to its time.

From ``queue.LOOKAHEAD_MIN_DISKS`` disks on, the working set no longer fits the caches
and every event would wait, one miss after another, for its disk's rows, its partner's,
its cells' list heads and its neighbours' rows.  Each time the calendar reaches a new
bucket, ``_lookahead`` therefore prefetches these for the events of that bucket and
the next few, one stage of that chain per bucket (see there), and between the events
of a bucket ``_stage_heap`` gives its remaining events the stages they still lack.
They only prefetch and note the stages given in ``E[:, STAGED]``: every event and all
other state are bit-identical with them on or off (tested by forcing them on for
small systems).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import kernel, njit
from . import prefetch, queue
from .grid import insert, neighbour, remove
from .predict import INF, box_wall_time, exit_time, pair_time, segment_time

# Float64 columns of S, and int32 columns of S.view(np.int32)
X, Y, VX, VY, T, R = 0, 1, 2, 3, 4, 5
N_STATE = 8
S_STAMP, S_NEXT, S_PREV = 12, 13, 14

# Int32 columns of E (NEXT, PREV and LOC belong to the queue), and float64 columns of
# E.view(np.float64) (QT belongs to the queue)
CELL, KIND, PARTNER, AUX, PSTAMP = 0, 1, 2, 3, 4
STAGED = 15
STAGE_BITS = 0b1110  # the bits of STAGED in use: stages 1-3 (see _stage)
E_TC, E_INVM = 5, 6
_KIND_MASK = 15  # low bits of E[:, KIND]; the bits above hold the crossing direction

# Event kinds
NONE = 0
DISK = 1
SEGMENT = 2
BOX = 3
CROSS = 4

# Counters (counts[...])
C_COLLISIONS = 0
C_WALL = 1
C_CROSSINGS = 2
C_STALE = 3
N_COUNTS = 4

# Accumulators (acc[...]): sum of J*|r_ij| over disk collisions (collision virial), the
# impulse delivered to each box wall (x=0, x=W, y=0, y=H) and to all wall segments, and
# the diagonal of the virial tensor, sum J |r_ij| n_x^2 and sum J |r_ij| n_y^2.
A_VIRIAL = 0
A_BOX = 1  # 1..4
A_SEGMENTS = 5
A_VIRIAL_XX = 6
A_VIRIAL_YY = 7
N_ACC = 8

# Modes of run(): process events, or predict every disk afresh and rebuild the queue
RUN_EVENTS = 0
PREDICT_ALL = 1

# Status codes returned by run()
REACHED_TIME = 0
REACHED_COLLISIONS = 1
REACHED_EVENT_LIMIT = 2
NO_EVENTS = 3
ERR_IMMOVABLE_PAIR = 10
ERR_IMMOVABLE_WALL = 11


def row_views(S, E):
    """The per-disk columns kept inside the rows of ``S`` and ``E``, as 1-D views
    (writable, strided): ``(stamp, nxt, prv, qt, tc, invm)``."""
    si = S.view(np.int32)
    ef = E.view(np.float64)
    return (si[:, S_STAMP], si[:, S_NEXT], si[:, S_PREV], ef[:, queue.QT], ef[:, E_TC],
            ef[:, E_INVM])


@njit(inline="always")
def _scan_disks(i, t, x, y, vx, vy, r, cx, cy, ox0, ox1, oy0, oy1,
                S, stamp, gi, gf, head, nxt, best, partner, aux, pst):
    """Earliest contact of disk ``i`` (at ``x, y`` at time ``t``) with the disks in the
    cells at offsets ``[ox0, ox1] x [oy0, oy1]`` from ``(cx, cy)``, if before ``best``
    (a time interval from ``t``)."""
    ncx = gi[0]
    for ox in range(ox0, ox1 + 1):
        nxc, sx = neighbour(cx, ox, ncx, gi[2] != 0)
        if nxc < 0:
            continue
        for oy in range(oy0, oy1 + 1):
            nyc, sy = neighbour(cy, oy, gi[1], gi[3] != 0)
            if nyc < 0:
                continue
            j = head[nxc + ncx * nyc]
            while j >= 0:
                if j != i:
                    dtj = t - S[j, T]
                    vjx = S[j, VX]
                    vjy = S[j, VY]
                    dx = x - (S[j, X] + dtj * vjx + sx * gf[0])
                    dy = y - (S[j, Y] + dtj * vjy + sy * gf[1])
                    dtc = pair_time(dx, dy, vx - vjx, vy - vjy, r + S[j, R])
                    if dtc < best:
                        best = dtc
                        partner = j
                        aux = (sx + 1) * 3 + (sy + 1)
                        pst = stamp[j]
                j = nxt[j]
    return best, partner, aux, pst


@njit(inline="always")
def _scan_walls(x, y, vx, vy, r, c, gf, wa, wb, wstart, wwall, wsx, wsy, best, partner, aux):
    """Earliest contact with the wall segments listed for cell ``c``, if before ``best``."""
    if wa.shape[0] == 0:  # no segments: spare the bucket lookup (a cache miss at large N)
        return best, partner, aux
    for k in range(wstart[c], wstart[c + 1]):
        w = wwall[k]
        shx = wsx[k] * gf[0]
        shy = wsy[k] * gf[1]
        dtw, part = segment_time(x, y, vx, vy, r,
                                 wa[w, 0] + shx, wa[w, 1] + shy,
                                 wb[w, 0] + shx, wb[w, 1] + shy)
        if dtw < best:
            best = dtw
            partner = w
            aux = part + 3 * ((wsx[k] + 1) * 3 + (wsy[k] + 1))
    return best, partner, aux


@njit(inline="always")
def _schedule(i, t, x, y, vx, vy, cx, cy, tc, E, gi, gf):
    """The time of disk ``i``'s next event: the earlier of its kept candidate and
    leaving its cell (whose direction is recorded in ``E[i, KIND]``)."""
    dtx, dirx = exit_time(x, vx, cx, gf[2], gi[0], gi[2] != 0)
    dty, diry = exit_time(y, vy, cy, gf[3], gi[1], gi[3] != 0)
    if dty < dtx:
        dtx = dty
        aux = 2 if diry > 0 else 3
    else:
        aux = 0 if dirx > 0 else 1
    E[i, KIND] = (E[i, KIND] & _KIND_MASK) | (aux << 4)
    return min(tc[i], t + dtx)


@njit(inline="always")
def predict(i, t, direction, S, E, tc, stamp, gi, gf, head, nxt,
            wa, wb, wstart, wwall, wsx, wsy):
    """Predict disk ``i``'s next event from time ``t``, keep its best non-crossing
    candidate, and return the time of the scheduled event.

    ``direction = -1``: a full prediction (all 9 neighbour cells, the walls listed for
    its cell, the box walls).  ``direction`` 0-3: ``i`` has just crossed into its
    current cell (not wrapped) in direction +x, -x, +y, -y; if its kept candidate is
    still valid only the newly exposed row of 3 cells (and the cell's walls) is
    scanned against it, otherwise the prediction is a full one.

    (One function for both, compiled into ``run`` at a single place; see there.)
    """
    partial = direction >= 0 and not (
        E[i, KIND] & _KIND_MASK == DISK and stamp[E[i, PARTNER]] != E[i, PSTAMP])
    dt0 = t - S[i, T]
    vx = S[i, VX]
    vy = S[i, VY]
    x = S[i, X] + dt0 * vx
    y = S[i, Y] + dt0 * vy
    r = S[i, R]
    c = E[i, CELL]
    cy = c // gi[0]
    cx = c - cy * gi[0]

    if partial:
        if direction == 0:
            ox0, ox1, oy0, oy1 = 1, 1, -1, 1
        elif direction == 1:
            ox0, ox1, oy0, oy1 = -1, -1, -1, 1
        elif direction == 2:
            ox0, ox1, oy0, oy1 = -1, 1, 1, 1
        else:
            ox0, ox1, oy0, oy1 = -1, 1, -1, -1
        best = tc[i] - t
        kind = NONE  # stays NONE unless something beats the kept candidate
        aux = 0
    else:
        ox0, ox1, oy0, oy1 = -1, 1, -1, 1
        # The three rows of neighbour cells are far apart in memory: request all
        # three at once instead of one after the other inside the scan.
        for oy in range(-1, 2):
            nyc, _ = neighbour(cy, oy, gi[1], gi[3] != 0)
            if nyc >= 0:
                prefetch(head, max(cx - 1, 0) + gi[0] * nyc)
        best = INF
        kind = NONE
        aux = 0
        if gi[2] == 0:
            dtw, side = box_wall_time(x, vx, r, gf[0])
            if dtw < best:
                best = dtw
                kind = BOX
                aux = side
        if gi[3] == 0:
            dtw, side = box_wall_time(y, vy, r, gf[1])
            if dtw < best:
                best = dtw
                kind = BOX
                aux = 2 + side
    partner = -1
    pst = 0
    bd, pd, ad, ps = _scan_disks(i, t, x, y, vx, vy, r, cx, cy, ox0, ox1, oy0, oy1,
                                 S, stamp, gi, gf, head, nxt, best, -1, 0, 0)
    if bd < best:
        best = bd
        kind = DISK
        partner = pd
        aux = ad
        pst = ps
    bw, pw, aw = _scan_walls(x, y, vx, vy, r, c, gf, wa, wb, wstart, wwall, wsx, wsy,
                             best, -1, 0)
    if bw < best:
        best = bw
        kind = SEGMENT
        partner = pw
        aux = aw
        pst = 0
    if not partial or kind != NONE:
        tc[i] = t + best
        E[i, KIND] = kind
        E[i, PARTNER] = partner
        E[i, AUX] = aux
        E[i, PSTAMP] = pst
    return _schedule(i, t, x, y, vx, vy, cx, cy, tc, E, gi, gf)


@njit
def _step_cell(c, up, n):
    """The cell index one step up (``up``) or down an axis of ``n`` cells, and the
    periodic wrap that step makes: +1 past the far edge, -1 past the near one, else 0."""
    if up:
        c += 1
        if c == n:
            return 0, 1
    else:
        c -= 1
        if c < 0:
            return n - 1, -1
    return c, 0


@njit
def _advance(i, t, S):
    dt = t - S[i, T]
    S[i, X] += dt * S[i, VX]
    S[i, Y] += dt * S[i, VY]
    S[i, T] = t


@njit(inline="always")
def _reflect(i, nx, ny, S, invm, acc, slot):
    """Mirror the velocity of disk ``i`` in the unit normal ``n`` (if approaching)."""
    vn = S[i, VX] * nx + S[i, VY] * ny
    if vn < 0.0:
        S[i, VX] -= 2.0 * vn * nx
        S[i, VY] -= 2.0 * vn * ny
        acc[slot] += -2.0 * vn / invm[i]


# Buckets ahead of the current one that the lookahead reaches (see _lookahead)
_AHEAD = 5


@njit(inline="always")
def _prefetch_cells(c, ox0, ox1, oy0, oy1, heads, S, gi, head):
    """Prefetch for the cells at offsets ``[ox0, ox1] x [oy0, oy1]`` from cell ``c``
    their list heads (``heads``), or else the state row (with its list link) of their
    first disks.  A block that crosses an edge of the grid is left out (a hint may miss:
    0.3 % of the cells at N = 10^6), which spares the wrapping arithmetic."""
    ncx = gi[0]
    cy = c // ncx
    cx = c - cy * ncx
    if cx + ox0 < 0 or cx + ox1 >= ncx or cy + oy0 < 0 or cy + oy1 >= gi[1]:
        return
    for oy in range(oy0, oy1 + 1):
        row = (cy + oy) * ncx + cx
        if heads:  # (the row's ends: one cache line, or the two it straddles)
            prefetch(head, row + ox0)
            prefetch(head, row + ox1)
            continue
        for ox in range(ox0, ox1 + 1):
            j = head[row + ox]
            if j >= 0:
                prefetch(S, j)


@njit
def _exposed(direction):
    """Offsets ``(ox0, ox1, oy0, oy1)`` of the cells that a crossing in ``direction``
    (+x, -x, +y, -y) brings into range, from the cell the disk leaves."""
    if direction == 0:
        return 2, 2, -1, 1
    if direction == 1:
        return -2, -2, -1, 1
    if direction == 2:
        return -1, 1, 2, 2
    return -1, 1, -2, -2


@kernel
def _lookahead(opened, cur, first, S, E, qt, tc, gi, head, qhead, mask):
    """Prefetch what the coming events will load (:func:`_lookahead_bucket`), as the
    calendar reaches bucket ``cur`` (its list starting at ``first``, ``qs[FIRST]``)
    after ``opened``, the last bucket this ran for (-1: none).  (A hint only: no effect
    on results.)

    The buckets in between were empty (the calendar stepped over them), but the lists
    ahead of each are due a stage from each: run for ``cur`` alone, 13 % of the lists
    (a bucket holds two events on average, and is empty with probability ``exp(-2)``)
    would each lose one.  Only ``cur`` is run for after a jump of more than ``_AHEAD``
    buckets, or when ``cur`` is not past ``opened`` (the calendar restarted at bucket
    0; a restart that lands past ``opened`` is taken for steps, which costs at most a
    few useless prefetches).
    """
    if opened < 0 or opened < cur - _AHEAD or opened >= cur:
        opened = cur - 1
    while opened < cur:
        opened += 1
        _lookahead_bucket(opened, cur, first, S, E, qt, tc, gi, head, qhead, mask)


@njit(inline="always")
def _lookahead_bucket(b, cur, first, S, E, qt, tc, gi, head, qhead, mask):
    """Prefetch, for the calendar at bucket ``b`` (``cur``, or a bucket before it that
    it stepped over), what the events of that bucket and the next ``_AHEAD`` will
    load, a stage at a time.

    At large N the rows of an event's disk, partner and neighbours are cache misses met
    one after another: a list is walked link by link, the partner and the cell are only
    known from the disk's row, the neighbours only from the cells' list heads.  Here
    the ``k``-th disk (from 0) of the list ``d`` buckets ahead gets stage
    ``_AHEAD - d - k`` (see :func:`_stage`) each time the calendar reaches a bucket,
    so that each stage finds in the caches what the previous one requested a bucket (a
    few events) earlier.  (Not always: a new event joins a list at its head, shifting
    ``k``; a hint that misses costs a miss.)  When the calendar steps over empty buckets
    this runs for each of them too (:func:`_lookahead`), so that no stage is skipped.

    Bucket ``cur`` is the one just reached, whose list ``top`` has moved into the heap:
    it is walked from ``first`` (-1: none), also from a bucket stepped over.  At
    ``d = 0`` the third to sixth disks of that list get one stage more (the third its
    last), which a list of 2-3 events (the calendar's target) would otherwise never
    give them: +3-6 % at N = 10^6, where the scan had waited on their neighbours'
    rows.  Whatever stages the later disks of a long list still lack,
    :func:`_stage_heap` gives them while the bucket's earlier events are processed.

    Stage 0, the disk's bookkeeping row (which holds its list link and queue time),
    is requested here; stages 1-3 by :func:`_stage`.  (Stages 4 and 5, reached by the
    first disks of the nearest lists, have nothing left to fetch.)

    (Measured at N = 10^6 against prefetching also the second disks of the cells, and
    against wrapping at the grid's edges: both cost more than they saved.)
    """
    for d in range(_AHEAD, -1, -1):
        if b + d == cur:
            h = first
        else:  # (a later bucket's list, or none: a bucket stepped over is empty)
            h = qhead[(b + d) & mask] if d > 0 else -1
        for k in range(_AHEAD - d + 1):
            if h < 0:
                break
            stage = _AHEAD - d - k
            if stage == 0:
                prefetch(E, h)
                break
            if stage <= 3:
                _stage(h, stage, S, E, qt, tc, gi, head)
            h = E[h, queue.NEXT]


@njit(inline="always")
def _stage(h, stage, S, E, qt, tc, gi, head):
    """Give disk ``h``'s scheduled event stage ``stage`` (1-3) of the lookahead and
    note it in ``E[h, STAGED]``; ``h``'s bookkeeping row must be in the caches (the
    previous stage requested it).

    1. its state row, its kept partner's two rows, the list heads of its 3x3 cells;
    2. if its event is a cell crossing, the list heads of the cells the crossing
       exposes; otherwise the first disk of each of its 9 cells and the list heads
       of the partner's cells;
    3. the first disks of the exposed cells, or of the partner's cells.
    """
    E[h, STAGED] |= 1 << stage
    # Up to two blocks of cells: ``own`` with the given offsets, and the partner's
    # 3x3 cells (``other``).
    own = np.int64(E[h, CELL])
    other = np.int64(-1)
    partner = E[h, PARTNER] if E[h, KIND] & _KIND_MASK == DISK else -1
    ox0, ox1, oy0, oy1 = -1, 1, -1, 1
    heads = True
    heads_other = True
    if stage == 1:
        prefetch(S, h)
        if partner >= 0:
            prefetch(S, partner)
            prefetch(E, partner)
    elif qt[h] < tc[h]:  # a cell crossing: only the exposed cells
        ox0, ox1, oy0, oy1 = _exposed(E[h, KIND] >> 4)
        heads = stage == 2
    elif stage == 2:
        heads = False
        if partner >= 0:
            other = E[partner, CELL]
    else:
        own = -1
        if partner >= 0:
            other = E[partner, CELL]
            heads_other = False
    # (One call site, no literal arguments: numba compiles a function once per
    # distinct literal argument otherwise.)
    for cell in (own, other):
        if cell >= 0:
            _prefetch_cells(cell, ox0, ox1, oy0, oy1, heads, S, gi, head)
        ox0, ox1, oy0, oy1 = -1, 1, -1, 1
        heads = heads_other


# Heap slots that _stage_heap looks at (the heap of a bucket holds 2-3 events)
_HEAP_STAGED = 8


@njit(inline="always")
def _stage_heap(S, E, qt, tc, gi, head, hv, nheap):
    """Give each event in the current bucket's heap but its root (the event being
    processed) the first stage of the lookahead it still lacks.

    The lookahead's staging leaves the later disks of a long list short: the fourth of
    a list never gets stage 3, the fifth neither 2 nor 3, and an event that joins the
    current bucket none.  Called at each event of a bucket after its first (the
    lookahead's turn), this gives them one stage per event, each finding in the caches
    what the previous one requested.  At N = 10^6 the neighbour rows that predictions
    found neither fetched nor used in the last 16 000 events fell from 1.55 to 0.95
    per collision, and with :func:`_lookahead`'s steps over empty buckets to 0.83
    (of 12.2 scanned); the speed rose by 6-7 % (each change alone: 2-3 %).
    """
    for slot in range(1, min(nheap, _HEAP_STAGED)):
        h = hv[slot]
        done = E[h, STAGED]
        stage = 1 if done & 2 == 0 else (2 if done & 4 == 0 else (3 if done & 8 == 0 else 0))
        if stage > 0:
            _stage(h, stage, S, E, qt, tc, gi, head)


@kernel
def run(t_end, max_collisions, max_events,
        S, E, stamp, nxt, prv, qt, tc, invm, image, gi, gf, head,
        wa, wb, wstart, wwall, wsx, wsy,
        hv, qhead, qs, qf,
        counts, acc, out, info, log_t, log_e, log_n, order, mode):
    """Process events in time order (``mode`` RUN_EVENTS), or (``mode`` PREDICT_ALL)
    predict every disk's next event from the time ``out[0]`` and rebuild the queue.

    (Both share the one place where the full prediction is compiled into this
    function: inlined, it is about 18 % faster than a call, and a second copy would
    add about 4 s to the first compilation.)

    Stops before the first event later than ``t_end``, right after the
    ``max_collisions``-th disk-disk collision of this call, or after ``max_events``
    processed events.  ``out[0]`` receives the time of the last processed event (or is
    left unchanged if none was processed).  Returns a status code; on an error the
    offending disks (or disk and wall) are written to ``info`` and the state is left as
    it was just before that event.

    If ``log_t`` has room, every disk-disk, segment and box-wall event is recorded as
    ``log_t[k]``, ``log_e[k] = (kind, i, partner)`` with ``log_n[0]`` counting them all;
    disks are recorded by their user index ``order[i]``.
    """
    ncx = gi[0]
    ncy = gi[1]
    width = gf[0]
    height = gf[1]
    log_cap = log_t.shape[0]
    n_coll = 0
    n_ev = 0
    status = REACHED_TIME
    t = out[0]
    # (Set per event below; defined here too because PREDICT_ALL skips that part.)
    i = -1
    kind = NONE
    partner = -1
    aux = 0
    redo0 = -1
    redo1 = -1
    direction = -1
    stale = False
    t_redo0 = INF
    t_redo1 = INF
    opened = np.int64(-1)  # the calendar bucket the lookahead last ran for (int64: one
    # compiled _lookahead, not a second for the literal)
    qs[queue.FIRST] = -1  # (left by an earlier call: its list may have changed since)
    while True:
        if mode == PREDICT_ALL:
            npred = S.shape[0]
        else:
            i = queue.top(qt, E, hv, qhead, qs, qf)
            if i < 0:
                status = NO_EVENTS
                break
            if qs[queue.LOOKAHEAD] != 0:
                if qs[queue.CUR] != opened:
                    _lookahead(opened, qs[queue.CUR], qs[queue.FIRST], S, E, qt, tc, gi,
                               head, qhead, qs[queue.MASK])
                    opened = qs[queue.CUR]
                else:
                    _stage_heap(S, E, qt, tc, gi, head, hv, qs[queue.NHEAP])
            t = qt[i]
            # The next events are most likely those of the heap root's children: start
            # loading their rows now (at large N each is a cache miss otherwise).
            if qs[queue.NHEAP] > 1:
                k = hv[1]
                prefetch(S, k)
                prefetch(E, k)
                if qs[queue.NHEAP] > 2:
                    k = hv[2]
                    prefetch(S, k)
                    prefetch(E, k)
            if t > t_end:
                status = REACHED_TIME
                break
            if n_ev >= max_events:
                status = REACHED_EVENT_LIMIT
                break
            if t < tc[i]:
                kind = CROSS
                partner = -1
                aux = E[i, KIND] >> 4
            else:
                kind = E[i, KIND] & _KIND_MASK
                partner = E[i, PARTNER]
                aux = E[i, AUX]
            # Disks whose events must be predicted afresh once this event is handled.
            redo0 = -1
            redo1 = -1
            direction = -1  # of a cell crossing of i, for a partial prediction
            stale = False

            if kind == DISK:
                j = partner
                if stamp[j] != E[i, PSTAMP]:
                    # The partner changed course since this was predicted: re-predict i only.
                    redo0 = i
                    stale = True
                elif invm[i] == 0.0 and invm[j] == 0.0:
                    info[0] = i
                    info[1] = j
                    status = ERR_IMMOVABLE_PAIR
                    break
                else:
                    _advance(i, t, S)
                    _advance(j, t, S)
                    sx = aux // 3 - 1
                    sy = aux % 3 - 1
                    dx = S[i, X] - (S[j, X] + sx * width)
                    dy = S[i, Y] - (S[j, Y] + sy * height)
                    dist = math.sqrt(dx * dx + dy * dy)
                    nx = dx / dist
                    ny = dy / dist
                    dvn = (S[i, VX] - S[j, VX]) * nx + (S[i, VY] - S[j, VY]) * ny
                    if dvn < 0.0:
                        # Impulse J along n: momentum J n moves from j to i; with the reduced
                        # mass this reverses the normal relative velocity (elastic).
                        wi = invm[i]
                        wj = invm[j]
                        impulse = -2.0 * dvn / (wi + wj)
                        S[i, VX] += impulse * wi * nx
                        S[i, VY] += impulse * wi * ny
                        S[j, VX] -= impulse * wj * nx
                        S[j, VY] -= impulse * wj * ny
                        jr = impulse * dist
                        acc[A_VIRIAL] += jr
                        acc[A_VIRIAL_XX] += jr * nx * nx
                        acc[A_VIRIAL_YY] += jr * ny * ny
                    # A contact that rounding left not approaching exchanges nothing but is a
                    # processed contact event like any other (as for walls, and as in the
                    # reference): counted, logged, both disks re-predicted.
                    counts[C_COLLISIONS] += 1
                    n_coll += 1
                    stamp[i] += 1
                    stamp[j] += 1
                    redo0 = i
                    redo1 = j
            elif kind == SEGMENT or kind == BOX:
                if invm[i] == 0.0:
                    info[0] = i
                    info[1] = partner if kind == SEGMENT else -1 - aux
                    status = ERR_IMMOVABLE_WALL
                    break
                _advance(i, t, S)
                if kind == BOX:
                    # Lower wall: normal +e; upper wall: normal -e.
                    sign = 1.0 if aux % 2 == 0 else -1.0
                    nx = sign if aux < 2 else 0.0
                    ny = 0.0 if aux < 2 else sign
                    slot = A_BOX + aux
                else:
                    part = aux % 3
                    code = aux // 3
                    shx = (code // 3 - 1) * width
                    shy = (code % 3 - 1) * height
                    ax = wa[partner, 0] + shx
                    ay = wa[partner, 1] + shy
                    bx = wb[partner, 0] + shx
                    by = wb[partner, 1] + shy
                    if part == 0:
                        ux = bx - ax
                        uy = by - ay
                        ln = math.sqrt(ux * ux + uy * uy)
                        nx = -uy / ln
                        ny = ux / ln
                        if (S[i, X] - ax) * nx + (S[i, Y] - ay) * ny < 0.0:
                            nx = -nx
                            ny = -ny
                    else:
                        ex = ax if part == 1 else bx
                        ey = ay if part == 1 else by
                        nx = S[i, X] - ex
                        ny = S[i, Y] - ey
                        ln = math.sqrt(nx * nx + ny * ny)
                        nx /= ln
                        ny /= ln
                    slot = A_SEGMENTS
                # (One call site: each inlined copy lengthens the first compilation.)
                _reflect(i, nx, ny, S, invm, acc, slot)
                stamp[i] += 1
                redo0 = i
                counts[C_WALL] += 1
            else:  # CROSS
                _advance(i, t, S)
                c = E[i, CELL]
                cy = c // ncx
                cx = c - cy * ncx
                axis = aux >> 1  # directions 0, 1: +x, -x; 2, 3: +y, -y
                if axis == 0:
                    cx, wrap = _step_cell(cx, aux == 0, ncx)
                else:
                    cy, wrap = _step_cell(cy, aux == 2, ncy)
                wrapped = wrap != 0
                if wrapped:
                    S[i, X + axis] -= wrap * gf[axis]
                    image[i, axis] += wrap
                remove(i, c, head, nxt, prv)
                c = cx + ncx * cy
                insert(i, c, head, nxt, prv)
                E[i, CELL] = c
                if wrapped:
                    # Other disks' predictions hold i's image shift: invalidate them, and
                    # the kept candidate of i is in the old frame: predict afresh.
                    stamp[i] += 1
                    redo0 = i
                else:
                    redo0 = i
                    direction = aux
                counts[C_CROSSINGS] += 1

            npred = 0 if redo0 < 0 else (1 if redo1 < 0 else 2)

        # (One call site each for the prediction and the queue update: both are
        # compiled into the loop, and a second copy would lengthen compilation.)
        # Both disks are predicted before either is re-queued, so that the queue lines
        # the first update needs are loading while the second disk is predicted.
        for k in range(npred):
            if mode == PREDICT_ALL:
                d = k
                dk = -1
            else:
                d = redo0 if k == 0 else redo1
                dk = direction if k == 0 else -1
            t_new = predict(d, t, dk, S, E, tc, stamp, gi, gf, head, nxt,
                            wa, wb, wstart, wwall, wsx, wsy)
            E[d, STAGED] = 0  # (a new event: no stage of the lookahead yet)
            if mode == PREDICT_ALL:
                qt[d] = t_new
            else:
                queue.prefetch_update(d, t_new, E, qhead, qs, qf)
                if k == 0:
                    t_redo0 = t_new
                else:
                    t_redo1 = t_new
        if mode == PREDICT_ALL:
            queue.build(t, qt, qt, E, hv, qhead, qs, qf)
            break
        for k in range(npred):
            queue.set_time(redo0 if k == 0 else redo1, t_redo0 if k == 0 else t_redo1,
                           qt, E, hv, qhead, qs, qf)
        if stale:
            counts[C_STALE] += 1
            continue

        n_ev += 1
        out[0] = t
        if kind != CROSS and log_cap > 0:
            k = log_n[0]
            if k < log_cap:
                log_t[k] = t
                log_e[k, 0] = kind
                log_e[k, 1] = order[i]
                if kind == DISK:
                    log_e[k, 2] = order[partner]
                else:
                    log_e[k, 2] = partner if kind == SEGMENT else aux
            log_n[0] = k + 1
        if n_coll >= max_collisions:
            status = REACHED_COLLISIONS
            break
    return status


@njit
def synchronized_positions(t, S, gi, gf, out):
    """Positions of all disks at time ``t`` (>= every local time), wrapped into the box."""
    for i in range(S.shape[0]):
        dt = t - S[i, T]
        x = S[i, X] + dt * S[i, VX]
        y = S[i, Y] + dt * S[i, VY]
        if gi[2] != 0:
            x -= gf[0] * math.floor(x / gf[0])
        if gi[3] != 0:
            y -= gf[1] * math.floor(y / gf[1])
        out[i, 0] = x
        out[i, 1] = y
