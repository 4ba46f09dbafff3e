"""Calendar queue (after Paul 2007) holding exactly one scheduled event time per disk.

Time is cut into buckets of width ``1 / qf[INVW]`` counted from ``qf[ORIGIN]``: an event
at time ``t`` belongs to bucket ``floor((t - origin) * invw)``.  The buckets of the
current *year*, ``qs[CUR] <= b < qs[CUR] + nb`` with ``nb`` a power of two, are ``nb``
unsorted lists (list ``b mod nb``); later events wait in one overflow list.  Only the
current bucket is kept sorted, as a small binary heap.  Inserting or removing an event
is then O(1) instead of a walk down a heap of ``N`` entries.

The order of events is exact: buckets partition time, and inside the current bucket
the heap orders by ``(time, disk index)``, so simultaneous events keep a deterministic
order.  Bucket numbers come from one monotonic float expression, so an earlier time
never lands in a later bucket.

Memory layout, chosen for large N where every access to a random disk is a cache miss:
a list is an array of disk indices in 64-byte *blocks* (one cache line each: a link,
a count and 14 indices), not a chain through the disks.  Inserting a disk into a list,
or removing it, then touches that list's block only, never another disk's data, and
the disks of the next bucket can be read off one line and prefetched before they are
needed.  Each year list owns a home block (row ``L`` of ``qb``) and borrows further
blocks from a pool only while it holds more than 14 disks.  The overflow list is a
chain of pool blocks with lazy removal: a disk leaving it is only marked (its ``LOC``),
and its stale entries are dropped when the overflow is next scanned (once a year), or
compacted earlier if the pool runs short.

Arrays (``N`` disks):

``qt[i]``
    the scheduled time of disk ``i`` (``inf``: nothing scheduled, not queued); a
    strided float64 view of columns 6-7 of the per-disk table, so that it shares the
    disk's row;
``ql[i, LOC]``
    (int32; column 5 of the engine's per-disk table ``E``, whose first columns belong to
    the event loop) ``i``'s slot in the heap if ``>= 0``; ``NOT_QUEUED``; ``IN_YEAR``
    (in list ``floor((qt[i] - origin) * invw) mod nb``); ``IN_OVERFLOW``;
``hv[k]`` (int32)
    the heap of the current bucket: the disk at slot ``k``;
``qb[k]`` (int32, 16 per row)
    blocks: ``qb[k, B_NEXT]`` the next block of the chain (-1: none), ``qb[k, B_COUNT]``
    the disks in the list (home blocks: in the whole list; overflow blocks: in this
    block), ``qb[k, B_IDS:]`` the disks; rows ``0 .. nb-1`` are the home blocks, the
    rest the pool (unused ones chained from ``qs[FREE]``);
``qs`` (int64) and ``qf`` (float64)
    the scalars below.

A year list of ``m`` disks fills its blocks in order: all but the last are full.  A
removal moves the list's last disk into the hole (found by scanning the list: usually
one cache line) and returns an emptied pool block.

The bucket width adapts: it is chosen at :func:`build` from the (trimmed) mean time to
the next event.  Every ``2 nb`` heap insertions plus bucket steps the occupancy is
checked: if the buckets held on average more than 8x or less than 1/8 of the target,
every queued event is re-placed with a width scaled to match (O(N), amortised over
those ``2 nb`` operations).  When the heap and all lists of the year are empty the
calendar jumps: it restarts at the earliest overflow event instead of stepping through
empty buckets.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import kernel, njit
from . import aligned_rows, prefetch

INF = math.inf

# Column of ql (the engine's table E, see loop.py) and its values besides heap slots;
# columns QT_COLUMNS of E hold qt.
LOC = 5
QT_COLUMNS = (6, 7)
N_QL = 8
NOT_QUEUED = -1
IN_YEAR = -2
IN_OVERFLOW = -3
_CLAIMED = -4  # transient, while the overflow is scanned
# Jobs of _rare
INSERT, REMOVE, KEEP, DETACH = 0, 1, 2, 3

# Blocks: link, count, disks
B_NEXT, B_COUNT, B_IDS = 0, 1, 2
B_WIDTH = 16
B_CAP = B_WIDTH - B_IDS

# qs: current bucket, heap size, disks in the year's lists, disks in the overflow,
# nb - 1, bucket at which the overflow is next scanned, heap insertions and bucket
# steps since the bucket width was last checked, first free pool block, first block of
# the overflow chain.
CUR, NHEAP, NLIST, NOVER, MASK, BOUNDARY, LOADED, ADVANCED, FREE, OVER = range(10)
N_QS = 10
# qf: time origin of bucket 0, inverse bucket width
ORIGIN, INVW = 0, 1
N_QF = 2

# Events per bucket the width is tuned for, and disks per year list (nb ~ N / this).
TARGET_PER_BUCKET = 2.0
DISKS_PER_LIST = 2
_RETUNE_FACTOR = 8.0


def allocate(n):
    """Arrays for a queue of ``n`` disks: ``(qt, ql, hv, qb, qs, qf)``; ``ql`` is the
    engine's whole per-disk table ``E`` (32-byte rows, 32-byte aligned) and ``qt`` a
    view of two of its columns."""
    nb = 16
    while nb * DISKS_PER_LIST < n:
        nb *= 2
    # Enough pool blocks that compacting the overflow always frees some: the live
    # disks never need more than n / 14 + 1 of them (see _rare).
    pool = n // B_CAP + n // (2 * B_CAP) + 8
    qb = aligned_rows(nb + pool, B_WIDTH, np.int32, align=64)
    qs = np.zeros(N_QS, np.int64)
    qs[MASK] = nb - 1
    qf = np.zeros(N_QF, np.float64)
    qf[INVW] = 1.0
    ql = aligned_rows(n, N_QL, np.int32, align=32)
    ql[:] = -1
    qt = ql.view(np.float64)[:, QT_COLUMNS[0] // 2]
    qt[:] = INF
    # (What _reset_blocks does, in numpy: nothing to compile here.)
    qb[:nb, B_NEXT] = -1
    qb[:, B_COUNT] = 0
    qb[nb:, B_NEXT] = np.arange(nb + 1, nb + pool + 1)
    qb[-1, B_NEXT] = -1
    qs[FREE] = nb
    qs[OVER] = -1
    return qt, ql, np.full(n, -1, np.int32), qb, qs, qf


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
def _reset_blocks(qb, qs):
    """Empty every list and return all pool blocks to the free chain."""
    nb = qs[MASK] + 1
    nblocks = qb.shape[0]
    for k in range(nb):
        qb[k, B_NEXT] = -1
        qb[k, B_COUNT] = 0
    for k in range(nb, nblocks):
        qb[k, B_NEXT] = k + 1 if k + 1 < nblocks else -1
        qb[k, B_COUNT] = 0
    qs[FREE] = nb if nblocks > nb else -1
    qs[OVER] = -1


@njit(inline="always")
def _free(k, qb, qs):
    qb[k, B_NEXT] = qs[FREE]
    qs[FREE] = k


@njit(inline="always")
def _pop_free(qb, qs):
    k = qs[FREE]
    qs[FREE] = qb[k, B_NEXT]
    qb[k, B_NEXT] = -1
    qb[k, B_COUNT] = 0
    return k


@njit(inline="always")
def _alloc(qt, ql, hv, qb, qs, qf):
    """A pool block (emptied, unlinked); compacts the overflow first if none is free."""
    if qs[FREE] < 0:
        _rare(np.int64(KEEP), np.int64(-1), np.int64(-1), qt, ql, hv, qb, qs, qf)
    return _pop_free(qb, qs)


@njit(inline="always")
def _slot(qb, home, p):
    """Block and column of position ``p`` of the list with home block ``home``."""
    k = home
    while p >= B_CAP:
        k = qb[k, B_NEXT]
        p -= B_CAP
    return k, B_IDS + p


@njit(inline="always")
def _list_insert(i, home, qt, ql, hv, qb, qs, qf):
    m = qb[home, B_COUNT]
    if m < B_CAP:
        qb[home, B_IDS + m] = i
        qb[home, B_COUNT] = m + 1
    else:
        _rare(np.int64(INSERT), np.int64(i), np.int64(home), qt, ql, hv, qb, qs, qf)


@njit(inline="always")
def _list_remove(i, home, qt, ql, hv, qb, qs, qf):
    """Take disk ``i`` out of the year list with home block ``home``: the list's last
    disk fills the hole."""
    m = qb[home, B_COUNT] - 1
    if m < B_CAP:  # one block: the usual case
        c = B_IDS
        while qb[home, c] != i:
            c += 1
        qb[home, c] = qb[home, B_IDS + m]
        qb[home, B_COUNT] = m
    else:
        _rare(np.int64(REMOVE), np.int64(i), np.int64(home), qt, ql, hv, qb, qs, qf)


@kernel
def _place(i, qt, ql, hv, qb, qs, qf):
    """Queue disk ``i`` (not queued) at its time ``qt[i]``."""
    t = qt[i]
    if t == INF:
        ql[i, LOC] = NOT_QUEUED
        return
    x = (t - qf[ORIGIN]) * qf[INVW]
    cur = qs[CUR]
    nb = qs[MASK] + 1
    if x < cur + 1:
        _heap_push(i, qt, ql, hv, qs)
    elif x < cur + nb:
        _list_insert(i, np.int64(x) & qs[MASK], qt, ql, hv, qb, qs, qf)
        ql[i, LOC] = IN_YEAR
        qs[NLIST] += 1
    else:
        k = qs[OVER]
        if k < 0 or qb[k, B_COUNT] == B_CAP:
            nk = _alloc(qt, ql, hv, qb, qs, qf)
            # (_alloc may have compacted the chain: read its head again)
            qb[nk, B_NEXT] = qs[OVER]
            qs[OVER] = nk
            k = nk
        m = qb[k, B_COUNT]
        qb[k, B_IDS + m] = i
        qb[k, B_COUNT] = m + 1
        ql[i, LOC] = IN_OVERFLOW
        qs[NOVER] += 1


@njit(inline="always")
def _take(i, qt, ql, hv, qb, qs, qf):
    """Take disk ``i`` out of the queue (wherever it is)."""
    loc = np.int64(ql[i, LOC])
    if loc >= 0:
        n = qs[NHEAP] - 1
        qs[NHEAP] = n
        if loc < n:
            last = hv[n]
            hv[loc] = last
            if _sift_up(qt, ql, hv, loc) == loc:
                _sift_down(qt, ql, hv, n, loc)
    elif loc == IN_YEAR:
        x = (qt[i] - qf[ORIGIN]) * qf[INVW]
        _list_remove(i, np.int64(x) & qs[MASK], qt, ql, hv, qb, qs, qf)
        qs[NLIST] -= 1
    elif loc == IN_OVERFLOW:
        qs[NOVER] -= 1  # its entry goes stale; dropped at the next scan
    ql[i, LOC] = NOT_QUEUED


@njit(inline="always")
def set_time(i, t, qt, ql, hv, qb, qs, qf):
    """Give disk ``i`` the event time ``t`` (``inf``: none) and restore the queue."""
    loc = np.int64(ql[i, LOC])
    x = (t - qf[ORIGIN]) * qf[INVW]
    cur = qs[CUR]
    if loc >= 0:
        if x < cur + 1:
            # Stays in the current bucket: reposition inside the heap.  (Counted as a
            # load: with buckets far too wide every event lands here.)
            qt[i] = t
            qs[LOADED] += 1
            if _sift_up(qt, ql, hv, loc) == loc:
                _sift_down(qt, ql, hv, qs[NHEAP], loc)
            return
    elif loc == IN_YEAR:
        if x < cur + qs[MASK] + 1 and np.int64(x) == np.int64(
                (qt[i] - qf[ORIGIN]) * qf[INVW]):
            qt[i] = t  # same bucket: the list stays as it is
            return
    elif loc == IN_OVERFLOW:
        if t < INF and x >= cur + qs[MASK] + 1:
            qt[i] = t  # still beyond the year: its overflow entry stays valid
            return
    _take(i, qt, ql, hv, qb, qs, qf)
    qt[i] = t
    _place(i, qt, ql, hv, qb, qs, qf)


@kernel
def _rare(job, i, home, qt, ql, hv, qb, qs, qf):
    """The rare jobs, in one compiled function (each function costs compile time):

    ``INSERT``/``REMOVE`` disk ``i`` into/from the year list with home block ``home``
    when that takes more than the home block;

    ``KEEP``: drop the stale and repeated entries of the overflow list, packing its
    live disks (each once) into its first blocks and freeing the rest; ``DETACH``: the
    same, then detach the list (for ``_refill`` to re-place its disks, left marked
    ``_CLAIMED``) and return its first block (-1: none).
    """
    if job == INSERT:
        m = qb[home, B_COUNT]
        k = home
        p = m
        while p > B_CAP:
            k = qb[k, B_NEXT]
            p -= B_CAP
        if p == B_CAP:  # the last block is full: chain a new one
            if qs[FREE] < 0:
                _compact(True, ql, qb, qs)
            nk = _pop_free(qb, qs)
            qb[k, B_NEXT] = nk
            k = nk
            p = 0
        qb[k, B_IDS + p] = i
        qb[home, B_COUNT] = m + 1
        return -1
    if job == REMOVE:
        m = qb[home, B_COUNT] - 1
        k = home
        c = B_IDS
        while qb[k, c] != i:
            c += 1
            if c == B_WIDTH:
                k = qb[k, B_NEXT]
                c = B_IDS
        lk, lc = _slot(qb, home, m)
        qb[k, c] = qb[lk, lc]
        if lc == B_IDS:  # the last block is now empty: return it
            pk, _ = _slot(qb, home, m - 1)
            qb[pk, B_NEXT] = -1
            _free(lk, qb, qs)
        qb[home, B_COUNT] = m
        return -1
    return _compact(job == KEEP, ql, qb, qs)


@njit(inline="always")
def _compact(keep, ql, qb, qs):
    """The overflow compaction of ``_rare`` (``KEEP`` if ``keep``, else ``DETACH``)."""
    first = qs[OVER]
    wk = first  # write position: block, count in it
    wm = 0
    k = first
    while k >= 0:
        m = qb[k, B_COUNT]
        for c in range(B_IDS, B_IDS + m):
            d = qb[k, c]
            if ql[d, LOC] == IN_OVERFLOW:
                ql[d, LOC] = _CLAIMED
                if wm == B_CAP:
                    qb[wk, B_COUNT] = wm
                    wk = qb[wk, B_NEXT]
                    wm = 0
                qb[wk, B_IDS + wm] = d
                wm += 1
        k = qb[k, B_NEXT]
    if first >= 0:
        qb[wk, B_COUNT] = wm
        k = qb[wk, B_NEXT]
        qb[wk, B_NEXT] = -1
        while k >= 0:
            nk = qb[k, B_NEXT]
            _free(k, qb, qs)
            k = nk
        if wm == 0:  # nothing live at all
            _free(wk, qb, qs)
            first = -1
    if keep:
        k = first
        while k >= 0:
            for c in range(B_IDS, B_IDS + qb[k, B_COUNT]):
                ql[qb[k, c], LOC] = IN_OVERFLOW
            k = qb[k, B_NEXT]
        qs[OVER] = first
    else:
        qs[OVER] = -1
    return first


@kernel
def _refill(qt, ql, hv, qb, qs, qf):
    """Retune the bucket width if due, then advance the calendar until the heap holds
    the current bucket's events (or nothing is left).  Out of line: once per bucket."""
    nb = qs[MASK] + 1
    if qs[LOADED] + qs[ADVANCED] >= 2 * nb:
        # Retune the bucket width from the events per bucket actually seen.
        per_bucket = qs[LOADED] / max(qs[ADVANCED], 1)
        if (per_bucket > _RETUNE_FACTOR * TARGET_PER_BUCKET
                or per_bucket * _RETUNE_FACTOR < TARGET_PER_BUCKET):
            build(qf[ORIGIN], qt, qt, ql, hv, qb, qs, qf,
                  qf[INVW] * per_bucket / TARGET_PER_BUCKET)
        qs[LOADED] = 0
        qs[ADVANCED] = 0
    while qs[NHEAP] == 0:
        if qs[NLIST] == 0 and qs[NOVER] == 0:
            return
        # With the year empty, jump: restart at the earliest overflow event.
        restart = qs[NLIST] == 0
        cur = qs[CUR]
        if not restart:
            cur += 1
            qs[CUR] = cur
            qs[ADVANCED] += 1
        if restart or cur >= qs[BOUNDARY]:
            # Move the overflow events into the year (the ones still beyond it back
            # into the overflow).
            first = _rare(np.int64(DETACH), np.int64(-1), np.int64(-1), qt, ql, hv, qb, qs, qf)
            qs[NOVER] = 0
            if restart:
                t0 = INF
                k = first
                while k >= 0:
                    for c in range(B_IDS, B_IDS + qb[k, B_COUNT]):
                        t0 = min(t0, qt[qb[k, c]])
                    k = qb[k, B_NEXT]
                # The empty buckets jumped over count as steps for the retuning
                # (capped: the gap may be astronomically many buckets).
                qs[ADVANCED] += np.int64(
                    min((t0 - qf[ORIGIN]) * qf[INVW] - qs[CUR], 2.0 ** 40))
                qf[ORIGIN] = t0
                qs[CUR] = 0
            qs[BOUNDARY] = qs[CUR] + nb
            k = first
            while k >= 0:
                for c in range(B_IDS, B_IDS + qb[k, B_COUNT]):
                    d = qb[k, c]
                    ql[d, LOC] = NOT_QUEUED
                    _place(np.int64(d), qt, ql, hv, qb, qs, qf)
                nk = qb[k, B_NEXT]
                _free(k, qb, qs)
                k = nk
            if restart:
                continue
        home = cur & qs[MASK]
        m = qb[home, B_COUNT]
        if m > 0:
            qs[NLIST] -= m
            k = home
            c = B_IDS
            for _ in range(m):
                _heap_push(qb[k, c], qt, ql, hv, qs)
                c += 1
                if c == B_WIDTH:
                    k = qb[k, B_NEXT]
                    c = B_IDS
            k = qb[home, B_NEXT]
            while k >= 0:
                nk = qb[k, B_NEXT]
                _free(k, qb, qs)
                k = nk
            qb[home, B_NEXT] = -1
            qb[home, B_COUNT] = 0


