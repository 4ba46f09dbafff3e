"""Memory layout promises of the engine: aligned per-disk rows, and the prefetch hint."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest
from numba import njit

import edmd2d as ed
from conftest import seed_of
from edmd2d._engine import aligned_rows, prefetch


@pytest.mark.parametrize("n", [7, 1500])
def test_state_and_bookkeeping_rows_stay_aligned(n):
    # One disk's state is one 64-byte cache line and its bookkeeping another: true
    # only if the tables start on those boundaries, also after the memory re-sorting of
    # large systems (forced often here) has replaced them.  The per-disk columns that
    # live in those rows must be views into the tables in use, not into old ones.
    sim = ed.make_gas(n, 0.5, seed=seed_of(3))
    sim._reorder_every = 499
    for _ in range(3):
        assert sim._S.ctypes.data % 64 == 0 and sim._S.strides == (64, 8)
        assert sim._E.ctypes.data % 64 == 0 and sim._E.strides == (64, 4)
        assert _view_offsets(sim) == _VIEW_OFFSETS
        sim.advance(collisions=2 * n)


# Where each per-disk column sits inside its table's row: (table, byte offset, dtype)
_VIEW_OFFSETS = {"_stamp": ("_S", 48, "<i4"), "_nxt": ("_S", 52, "<i4"),
                 "_prv": ("_S", 56, "<i4"), "_qt": ("_E", 32, "<f8"),
                 "_tcand": ("_E", 40, "<f8"), "_invm": ("_E", 48, "<f8")}


def _view_offsets(sim):
    """For each per-disk column: the table it is a view into (one whose memory it
    shares, row by row), its byte offset in the row and its dtype."""
    out = {}
    for name, (table_name, _, _) in _VIEW_OFFSETS.items():
        column, table = getattr(sim, name), getattr(sim, table_name)
        assert column.shape == (len(table),) and column.strides == (64,), name
        assert np.shares_memory(column, table), name
        out[name] = (table_name, column.ctypes.data - table.ctypes.data, column.dtype.str)
    return out


def _pinned_mixture(n, seed):
    """Positions, velocities, radii, masses (two values, every 37th disk immovable and
    at rest) and box of a gas with one pair of walls."""
    base = ed.make_gas(n, 0.4, radii=np.where(np.arange(n) % 3, 0.5, 0.6),
                       periodic=(True, False), seed=seed)
    vel = base.velocities.copy()
    mass = np.where(np.arange(n) % 2, 1.0, 3.0)
    mass[::37] = np.inf
    vel[::37] = 0.0
    return base.positions, vel, base.radii, mass, base.box


def test_masses_and_pinned_disks_survive_reordering():
    # The inverse masses move with the bookkeeping rows when the rows are re-sorted.
    pos, vel, rad, mass, box = _pinned_mixture(1500, 8)
    sim = ed.Simulation(pos, vel, rad, mass, box=box)
    sim._reorder_every = 701
    energy = sim.kinetic_energy()
    for _ in range(4):
        sim.advance(collisions=5000)
        assert np.array_equal(sim._invm, np.where(np.isinf(sim._mass), 0.0, 1.0 / sim._mass))
        assert sim.kinetic_energy() == pytest.approx(energy, rel=1e-12)
    assert not np.array_equal(sim._order, np.arange(1500))  # it did re-sort
    assert np.array_equal(sim.positions[::37], pos[::37])
    assert np.array_equal(sim.masses, mass)


def test_reordering_changes_no_event():
    # Re-sorted in memory every 213 events or (after the constructor's) never: the same
    # events in the user's numbering and the same final state.  (Only to rounding: the
    # internal order decides which of two disks a pair's event is computed from, and
    # simultaneous events tie-break on the internal index.)
    pos, vel, rad, mass, box = _pinned_mixture(1500, 9)
    runs = []
    for every in (213, np.iinfo(np.int64).max):
        sim = ed.Simulation(pos, vel, rad, mass, box=box)
        sim._reorder_every = every
        sim._record_events(40_000)
        sim.advance(until=0.6)
        events = sorted((t, kind, *sorted((a, b))) if kind == "disk" else (t, kind, a, b)
                        for t, kind, a, b in sim._recorded_events())
        runs.append((events, sim.positions, sim.velocities, sim.counts))
    (ev1, p1, v1, c1), (ev2, p2, v2, c2) = runs
    assert len(ev1) > 1000 and c1 == c2
    assert [e[1:] for e in ev1] == [e[1:] for e in ev2]
    assert np.allclose([e[0] for e in ev1], [e[0] for e in ev2], rtol=0, atol=1e-9)
    assert np.allclose(p1, p2, rtol=0, atol=1e-9) and np.allclose(v1, v2, rtol=0, atol=1e-9)


@pytest.mark.parametrize("how", ["deepcopy", "pickle", "copy"])
def test_a_copy_runs_like_the_original(how):
    # The per-disk columns of a copy must be views into the copy's own tables (not
    # arrays of their own), and the tables 64-byte aligned again.  (A shallow copy
    # would share the queue and grid with the original but not the tables: copy.copy
    # copies everything.)
    sim = ed.make_gas(1500, 0.5, seed=seed_of(4))
    sim._reorder_every = 997
    sim.advance(collisions=1000)
    twin = {"deepcopy": copy.deepcopy, "copy": copy.copy,
            "pickle": lambda s: pickle.loads(pickle.dumps(s))}[how](sim)
    assert not any(np.shares_memory(a, b) for a in vars(sim._state).values()
                   for b in vars(twin._state).values()
                   if isinstance(a, np.ndarray) and isinstance(b, np.ndarray))
    assert _view_offsets(twin) == _VIEW_OFFSETS
    assert twin._S.ctypes.data % 64 == 0 and twin._E.ctypes.data % 64 == 0
    sim.advance(collisions=5000)  # (with re-sorts on the way)
    twin.advance(collisions=5000)
    assert np.array_equal(sim.positions, twin.positions)
    assert sim.counts == twin.counts


def test_a_pickle_keeps_the_lookahead_notes_and_refuses_what_it_cannot_read():
    # A pickle keeps the lookahead stage notes (column STAGED) and runs like the
    # original; a queue state of another length is refused instead of read past its
    # end, and so is a pickle of the format that held the Simulation's attributes
    # (version 1) rather than the engine's state.
    from edmd2d._engine import layout, queue
    from edmd2d._state import EngineState

    sim = ed.make_gas(600, 0.5, seed=seed_of(4))
    sim._qs[queue.LOOKAHEAD] = 1
    sim.advance(collisions=500)
    state = pickle.loads(pickle.dumps(sim))._state.__getstate__()  # (arrays of its own)
    staged = state["E"][:, layout.STAGED].copy()
    assert (staged != 0).any() and (staged & ~layout.STAGE_BITS == 0).all()
    twin = pickle.loads(pickle.dumps(sim))
    assert np.array_equal(twin._E[:, layout.STAGED], staged)
    assert len(twin._qs) == queue.N_QS
    sim.advance(collisions=2000)
    twin.advance(collisions=2000)
    assert np.array_equal(sim.positions, twin.positions) and sim.counts == twin.counts
    with pytest.raises(ValueError, match="incompatible version"):
        EngineState.__new__(EngineState).__setstate__(
            dict(state, qs=state["qs"][:queue.FIRST - 1]))
    with pytest.raises(ValueError, match="format version 1"):
        ed.Simulation.__new__(ed.Simulation).__setstate__(
            {"_" + key: value for key, value in state.items()})


@pytest.mark.parametrize("dtype, width, align", [(np.float64, 8, 64), (np.int32, 8, 32),
                                                 (np.int32, 3, 64)])
def test_aligned_rows(dtype, width, align):
    for n in (0, 1, 5, 1000):
        a = aligned_rows(n, width, dtype, align)
        assert a.shape == (n, width) and a.dtype == dtype and a.flags.c_contiguous
        if n:  # (an empty array has no row to align)
            assert a.ctypes.data % align == 0


@njit
def _sum_with_prefetch(a, b):
    total = 0.0
    for i in range(a.shape[0]):
        prefetch(a, a.shape[0] - 1 - i)  # a 2D row
        prefetch(b, i)  # a 1D element
        total += a[i, 0] + b[i]
    return total


def test_prefetch_is_only_a_hint():
    # Prefetching any valid row, including the last, changes no value and no array.
    rng = np.random.default_rng(seed_of(0))
    a, b = rng.random((300, 8)), rng.random(300)
    a0, b0 = a.copy(), b.copy()
    assert _sum_with_prefetch(a, b) == pytest.approx(a[:, 0].sum() + b.sum(), rel=1e-15)
    assert (a == a0).all() and (b == b0).all()


def test_wall_free_gas_holds_no_per_cell_wall_index():
    # Part of the memory budget: without wall segments there is nothing to look up per
    # cell, and a large system re-sorts without holding the cells' Morton ranks.
    sim = ed.make_gas(1500, 0.5, seed=seed_of(4))
    assert sim._wstart.shape == (1,) and not hasattr(sim, "_cell_rank")
    sim._reorder_every = 999
    sim.advance(collisions=3000)
    assert not np.array_equal(sim._order, np.arange(1500))  # it did re-sort
    listed = []
    for c, first in enumerate(sim._head):  # every disk in exactly its own cell's list
        j = first
        while j >= 0:
            assert sim._E[j, 0] == c
            listed.append(j)
            j = sim._nxt[j]
    assert sorted(listed) == list(range(1500))


def _runs_with_and_without_lookahead(build, collisions, reorder_every=None):
    """The recorded events, state rows, bookkeeping rows and counts of two runs of the
    same system, with the lookahead switched on and off (whatever its size)."""
    from edmd2d._engine import queue

    runs = []
    for lookahead in (1, 0):
        sim = build()
        sim._qs[queue.LOOKAHEAD] = lookahead
        if reorder_every is not None:
            sim._reorder_every = reorder_every
        sim._record_events(collisions + 10_000)
        sim.advance(collisions=collisions)
        assert sim._qs[queue.LOOKAHEAD] == lookahead  # kept through any re-sort
        runs.append((sim._recorded_events(), sim._S.copy(), sim._E.copy(), sim.counts))
    assert len(runs[0][0]) >= collisions
    return runs


def _same_bits(a, b):
    """Equal bit for bit (the row tables hold integer columns too, whose bit patterns
    may read as NaN in a float view)."""
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def _assert_identical(runs):
    """The same events, counts and rows, but for the lookahead's notes of the stages
    given (E[:, STAGED]), which it must have written only when on."""
    from edmd2d._engine import layout

    (ev_on, s_on, e_on, c_on), (ev_off, s_off, e_off, c_off) = runs
    assert ev_on == ev_off
    assert (e_off[:, layout.STAGED] == 0).all() and (e_on[:, layout.STAGED] != 0).any()
    e_on, e_off = e_on.copy(), e_off.copy()
    e_on[:, layout.STAGED] = e_off[:, layout.STAGED] = 0
    assert _same_bits(s_on, s_off) and _same_bits(e_on, e_off)
    assert c_on == c_off


@pytest.mark.parametrize("periodic", [True, (True, False), False])
def test_lookahead_changes_no_event_and_no_state(periodic):
    # The lookahead of large systems only prefetches: forced on for a small one (a
    # mixture, with box walls on the walled axes and frequent re-sorting in memory) it
    # must leave every event, count and the final state bit-identical.
    from edmd2d._engine import queue

    def build():
        sim = ed.make_gas(1500, 0.55, radii=np.where(np.arange(1500) % 3, 0.5, 0.65),
                          periodic=periodic, seed=seed_of(5))
        assert sim._qs[queue.LOOKAHEAD] == 0  # off below LOOKAHEAD_MIN_DISKS
        return sim

    _assert_identical(_runs_with_and_without_lookahead(build, 30_000, reorder_every=2999))


def _assert_only_stages_noted(arrays, before):
    """Every array as it was, but for stage bits (1-3) added to E[:, STAGED]."""
    from edmd2d._engine import layout

    e_now, e_then = arrays[1], before[1]
    now, then = e_now[:, layout.STAGED], e_then[:, layout.STAGED]
    assert (now & then == then).all()  # (bits are only added,)
    assert (now & ~0b1110 == then & ~0b1110).all()  # (and only those of stages 1-3)
    e_now, e_then = e_now.copy(), e_then.copy()
    e_now[:, layout.STAGED] = e_then[:, layout.STAGED] = 0
    assert _same_bits(e_now, e_then)
    assert all(_same_bits(a, b) for i, (a, b) in enumerate(zip(arrays, before)) if i != 1)
    return int((now != then).sum())


@pytest.mark.parametrize("periodic", [True, False])
def test_lookahead_kernel_writes_nothing_but_its_notes(periodic):
    # Run directly for every bucket of the calendar (so also for lists whose disks sit
    # at the edges of a walled box), the lookahead leaves every array as it was, but
    # for the stages it notes as given.
    from edmd2d._engine import lookahead, queue

    sim = ed.make_gas(800, 0.5, periodic=periodic, seed=seed_of(6))
    sim.advance(collisions=2000)
    arrays = (sim._S, sim._E, sim._qt, sim._tcand, sim._gi, sim._head, sim._qhead)
    before = [a.copy() for a in arrays]
    mask = int(sim._qs[queue.MASK])
    for cur in range(int(sim._qs[queue.CUR]), int(sim._qs[queue.CUR]) + mask + 2):
        # (As the list just moved into the heap, none, or any list: hints all.)
        for first in (-1, int(sim._qhead[(cur + 7) & mask])):
            lookahead.lookahead(cur - 1, cur, first, *arrays, mask)
    assert _assert_only_stages_noted(arrays, before) > 100
    assert (sim._qhead >= 0).sum() > 100  # the lists it walked were not empty


def test_a_new_event_starts_with_no_stage_noted():
    # Stages are given only to events at most lookahead._AHEAD buckets ahead; an event
    # predicted afresh starts with none, so every event queued further ahead has none,
    # whatever stages the disk's earlier events had.
    from edmd2d._engine import layout, lookahead, queue

    sim = ed.make_gas(3000, 0.5, seed=seed_of(9))
    sim._qs[queue.LOOKAHEAD] = 1
    far = near = 0
    for _ in range(5):
        sim.advance(collisions=4000)
        cur, mask = int(sim._qs[queue.CUR]), int(sim._qs[queue.MASK])
        for d in range(1, mask + 2):
            h = sim._qhead[(cur + d) & mask] if d <= mask else sim._qhead[mask + 1]
            while h >= 0:
                staged = sim._E[h, layout.STAGED]
                if d > lookahead._AHEAD:
                    assert staged == 0, (d, staged)
                    far += 1
                elif d <= 2:
                    near += staged != 0
                h = sim._E[h, queue.NEXT]
    assert far > 5 * 2000 and near > 5 * 3
    # A re-sort moves the rows, and with them whatever the lookahead had fetched.
    sim._reorder()
    assert (sim._E[:, layout.STAGED] == 0).all()


def test_heap_staging_gives_each_waiting_event_its_next_stage():
    # Between the events of a bucket, every event in its heap but the root gets the
    # first stage it lacks, one per call, and nothing else changes.
    from edmd2d._engine import layout, lookahead

    sim = ed.make_gas(800, 0.5, seed=seed_of(6))
    sim.advance(collisions=2000)
    arrays = (sim._S, sim._E, sim._qt, sim._tcand, sim._gi, sim._head)
    disks = np.arange(0, 800, 80)  # ten disks (stand-ins for a heap)
    hv = disks.astype(np.int32)
    given = [0, 0, 0b0010, 0b0110, 0b1110, 0b1010, 0, 0, 0, 0]
    # slot 0: the root, left alone; slot 5 lacks stage 2 only; slots 8, 9 are past
    # the slots looked at (lookahead._HEAP_STAGED).
    assert lookahead._HEAP_STAGED == 8
    sim._E[disks, layout.STAGED] = given
    before = [a.copy() for a in arrays]
    lookahead.stage_heap(*arrays, hv, 10)
    after = sim._E[disks, layout.STAGED].tolist()
    assert after == [0, 0b0010, 0b0110, 0b1110, 0b1110, 0b1110, 0b0010, 0b0010, 0, 0]
    _assert_only_stages_noted(arrays, before)
    lookahead.stage_heap(*arrays, hv, 3)  # (a heap of three: slots 1 and 2 only)
    assert sim._E[disks, layout.STAGED].tolist()[:4] == [0, 0b0110, 0b1110, 0b1110]


def test_lookahead_is_on_for_large_systems_only():
    from edmd2d._engine import queue

    assert queue.allocate(queue.LOOKAHEAD_MIN_DISKS - 1)[4][queue.LOOKAHEAD] == 0
    assert queue.allocate(queue.LOOKAHEAD_MIN_DISKS)[4][queue.LOOKAHEAD] == 1


def test_lookahead_on_by_default_at_its_size_changes_nothing():
    # At the size where it switches on by itself: the same events and state as with it
    # switched off.
    from edmd2d._engine import queue

    def build():
        sim = ed.make_gas(queue.LOOKAHEAD_MIN_DISKS, 0.5, seed=seed_of(7))
        assert sim._qs[queue.LOOKAHEAD] == 1
        return sim

    runs = _runs_with_and_without_lookahead(build, 50_000)
    assert len(runs[0][0]) == 50_000
    _assert_identical(runs)


_COUNT_LOOKAHEAD_CALLS = r"""
import edmd2d as ed
from edmd2d._engine import lookahead, queue

