"""Calendar queue (after Paul 2007) holding exactly one scheduled event time per disk.

Time is cut into buckets of width ``1 / qf[INVW]`` counted from ``qf[ORIGIN]``: an event
at time ``t`` belongs to bucket ``floor((t - origin) * invw)``.  The buckets of the
current *year*, ``qs[CUR] <= b < qs[CUR] + nb`` with ``nb`` a power of two, are ``nb``
unsorted doubly linked lists (list ``b mod nb``); later events wait in one overflow
list.  Only the current bucket is kept sorted, as a small binary heap.  Inserting or
removing an event is then O(1) (a list link, or a heap of a few entries) instead of a
walk down a heap of ``N`` entries, with its mispredicted branches and, at large N,
cache misses.

The order of events is exact: buckets partition time, and inside the current bucket
the heap orders by ``(time, disk index)``, so simultaneous
events keep a deterministic order.  Bucket numbers come from one monotonic float
expression, so an earlier time never lands in a later bucket.

Arrays (``N`` disks):

``qt[i]``
    the scheduled time of disk ``i`` (``inf``: nothing scheduled, not queued): a
    strided view of the float64 column ``QT`` of the engine's per-disk table ``E``
    (``E.view(np.float64)[:, QT]``), so that it shares the disk's cache line with its
    links;
``ql[i, NEXT]``, ``ql[i, PREV]``, ``ql[i, LOC]``
    (int32 columns of ``E``, whose other columns belong to the event loop, see
    layout.py) ``NEXT``/``PREV`` link ``i`` in its bucket list; ``LOC`` is ``i``'s slot
    in the heap if ``>= 0``, ``-1`` if not queued, or ``-2 - list`` if in list
    ``list`` (``nb`` is the overflow list);
``hv[k]`` (int32)
    the heap of the current bucket: the disk at slot ``k``;
``qhead[nb + 1]``
    the first disk of each list (``-1``: empty);
``qs`` (int64) and ``qf`` (float64)
    the scalars below.

The bucket width adapts: it is chosen at :func:`build` from the (trimmed) mean time to
the next event.  Every ``2 nb`` heap insertions plus bucket steps the occupancy is
checked: if the buckets held on average more than 8x or less than 1/8 of the target of
two events, every queued event is re-placed with a width scaled to match (O(N),
amortised over those ``2 nb`` operations).  When the heap and all lists of the year
are empty the calendar jumps: it restarts at the earliest overflow event instead of
stepping through empty buckets.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import kernel, njit
from . import aligned_rows, prefetch
from .layout import LOC, N_E, NEXT, PREV, QT

INF = math.inf

# Columns of ql (the engine's table E, declared in layout.py): int32 columns, and the
# float64 column (of E.view(np.float64)) that holds qt.  One row is 64 bytes.
N_QL = N_E
# qs: current bucket, heap size, events in the year's lists, events in overflow,
# nb - 1, bucket at which the overflow is next scanned, heap insertions and bucket
# steps since the bucket width was last checked, whether the event loop prefetches
# ahead along the lists (1) or not (0; see lookahead.py), and the first disk of
# the list that ``top`` last moved into the heap (-1 if the heap was filled otherwise):
# its links run through that list only until one of the heap's disks is re-queued, so
# it means something only right after the ``top`` that set it.
CUR, NHEAP, NLIST, NOVER, MASK, BOUNDARY, LOADED, ADVANCED, LOOKAHEAD, FIRST = range(10)
N_QS = 10
# From this many disks on the working set has left the caches and the lookahead pays;
# below, it costs more than it saves (measured in docs/performance-notes.md).
LOOKAHEAD_MIN_DISKS = 2 ** 15
# qf: time origin of bucket 0, inverse bucket width
ORIGIN, INVW = 0, 1
N_QF = 2

TARGET_PER_BUCKET = 2.0
_MAX_INVW = 1e300  # (finite: see _replace_all)
_RETUNE_FACTOR = 8.0


def allocate(n):
    """Arrays for a queue of ``n`` disks: ``(qt, ql, hv, qhead, qs, qf)``; ``ql`` is
    the engine's whole per-disk table ``E`` (64-byte rows, 64-byte aligned; columns
    the queue does not use start as -1) and ``qt`` a view of its column ``QT``."""
    nb = 16
    while nb < n:
        nb *= 2
    qs = np.zeros(N_QS, np.int64)
    qs[MASK] = nb - 1
    qs[FIRST] = -1
    qs[LOOKAHEAD] = 1 if n >= LOOKAHEAD_MIN_DISKS else 0
    qf = np.zeros(N_QF, np.float64)
    qf[INVW] = 1.0
    ql = aligned_rows(n, N_QL, np.int32)
    ql[:] = -1
    qt = ql.view(np.float64)[:, QT]
    qt[:] = INF
    return qt, ql, np.full(n, -1, np.int32), np.full(nb + 1, -1, np.int32), qs, qf


@njit(inline="always")
def _before(qt, a, b):
    ta = qt[a]
    tb = qt[b]
    return ta < tb or (ta == tb and a < b)


@kernel
def _sift_up(qt, ql, hv, k):
    """Move the heap entry at slot ``k`` up while earlier than its parent; its slot."""
    i = hv[k]
    while k > 0:
        p = (k - 1) >> 1
        j = hv[p]
        if _before(qt, i, j):
            hv[k] = j
            ql[j, LOC] = k
            k = p
        else:
            break
    hv[k] = i
    ql[i, LOC] = k
    return k


@kernel
def _sift_down(qt, ql, hv, n, k):
    """Move the heap entry at slot ``k`` down while a child is earlier."""
    i = hv[k]
    while True:
        c = 2 * k + 1
        if c >= n:
            break
        j = hv[c]
        if c + 1 < n:
            j2 = hv[c + 1]
            if _before(qt, j2, j):
                c += 1
                j = j2
        if _before(qt, j, i):
            hv[k] = j
            ql[j, LOC] = k
            k = c
        else:
            break
    hv[k] = i
    ql[i, LOC] = k


@njit(inline="always")
def _heap_push(i, qt, ql, hv, qs):
    n = qs[NHEAP]
    hv[n] = i
    qs[NHEAP] = n + 1
    qs[LOADED] += 1
    _sift_up(qt, ql, hv, n)


@njit(inline="always")
def _link(i, lst, ql, qhead):
    h = qhead[lst]
    ql[i, NEXT] = h
    ql[i, PREV] = -1
    if h >= 0:
        ql[h, PREV] = i
    qhead[lst] = i
    ql[i, LOC] = -2 - lst


@kernel
def _link_at(i, x, ql, qhead, qs):
    """Link disk ``i`` into the list of bucket ``x`` (not the current one), or the
    overflow list beyond the year.  (A call with few array arguments: numba passes each
    array field by field, and the event loop calls this twice per collision.)"""
    nb = qs[MASK] + 1
    if x < qs[CUR] + nb:
        _link(i, np.int64(x) & qs[MASK], ql, qhead)
        qs[NLIST] += 1
    else:
        _link(i, nb, ql, qhead)
        qs[NOVER] += 1


@kernel
def _place(i, qt, ql, hv, qhead, qs, qf):
    """Queue disk ``i`` (not queued) at its time ``qt[i]``."""
    t = qt[i]
    if t == INF:
        ql[i, LOC] = -1
        return
    x = (t - qf[ORIGIN]) * qf[INVW]
    if x < qs[CUR] + 1:
        _heap_push(i, qt, ql, hv, qs)
    else:
        _link_at(i, x, ql, qhead, qs)


@njit(inline="always")
def _take(i, qt, ql, hv, qhead, qs):
    """Take disk ``i`` out of the queue (wherever it is)."""
    loc = np.int64(ql[i, LOC])  # (int64: one compiled _sift_up for every caller)
    if loc >= 0:
        n = qs[NHEAP] - 1
        qs[NHEAP] = n
        if loc < n:
            last = hv[n]
            hv[loc] = last
            if _sift_up(qt, ql, hv, loc) == loc:
                _sift_down(qt, ql, hv, n, loc)
    elif loc <= -2:
        lst = -2 - loc
        p = ql[i, PREV]
        nx = ql[i, NEXT]
        if p >= 0:
            ql[p, NEXT] = nx
        else:
            qhead[lst] = nx
        if nx >= 0:
            ql[nx, PREV] = p
        if lst == qs[MASK] + 1:
            qs[NOVER] -= 1
        else:
            qs[NLIST] -= 1
    ql[i, LOC] = -1


@njit(inline="always")
def set_time(i, t, qt, ql, hv, qhead, qs, qf):
    """Give disk ``i`` the event time ``t`` (``inf``: none) and restore the queue."""
    loc = np.int64(ql[i, LOC])
    if loc >= 0 and (t - qf[ORIGIN]) * qf[INVW] < qs[CUR] + 1:
        # Stays in the current bucket: reposition inside the heap.  (Counted as a
        # load: with buckets far too wide every event lands here.)
        qt[i] = t
        qs[LOADED] += 1
        if _sift_up(qt, ql, hv, loc) == loc:
            _sift_down(qt, ql, hv, qs[NHEAP], loc)
        return
    _take(i, qt, ql, hv, qhead, qs)
    qt[i] = t
    # The common case, a later bucket's list, through a call with few arrays (numba
    # passes each array field by field); the heap and "none" through _place.
    x = (t - qf[ORIGIN]) * qf[INVW]
    if t < INF and x >= qs[CUR] + 1:
        _link_at(i, x, ql, qhead, qs)
    else:
        _place(i, qt, ql, hv, qhead, qs, qf)


@njit(inline="always")
def prefetch_update(i, t, ql, qhead, qs, qf):
    """Start loading what ``set_time(i, t, ...)`` will touch: the list neighbours that
    taking ``i`` out of its list relinks, and the head of the list that receives it.
    (A hint only; at large N each is otherwise a cache miss met one after the other.)"""
    loc = ql[i, LOC]
    if loc <= -2:
        p = ql[i, PREV]
        if p >= 0:
            prefetch(ql, p)
        else:
            prefetch(qhead, -2 - loc)
        nx = ql[i, NEXT]
        if nx >= 0:
            prefetch(ql, nx)
    x = (t - qf[ORIGIN]) * qf[INVW]
    cur = qs[CUR]
    if cur + 1 <= x < cur + qs[MASK] + 1:
        prefetch(qhead, np.int64(x) & qs[MASK])


@kernel
def _replace_all(invw, qt, ql, hv, qhead, qs, qf):
    """Re-place every queued event with bucket width ``1 / invw``, bucket 0 starting at
    the earliest of them.

    ``invw`` is capped at ``_MAX_INVW``: when the clock stops advancing (events piling
    up at one time, as in an inelastic collapse) every retune narrows the buckets, and
    an infinite ``invw`` would make ``(t - origin) * invw`` a NaN (``0 * inf``), which
    no bucket holds."""
    invw = min(invw, _MAX_INVW)
    n = qt.shape[0]
    t0 = INF
    for i in range(n):
        if ql[i, LOC] != -1 and qt[i] < t0:
            t0 = qt[i]
    for k in range(qhead.shape[0]):
        qhead[k] = -1
    qs[NHEAP] = 0
    qs[NLIST] = 0
    qs[NOVER] = 0
    qs[CUR] = 0
    qs[BOUNDARY] = qs[MASK] + 1
    qs[LOADED] = 0
    qs[ADVANCED] = 0
    qs[FIRST] = -1
    qf[ORIGIN] = t0 if t0 < INF else 0.0
    qf[INVW] = invw
    for i in range(n):
        if ql[i, LOC] != -1:
            ql[i, LOC] = -1
            _place(i, qt, ql, hv, qhead, qs, qf)


@kernel
def _scan_overflow(restart, qt, ql, hv, qhead, qs, qf):
    """Move the overflow events that now fall inside the year into their lists.  With
    ``restart`` the calendar first restarts at the earliest of them (bucket 0)."""
    nb = qs[MASK] + 1
    chain = np.int64(qhead[nb])
    qhead[nb] = -1
    qs[NOVER] = 0
    if restart:
        t0 = INF
        i = chain
        while i >= 0:
            t0 = min(t0, qt[i])
            i = ql[i, NEXT]
        # The empty buckets jumped over count as steps for the retuning (capped: the
        # gap may be astronomically many buckets).
        qs[ADVANCED] += np.int64(min((t0 - qf[ORIGIN]) * qf[INVW] - qs[CUR], 2.0 ** 40))
        qf[ORIGIN] = t0
        qs[CUR] = 0
    qs[BOUNDARY] = qs[CUR] + nb
    i = chain
    while i >= 0:
        nx = np.int64(ql[i, NEXT])  # (int64: one compiled _place for every caller)
        _place(i, qt, ql, hv, qhead, qs, qf)
        i = nx


@njit(inline="always")
def top(qt, ql, hv, qhead, qs, qf):
    """The disk with the earliest event, or -1 if nothing is scheduled.

    Advances the calendar to the first non-empty bucket if the current one is done.
    """
    nb = qs[MASK] + 1
    if qs[LOADED] + qs[ADVANCED] >= 2 * nb:
        # Retune the bucket width from the events per bucket actually seen.
        per_bucket = qs[LOADED] / max(qs[ADVANCED], 1)
        if (per_bucket > _RETUNE_FACTOR * TARGET_PER_BUCKET
                or per_bucket * _RETUNE_FACTOR < TARGET_PER_BUCKET):
            _replace_all(qf[INVW] * per_bucket / TARGET_PER_BUCKET, qt, ql, hv, qhead, qs, qf)
        qs[LOADED] = 0
        qs[ADVANCED] = 0
    while qs[NHEAP] == 0:
        if qs[NLIST] == 0:
            if qs[NOVER] == 0:
                return np.int64(-1)
            # (``restart`` as a value known only at run time, True here and False
            # below: a literal would compile the function once for each.)
            _scan_overflow(qs[NLIST] == 0, qt, ql, hv, qhead, qs, qf)
            qs[FIRST] = -1
            continue
        cur = qs[CUR] + 1
        qs[CUR] = cur
        qs[ADVANCED] += 1
        if cur >= qs[BOUNDARY]:
            _scan_overflow(qs[NLIST] == 0, qt, ql, hv, qhead, qs, qf)
        lst = cur & qs[MASK]
        i = qhead[lst]
        qhead[lst] = -1
        qs[FIRST] = i
        while i >= 0:
            nx = ql[i, NEXT]
            qs[NLIST] -= 1
            _heap_push(i, qt, ql, hv, qs)
            i = nx
    return np.int64(hv[0])


@kernel
def build(now, times, qt, ql, hv, qhead, qs, qf):
    """Queue every disk at ``times[i]`` (all ``>= now``; ``inf``: none), choosing the
    bucket width so that the current rate of events fills about two per bucket."""
    n = times.shape[0]
    # The mean wait, recomputed without the waits beyond four times the mean: a few
    # very slow disks must not widen every bucket.  (Only a starting value: the width
    # is retuned from the events actually seen.)
    wait = 0.0
    queued = 0
    for sweep in range(2):
        limit = 4.0 * wait if sweep == 1 else INF
        count = 0
        total = 0.0
        for i in range(n):
            w = times[i] - now
            if times[i] < INF and w <= limit:
                count += 1
                total += w
        if sweep == 0:
            queued = count
        if count > 0:
            wait = total / count
    invw = 1.0
    if wait > 0.0:
        invw = queued / (TARGET_PER_BUCKET * wait)
    for i in range(n):
        qt[i] = times[i]
        ql[i, LOC] = 0 if times[i] < INF else -1
    _replace_all(invw, qt, ql, hv, qhead, qs, qf)
