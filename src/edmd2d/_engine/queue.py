"""Indexed binary min-heap holding exactly one scheduled event per disk.

``heap[k]`` is a disk, ``where[i]`` its slot, ``ev_t[i]`` its key.  Memory is ``2N``
integers whatever the run length.  Ties in time are broken by the disk index, so the
order of simultaneous events is deterministic.
"""

from __future__ import annotations

from .._jit import njit


@njit(inline="always")
def _less(ev_t, i, j):
    ti = ev_t[i]
    tj = ev_t[j]
    return ti < tj or (ti == tj and i < j)


@njit
def sift_up(heap, where, ev_t, k):
    i = heap[k]
    while k > 0:
        parent = (k - 1) >> 1
        p = heap[parent]
        if _less(ev_t, i, p):
            heap[k] = p
            where[p] = k
            k = parent
        else:
            break
    heap[k] = i
    where[i] = k


@njit
def sift_down(heap, where, ev_t, k):
    n = heap.shape[0]
    i = heap[k]
    while True:
        child = 2 * k + 1
        if child >= n:
            break
        c = heap[child]
        if child + 1 < n:
            c2 = heap[child + 1]
            if _less(ev_t, c2, c):
                child += 1
                c = c2
        if _less(ev_t, c, i):
            heap[k] = c
            where[c] = k
            k = child
        else:
            break
    heap[k] = i
    where[i] = k


@njit
def update(heap, where, ev_t, i):
    """Restore the heap after the key of disk ``i`` changed (either direction)."""
    k = where[i]
    sift_up(heap, where, ev_t, k)
    sift_down(heap, where, ev_t, where[i])


@njit
def build(heap, where, ev_t):
    """Heapify all disks from scratch (O(N))."""
    n = heap.shape[0]
    for i in range(n):
        heap[i] = i
        where[i] = i
    for k in range(n // 2 - 1, -1, -1):
        sift_down(heap, where, ev_t, k)
