"""The calendar queue (``_engine/queue.py``) against a plain sorted reference.

The engine relies on two properties: ``top`` always names the disk with the earliest
``(time, index)`` among everything scheduled, and the structure stays consistent under
any sequence of ``set_time`` calls (ties, ``inf``, times far beyond the calendar's
year, changes of the event rate that retune the bucket width).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import edmd2d as ed
from conftest import seed_of
from edmd2d._engine import queue as q


def check_queue(qt, ql, hv, qhead, qs, qf):
    """Assert every structural invariant of the queue; return the set of queued disks."""
    n = len(qt)
    nb = int(qs[q.MASK]) + 1
    cur = int(qs[q.CUR])
    origin, invw = float(qf[q.ORIGIN]), float(qf[q.INVW])
    seen = {}
    nheap = int(qs[q.NHEAP])
    for k in range(nheap):
        d = int(hv[k])
        assert ql[d, q.LOC] == k
        assert d not in seen
        seen[d] = "heap"
        assert math.floor((float(qt[d]) - origin) * invw) <= cur
        if k:
            p = int(hv[(k - 1) // 2])
            assert (qt[p], p) < (qt[d], d), "heap order"
    counts = [0, 0]
    for lst in range(nb + 1):
        d, prev = int(qhead[lst]), -1
        while d >= 0:
            assert d not in seen
            seen[d] = lst
            assert ql[d, q.LOC] == -2 - lst and ql[d, q.PREV] == prev
            x = (float(qt[d]) - origin) * invw
            if lst < nb:
                b = math.floor(x)
                assert cur < b < cur + nb and b % nb == lst
            else:
                assert x >= qs[q.BOUNDARY]
            counts[lst == nb] += 1
            prev, d = d, int(ql[d, q.NEXT])
    assert counts == [qs[q.NLIST], qs[q.NOVER]]
    for d in range(n):
        assert (d in seen) == (qt[d] < np.inf)
        if d not in seen:
            assert ql[d, q.LOC] == -1
    return set(seen)


def snapshot(qt, ql, hv, qhead, qs, qf):
    """What :func:`check_first` compares with: the queue's state before a ``top``."""
    return (qs.copy(), qf.copy(), qhead.copy(), ql[:, q.NEXT].copy())


def check_first(qt, ql, hv, qhead, qs, qf, before=None):
    """Right after ``top`` moved the calendar on: the links from ``qs[FIRST]`` (the
    lookahead's way into the bucket just reached) run through disks now in the heap,
    each once.  Given the ``snapshot`` from before that ``top``, and if the heap was
    then empty and ``top`` only stepped from bucket to bucket (no retuning, restart or
    overflow scan), they run through exactly the list the new bucket had then."""
    heap = {int(d) for d in hv[:qs[q.NHEAP]]}
    d, walked = int(qs[q.FIRST]), []
    while d >= 0:
        assert d in heap and d not in walked
        walked.append(d)
        d = int(ql[d, q.NEXT])
    if before is not None:
        qs0, qf0, qhead0, next0 = before
        if (qs0[q.NHEAP] == 0 and (qf0 == qf).all() and qs[q.CUR] < qs0[q.BOUNDARY]
                and qs[q.CUR] > qs0[q.CUR]):
            d, listed = int(qhead0[qs[q.CUR] & qs[q.MASK]]), []
            while d >= 0:
                listed.append(d)
                d = int(next0[d])
            assert walked == listed and set(listed) == heap
    return walked


def earliest(qt):
    finite = np.flatnonzero(qt < np.inf)
    if not len(finite):
        return -1
    return int(min(finite, key=lambda d: (qt[d], d)))


def drive(n, now, times, updates):
    """Build a queue of ``n`` disks, then alternately pop the top (giving it a later
    time from ``updates``) and reschedule arbitrary disks, checking against the
    reference after every step."""
    arrays = q.allocate(n)
    qt = arrays[0]
    q.build(now, np.asarray(times, float), *arrays)
    check_queue(*arrays)
    for chosen, dt, pop in updates:
        disk = chosen
        before = snapshot(*arrays)
        top = q.top(*arrays)
        assert top == earliest(qt)
        if arrays[4][q.CUR] != before[0][q.CUR]:
            check_first(*arrays, before)
        if top >= 0:
            now = qt[top]
        if pop and top >= 0:
            disk = top
        elif disk >= n:
            continue
        q.set_time(disk, now + dt, *arrays)
        check_queue(*arrays)
        assert q.top(*arrays) == earliest(qt)
    return arrays


# Waiting times: mostly of order 1, some ties (0), some huge, some never.
waits = st.one_of(
    st.floats(0.0, 3.0),
    st.sampled_from([0.0, 0.5, 1e-12, 1e9, 1e300, math.inf]),
)


