"""Indexed 4-ary min-heap holding exactly one scheduled event time per disk.

``hkey[k]`` is the time at heap slot ``k`` and ``hval[k]`` the disk there; ``where[i]``
is the slot of disk ``i``.  Keys live in heap order, so the four children of a slot,
which are compared together, sit next to each other in memory (32 bytes, one or two
cache lines) instead of being looked up disk by disk; a 4-ary tree is also half as deep
as a binary one.  At N = 10^6 an update went from 516 to 286 ns in isolation.

Memory is ``N`` keys and ``2N`` indices whatever the run length.  Ties in time are
broken by the engine's internal disk index (the row order, which the Z-order sorting of
large systems changes), so the order of simultaneous events is deterministic for a
given run, though not by the user's disk numbering.
"""

from __future__ import annotations

from .._jit import kernel, njit


@njit(inline="always")
def _before(ka, ia, kb, ib):
    return ka < kb or (ka == kb and ia < ib)


@kernel
def sift_up(hkey, hval, where, k):
    """Move the entry at slot ``k`` towards the root while it is earlier than its parent."""
    key = hkey[k]
    i = hval[k]
    while k > 0:
        p = (k - 1) >> 2
        if _before(key, i, hkey[p], hval[p]):
            hkey[k] = hkey[p]
            hval[k] = hval[p]
            where[hval[k]] = k
            k = p
        else:
            break
    hkey[k] = key
    hval[k] = i
    where[i] = k
    return k


@kernel
def sift_down(hkey, hval, where, k):
    """Move the entry at slot ``k`` away from the root while a child is earlier."""
    n = hkey.shape[0]
    key = hkey[k]
    i = hval[k]
    while True:
        c = 4 * k + 1
        if c >= n:
            break
        best = c
        bk = hkey[c]
        bi = hval[c]
        end = min(c + 4, n)
        for cc in range(c + 1, end):
            kk = hkey[cc]
            if kk < bk or (kk == bk and hval[cc] < bi):
                best = cc
                bk = kk
                bi = hval[cc]
        if _before(bk, bi, key, i):
            hkey[k] = bk
            hval[k] = bi
            where[bi] = k
            k = best
        else:
            break
    hkey[k] = key
    hval[k] = i
    where[i] = k


@kernel
def set_time(hkey, hval, where, i, t):
    """Give disk ``i`` the event time ``t`` and restore the heap."""
    k = where[i]
    hkey[k] = t
    if sift_up(hkey, hval, where, k) == k:
        sift_down(hkey, hval, where, k)


@njit
def build(hkey, hval, where, times):
    """Heapify all disks from scratch (O(N)) with ``times[i]`` the time of disk ``i``."""
    n = hkey.shape[0]
    for i in range(n):
        hkey[i] = times[i]
        hval[i] = i
        where[i] = i
    if n > 1:
        for k in range((n - 2) // 4, -1, -1):
            sift_down(hkey, hval, where, k)
