"""The lookahead: prefetch hints for the events the calendar queue will process next.

From ``queue.LOOKAHEAD_MIN_DISKS`` disks on, the working set no longer fits the caches
and every event would wait, one miss after another, for its disk's rows, its partner's,
its cells' list heads and its neighbours' rows.  Each time the calendar reaches a new
bucket, :func:`lookahead` therefore prefetches these for the events of that bucket and
the next few, one stage of that chain per bucket, and between the events of a bucket
:func:`stage_heap` gives its remaining events the stages they still lack.

Invariant: these functions only prefetch and note the stages given in
``E[:, STAGED]``; every event and all other state are bit-identical with them on or
off (tested by forcing them on for small systems).
"""

from __future__ import annotations

import numpy as np

from .._jit import kernel, njit
from . import prefetch
from .layout import CELL, DISK, KIND, NEXT, PARTNER, STAGED, direction_of, kind_of

# Buckets ahead of the current one that the lookahead reaches (see _lookahead)
_AHEAD = 5


@njit(inline="always")
def _prefetch_cells(c, ox0, ox1, oy0, oy1, heads, S, gi, head):
    """Prefetch for the cells at offsets ``[ox0, ox1] x [oy0, oy1]`` from cell ``c``
    their list heads (``heads``), or else the state row (with its list link) of their
    first disks.  A block that crosses an edge of the grid is left out (a hint may
    miss), which spares the wrapping arithmetic."""
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
def lookahead(opened, cur, first, S, E, qt, tcand, gi, head, qhead, mask):
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
        _lookahead_bucket(opened, cur, first, S, E, qt, tcand, gi, head, qhead, mask)


@njit(inline="always")
def _lookahead_bucket(b, cur, first, S, E, qt, tcand, gi, head, qhead, mask):
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
    this runs for each of them too (:func:`lookahead`), so that no stage is skipped.

    Bucket ``cur`` is the one just reached, whose list ``top`` has moved into the heap:
    it is walked from ``first`` (-1: none), also from a bucket stepped over.  At
    ``d = 0`` the third to sixth disks of that list get one stage more (the third its
    last), which a list of 2-3 events (the calendar's target) would otherwise never
    give them.  Whatever stages the later disks of a long list still lack,
    :func:`stage_heap` gives them while the bucket's earlier events are processed.

    Stage 0, the disk's bookkeeping row (which holds its list link and queue time),
    is requested here; stages 1-3 by :func:`_stage`.  (Stages 4 and 5, reached by the
    first disks of the nearest lists, have nothing left to fetch.)
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
                _stage(h, stage, S, E, qt, tcand, gi, head)
            h = E[h, NEXT]


@njit(inline="always")
def _stage(h, stage, S, E, qt, tcand, gi, head):
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
    partner = E[h, PARTNER] if kind_of(E[h, KIND]) == DISK else -1
    ox0, ox1, oy0, oy1 = -1, 1, -1, 1
    heads = True
    heads_other = True
    if stage == 1:
        prefetch(S, h)
        if partner >= 0:
            prefetch(S, partner)
            prefetch(E, partner)
    elif qt[h] < tcand[h]:  # a cell crossing: only the exposed cells
        ox0, ox1, oy0, oy1 = _exposed(direction_of(E[h, KIND]))
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
def stage_heap(S, E, qt, tcand, gi, head, hv, nheap):
    """Give each event in the current bucket's heap but its root (the event being
    processed) the first stage of the lookahead it still lacks.

    The lookahead's staging leaves the later disks of a long list short: the fourth of
    a list never gets stage 3, the fifth neither 2 nor 3, and an event that joins the
    current bucket none.  Called at each event of a bucket after its first (the
    lookahead's turn), this gives them one stage per event, each finding in the caches
    what the previous one requested.
    """
    for slot in range(1, min(nheap, _HEAP_STAGED)):
        h = hv[slot]
        done = E[h, STAGED]
        stage = 1 if done & 2 == 0 else (2 if done & 4 == 0 else (3 if done & 8 == 0 else 0))
        if stage > 0:
            _stage(h, stage, S, E, qt, tcand, gi, head)