@njit(inline="always")
def top(qt, ql, hv, qb, qs, qf):
    """The disk with the earliest event, or -1 if nothing is scheduled.

    Advances the calendar to the first non-empty bucket if the current one is done.
    """
    if qs[NHEAP] == 0 or qs[LOADED] + qs[ADVANCED] >= 2 * (qs[MASK] + 1):
        _refill(qt, ql, hv, qb, qs, qf)
        if qs[NHEAP] == 0:
            return np.int64(-1)
    return np.int64(hv[0])


@njit(inline="always")
def prefetch_list(t, qb, qs, qf):
    """Start loading the home block of the year list that time ``t`` belongs to (an
    insertion or removal there is otherwise a cache miss at large N)."""
    x = (t - qf[ORIGIN]) * qf[INVW]
    if x < qs[CUR] + qs[MASK] + 1:  # (also false for inf)
        prefetch(qb, np.int64(x) & qs[MASK])


@njit(inline="always")
def upcoming(ahead, qb, qs):
    """The home block of the bucket ``ahead`` after the current one, and how many of
    its disks it holds (for prefetching their data before they come due)."""
    home = (qs[CUR] + ahead) & qs[MASK]
    return home, min(qb[home, B_COUNT], B_CAP)


@kernel
def build(now, times, qt, ql, hv, qb, qs, qf, invw):
    """Queue every disk at ``times[i]`` (all ``>= now``; ``inf``: none; ``times`` may
    be ``qt`` itself) with buckets ``1 / invw`` wide, bucket 0 starting at the earliest
    event.  ``invw = 0``: choose the width so that the current rate of events fills
    about the target per bucket.  (Also the retuning, which re-places every queued
    disk: one function less to compile.)"""
    n = times.shape[0]
    if invw <= 0.0:
        # The mean wait, recomputed without the waits beyond four times the mean: a
        # few very slow disks must not widen every bucket.  (Only a starting value:
        # the width is retuned from the events actually seen.)
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
    t0 = INF
    for i in range(n):
        qt[i] = times[i]
        t0 = min(t0, qt[i])
    _reset_blocks(qb, qs)
    qs[NHEAP] = 0
    qs[NLIST] = 0
    qs[NOVER] = 0
    qs[CUR] = 0
    qs[BOUNDARY] = qs[MASK] + 1
    qs[LOADED] = 0
    qs[ADVANCED] = 0
    qf[ORIGIN] = t0 if t0 < INF else 0.0
    qf[INVW] = invw
    for i in range(n):
        ql[i, LOC] = NOT_QUEUED
        _place(i, qt, ql, hv, qb, qs, qf)