@settings(max_examples=150, deadline=None)
@given(
    n=st.integers(1, 40),
    now=st.sampled_from([0.0, 1.0, 1e6]),
    data=st.data(),
)
def test_random_operations_match_sorted_reference(n, now, data):
    times = [now + w for w in data.draw(st.lists(waits, min_size=n, max_size=n))]
    updates = data.draw(st.lists(
        st.tuples(st.integers(0, n + 2), waits, st.booleans()), max_size=120))
    drive(n, now, times, updates)


def test_rate_change_retunes_bucket_width():
    # Start with waiting times of order 1, then (as after a change of temperature)
    # give every disk a wait 10^4 times shorter, run, then 10^4 times longer: each
    # regime must end up with about two events per bucket (within the retuning
    # factor), and the order stays exact throughout.
    rng = np.random.default_rng(seed_of(7))
    n = 300
    arrays = q.allocate(n)
    qt, qs, qf = arrays[0], arrays[4], arrays[5]
    q.build(0.0, rng.exponential(1.0, n), *arrays)
    for scale in (1e-4, 1e4):
        now = qt[q.top(*arrays)]
        for i in range(n):
            q.set_time(i, now + rng.exponential(scale), *arrays)
        for k in range(40 * n):
            cur = qs[q.CUR]
            i = q.top(*arrays)
            if k % 50 == 0:
                assert i == earliest(qt)
            if qs[q.CUR] != cur:  # (through retunes too: no stale qs[FIRST])
                check_first(*arrays)
            q.set_time(i, qt[i] + rng.exponential(scale), *arrays)
        check_queue(*arrays)
        # Events processed per unit time ~ n / scale; one bucket is 1 / invw long.
        per_bucket = (n / scale) / qf[q.INVW]
        assert 1 / q._RETUNE_FACTOR <= per_bucket / q.TARGET_PER_BUCKET <= q._RETUNE_FACTOR


def test_all_events_at_one_instant_and_nothing_scheduled():
    # A perfect lattice moving in step crosses cells all at once: many exact ties.
    arrays = drive(50, 2.0, [2.5] * 50, [(k % 50, 0.5, True) for k in range(200)])
    qt = arrays[0]
    for d in range(50):
        q.set_time(d, math.inf, *arrays)
    check_queue(*arrays)
    assert q.top(*arrays) == -1 and (qt == np.inf).all()


@pytest.mark.parametrize("n", [10, 2000])
def test_engine_queue_consistent_during_runs(n):
    # The queue inside a real simulation (with memory re-sorting for the larger one,
    # done far more often than usual) stays consistent and its top is the earliest.
    sim = ed.make_gas(n, 0.6, seed=seed_of(32))
    if n >= 1024:
        sim._reorder_every = 997
    for step in range(1, 21):
        sim.advance(until=0.05 * step)
        arrays = sim._queue_args()
        check_queue(*arrays)
        assert q.top(*arrays) == earliest(arrays[0])


def test_queue_leaves_the_loops_columns_alone():
    # The queue shares its rows with the event loop: it may write only its own links
    # and times, whatever it does.
    from edmd2d._engine import layout

    n = 64
    arrays = q.allocate(n)
    qt, ql = arrays[0], arrays[1]
    floats = ql.view(np.float64)
    ql[:, :q.NEXT] = 12345
    floats[:, layout.E_TCAND] = 7.5
    floats[:, layout.E_INVM] = 0.25
    rng = np.random.default_rng(seed_of(1))
    q.build(0.0, rng.exponential(1.0, n), *arrays)
    for _ in range(2000):
        i = q.top(*arrays)
        q.set_time(i, qt[i] + rng.exponential(1.0), *arrays)
    assert (ql[:, :q.NEXT] == 12345).all()
    assert (floats[:, layout.E_TCAND] == 7.5).all() and (floats[:, layout.E_INVM] == 0.25).all()


def test_first_names_the_list_just_moved_into_the_heap():
    # Three disks share a later bucket's list: once the calendar reaches that bucket,
    # qs[FIRST] leads through exactly those three.
    arrays = q.allocate(16)
    ql = arrays[1]
    times = np.arange(16.0)
    times[[2, 4, 5]] = [10.1, 10.2, 10.3]
    times[10] = 20.0
    q.build(0.0, times, *arrays)
    loc = ql[:, q.LOC]
    assert loc[2] <= -2 and (np.flatnonzero(loc == loc[2]) == [2, 4, 5]).all()
    while (i := q.top(*arrays)) not in (2, 4, 5):
        q.set_time(i, math.inf, *arrays)
    assert sorted(check_first(*arrays)) == [2, 4, 5]
    check_queue(*arrays)