calls = []
inner = lookahead._lookahead_bucket
def counting(cur, *args):
    calls.append(int(cur))
    return inner(cur, *args)
lookahead._lookahead_bucket = counting  # (as plain Python, looked up at each call)
inner_heap = lookahead.stage_heap
def counting_heap(*args):
    heap_calls[0] += 1
    return inner_heap(*args)
lookahead.stage_heap = counting_heap
inner_top = queue.top
def top(qt, ql, hv, qhead, qs, qf):
    before = int(qs[queue.CUR])
    i = inner_top(qt, ql, hv, qhead, qs, qf)
    after = int(qs[queue.CUR])
    # The buckets the lookahead should run for: each one reached or stepped over
    # (when the calendar moved on by up to lookahead._AHEAD buckets), else the new one.
    if not expected:
        expected.append(after)
    elif after == before:
        stays[0] += 1  # (the heap staging's turn)
    else:
        gap = after - before
        expected.extend(range(before + 1, after + 1) if 0 < gap <= lookahead._AHEAD else [after])
        skips[0] += 1 < gap <= lookahead._AHEAD
    return i
queue.top = top

out = []
for flag in (1, 0):
    sim = ed.make_gas(150, 0.5, seed=8)
    sim._qs[queue.LOOKAHEAD] = flag
    calls.clear()
    expected = []
    skips = [0]
    stays = [0]
    heap_calls = [0]
    sim.advance(collisions=300)
    out.append((len(calls), calls == expected, skips[0], heap_calls[0], stays[0]))
print(out)
"""


def test_event_loop_runs_the_lookahead_for_each_bucket_reached_or_stepped_over():
    # Prefetching has no observable effect, so the bit-identity tests above would also
    # pass if the loop never called the lookahead.  As plain Python (numba's JIT off,
    # in a child process) the call can be counted: on, once per bucket the calendar
    # reaches or steps over (consecutive calls run for consecutive buckets, but where
    # the calendar restarts), and the heap staging once per event that finds the
    # calendar on the same bucket; off, never.
    import ast
    import os
    import subprocess
    import sys

    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    res = subprocess.run([sys.executable, "-c", _COUNT_LOOKAHEAD_CALLS], env=env,
                         capture_output=True, text=True, timeout=600, check=True)
    (n_on, as_expected, skips, heap_on, stays), (n_off, _, _, heap_off, _) = (
        ast.literal_eval(res.stdout.strip().splitlines()[-1]))
    assert n_on > 50 and as_expected
    assert skips > 10  # (the calendar did step over empty buckets)
    assert heap_on == stays > 50
    assert n_off == 0 and heap_off == 0
