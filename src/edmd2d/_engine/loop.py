"""The event loop: the algorithm, one scheduled event per disk.

Pop the earliest event; if it was predicted against a partner that has changed course
since, predict its disk afresh; otherwise bring the disks involved to its time, let the
physics respond (:mod:`.response`) or move the disk into its new grid cell, predict
afresh the disks whose course changed (:mod:`.scan`), re-queue them (:mod:`.queue`),
log the event, and stop at the requested time, collision count or event budget.
The state layout is declared in :mod:`.layout`.

Why one event per disk is enough: a disk's event is the minimum over its candidates.
When a partner ``j`` changes course it is re-predicted against all its neighbours, so
any new contact with ``j`` is held by ``j``; the other candidates of ``i`` are all later
than ``i``'s stale event, so re-predicting ``i`` when that stale event comes due is
enough.  ``stamp[i]`` grows whenever ``i``'s trajectory changes (a collision) or its
stored coordinates jump by a box length (a periodic wrap).

Positions are "delayed states": ``S[i, 0:2]`` is valid at ``S[i, T]``; only the disks of
an event are moved to its time (:mod:`.flight`).

From ``queue.LOOKAHEAD_MIN_DISKS`` disks on, the loop also runs the lookahead
(:mod:`.lookahead`), which prefetches what the coming events will read: a hint only,
every event and all state are bit-identical with it on or off.

The loop receives its state and its physics in named bundles, declared once in
:mod:`.layout` and read by field name: ``control`` (what to do and where to report),
``particles``, ``grid``, ``walls``, ``calendar``, ``tallies`` and ``log``; then one
argument per physics family, each ``None`` when unused:

``contact``
    restitution and the TC model (``layout.Contact``; ``None``: elastic contacts);
``heated``
    walls that send disks back at their temperature (``layout.HeatedWalls``);
``thermostat``
    the Andersen thermostat's redraws (``layout.Thermostat``);
``uniforms``
    the random numbers that heated walls and the thermostat draw
    (``layout.Uniforms``; present whenever either of them is);
``gravity``
    a uniform acceleration (``layout.Gravity``; ``None``: straight-line flight, see
    :mod:`.flight`);
``growth``
    radii that grow linearly in time (``layout.Growth``), ``S[i, R] (1 + rate (t -
    t0))`` (:func:`.predict.growth_factor`), in straight-line flight with elastic
    contacts.  The grid's cells must stay wider than the largest diameter: the caller
    stops the run before they no longer are and rebuilds it;
``rest``
    disks that come to rest under gravity (``layout.Rest``, :mod:`.resting`; with
    ``gravity`` only): after each collision a slow, held disk is put to rest, and a
    flying disk meets a resting one as a fixed circle unless the impact wakes it;
``shear``
    Lees-Edwards boundaries (``layout.Shear``, :mod:`.sheared`): the images above and
    below the box slide along x; when they have slid by a cell width (a ``SLIDE``, due
    at ``shear.clock[T_NEXT]``, processed before any later event and never logged),
    the disks of the top and bottom rows of cells are predicted afresh;
``helfand``
    the sums of the Einstein-Helfand moments (``layout.Helfand``, :mod:`.helfand`):
    each disk's free flights as the loop moves it, and each collision's transfer of
    energy across the pair (elastic disks in a periodic box only);
``rough``
    disks that spin (``layout.Rough``, :mod:`.rough`): after each collision with a disk
    or a wall, the tangential impulse of the contact points.
``wide``
    disks wider than the grid's cells (``layout.Wide``, :mod:`.wide`), listed in
    every cell of their footprint: a wide disk's crossing changes its footprint by a
    column or a row (or wraps its centre), and a narrow disk also meets the wide disks
    listed in its own cell.
``motion``
    wall segments that move (``layout.Motion``, :mod:`.moving`): a disk's contact with
    one is searched along the segment's path, and the collision reflects the velocity
    relative to the segment's and tallies the work it does.

numba prunes the branches of an argument that is ``None``, so each combination of
families compiles its own ``run``, only when used, and the elastic default compiles to
the plain algorithm.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import kernel, njit
from . import helfand as _helfand
from . import lookahead, prefetch, queue, response, resting, sheared
from . import rough as _rough
from . import wide as _wide
from .flight import drift, velocity_at
from .grid import insert, remove
from .layout import (
    AUX,
    BOX,
    C_COLLISIONS,
    C_CROSSINGS,
    C_KICKS,
    C_STALE,
    C_WALL,
    CELL,
    CROSS,
    DISK,
    ERR_IMMOVABLE_PAIR,
    ERR_IMMOVABLE_WALL,
    ERR_STALLED,
    KICK,
    KIND,
    LOG_FULL,
    NEED_RANDOM,
    NO_EVENTS,
    NONE,
    PARTNER,
    PREDICT_ALL,
    PSTAMP,
    REACHED_COLLISIONS,
    REACHED_EVENT_LIMIT,
    REACHED_TIME,
    SEGMENT,
    SLIDE,
    STAGED,
    VX,
    VY,
    X,
    direction_of,
    kind_of,
)
from .predict import INF
from .scan import predict


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
def _velocity_after(d, S, gravity, rest):
    """Disk ``d``'s velocity right after the event: the one it came to rest with, if
    the event ended with it at rest (its velocity is then 0)."""
    if rest is not None and resting.is_resting(d, gravity):
        return rest.frozen[d, 0], rest.frozen[d, 1]
    return S[d, VX], S[d, VY]


@njit
def _log_event(k, t, kind, i, partner, aux, pvx, pvy, qvx, qvy, S, invm, order,
               log_t, log_e, log_j, gravity, rest):
    """Write event ``k`` of the log: its time, kind, disks (by user index) or wall, and
    its impulse, the momentum change of a movable disk of the event (velocities
    ``pv`` of ``i`` and ``qv`` of a partner disk before it; after it, as the event
    left them, before a rest that followed).  (A function of its own: compiled once,
    not into the loop.)"""
    log_t[k] = t
    log_e[k, 0] = kind
    log_e[k, 1] = order[i]
    if kind == DISK:
        log_e[k, 2] = order[partner]
    else:
        log_e[k, 2] = partner if kind == SEGMENT else aux
    if invm[i] > 0.0:
        vx, vy = _velocity_after(i, S, gravity, rest)
        log_j[k] = math.hypot(vx - pvx, vy - pvy) / invm[i]
    elif kind == DISK:
        vx, vy = _velocity_after(partner, S, gravity, rest)
        log_j[k] = math.hypot(vx - qvx, vy - qvy) / invm[partner]
    else:
        log_j[k] = 0.0


@njit
def _make_room(m, k, log_t, log_e, log_j):
    """Move the log's entries ``m .. k-1`` one place on, to free entry ``m``."""
    for r in range(k - 1, m - 1, -1):
        log_t[r + 1] = log_t[r]
        log_e[r + 1, 0] = log_e[r, 0]
        log_e[r + 1, 1] = log_e[r, 1]
        log_e[r + 1, 2] = log_e[r, 2]
        log_j[r + 1] = log_j[r]


@kernel
def run(control, particles, grid, walls, calendar, tallies, log,
        contact, heated, thermostat, uniforms, gravity, growth, rest, shear, helfand,
        rough, wide, motion):
    """Process events in time order (``control.mode`` RUN_EVENTS), or (``mode``
    PREDICT_ALL) predict every disk's next event from the time ``out[0]`` and rebuild
    the queue.  (``t_end``, ``max_collisions``, ``max_events``, ``mode``, ``out`` and
    ``info`` are the fields of ``control``; ``log_t``, ``log_e``, ``log_n`` and
    ``log_j`` those of ``log``: ``times``, ``events``, ``count``, ``impulses``.)

    (Both share the one place where the full prediction is compiled into this
    function; see the module notes for the bundles.)

    Stops before the first event later than ``t_end``, right after the
    ``max_collisions``-th disk-disk collision of this call, or after ``max_events``
    processed events.  ``out[0]`` receives the time of the last processed event (or is
    left unchanged if none was processed).  Returns a status code; on an error the
    offending disks (or disk and wall: ``-1 - side`` for a box wall) are written to
    ``info`` and the state is left as it was just before that event.

    The thermostat's redraws (``KICK``) are events of their own, at their times: one
    due before the next scheduled event is processed first.  With ``uniforms`` (heated
    walls or a thermostat) the loop returns ``NEED_RANDOM`` before an event when its
    buffer runs low (nothing of that event done yet): refill it and call again.

    With a log (``log.capacity > 0``), every disk-disk, segment, box-wall and
    thermostat event is recorded as ``log_t[k]``, ``log_e[k] = (kind, i, partner)``
    (partner -1 for a redraw), with its impulse ``log_j[k]`` (the momentum change of a
    movable disk of the event: ``J`` for a contact), and ``log_n[0]`` counts them; disks
    are recorded by their user index ``order[i]``.  Where disks come to rest, their
    rests and wakes are recorded too (by ``resting``, partner -1): at one instant the
    wakes an event causes come before it, the rests after it.  Once ``log.capacity``
    entries are logged the loop returns ``LOG_FULL`` after the event (the caller
    empties the log and calls again; the arrays have room for what one event logs
    beyond that, so no event is lost); with no log none of this runs.
    """
    t_end = control.t_end
    max_collisions = control.max_collisions
    max_events = control.max_events
    mode = control.mode
    out = control.out
    info = control.info
    S = particles.S
    E = particles.E
    stamp = particles.stamp
    nxt = particles.nxt
    prv = particles.prv
    qt = particles.qt
    tcand = particles.tcand
    invm = particles.invm
    image = particles.image
    order = particles.order
    gi = grid.gi
    gf = grid.gf
    head = grid.head
    wa = walls.wa
    wb = walls.wb
    wstart = walls.wstart
    wwall = walls.wwall
    wsx = walls.wsx
    wsy = walls.wsy
    hv = calendar.hv
    qhead = calendar.qhead
    qs = calendar.qs
    qf = calendar.qf
    counts = tallies.counts
    acc = tallies.acc
    wacc = tallies.wacc
    log_t = log.times
    log_e = log.events
    log_n = log.count
    log_j = log.impulses
    ncx = gi[0]
    ncy = gi[1]
    log_cap = log.capacity
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
    sliding = False
    mark = -1
    t_redo0 = INF
    t_redo1 = INF
    opened = np.int64(-1)  # the calendar bucket the lookahead last ran for (int64: one
    # compiled lookahead, not a second for the literal)
    qs[queue.FIRST] = -1  # (left by an earlier call: its list may have changed since)
    pvx = pvy = qvx = qvy = 0.0  # (velocities before an event, for the log's impulse)
    while True:
        if mode == PREDICT_ALL:
            npred = S.shape[0]
        else:
            i = queue.top(qt, E, hv, qhead, qs, qf)
            # (Every test of a family starts with `family is not None`: numba prunes it
            # all from a loop without it, which compiles as if it were not there.)
            kicked = False
            sliding = False
            if shear is not None:
                # The images' slide by a cell, due before the next event (or at its
                # time) or the next redraw, comes first.
                t_slide = shear.clock[sheared.T_NEXT]
                if t_slide <= t_end and (i < 0 or t_slide <= qt[i]) and (
                        thermostat is None or t_slide <= thermostat.t_next[0]):
                    if n_ev >= max_events:
                        status = REACHED_EVENT_LIMIT
                        break
                    if thermostat is None and (i < 0 or qt[i] == INF):
                        # No disk has an event: all are at rest (a moving disk
                        # crosses cells).  Their images slide past at U alone, so
                        # within one slide past the whole width every pair that ever
                        # meets is predicted; after that nothing ever happens.
                        shear.idle[0] += 1
                        if shear.idle[0] > ncx + 2:
                            status = NO_EVENTS
                            break
                    else:
                        shear.idle[0] = 0
                    sliding = True
                    t = t_slide
            if uniforms is not None and not sliding:
                if response.needs_random(uniforms) or (rough is not None
                                                       and _rough.needs_random(uniforms)):
                    status = NEED_RANDOM
                    break
            if thermostat is not None and not sliding:
                # A thermostat redraw due before the next event (or at its time) comes
                # first.
                t_kick = thermostat.t_next[0]
                if t_kick <= t_end and (i < 0 or t_kick <= qt[i]):
                    if n_ev >= max_events:
                        status = REACHED_EVENT_LIMIT
                        break
                    kicked = True
                    t = t_kick
                    i = response.kick(S.shape[0], thermostat, uniforms)
                    if invm[i] == 0.0:
                        continue  # (an immovable disk keeps its velocity)
            if thermostat is not None and kicked:
                kind = KICK
                partner = -1
                aux = -1
            elif shear is not None and sliding:
                kind = SLIDE
                partner = -1
                aux = -1
            else:
                if i < 0:
                    status = NO_EVENTS
                    break
                if qs[queue.LOOKAHEAD] != 0:
                    if qs[queue.CUR] != opened:
                        lookahead.lookahead(opened, qs[queue.CUR], qs[queue.FIRST], S, E, qt,
                                            tcand, gi, head, qhead, qs[queue.MASK])
                        opened = qs[queue.CUR]
                    else:
                        lookahead.stage_heap(S, E, qt, tcand, gi, head, hv, qs[queue.NHEAP])
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
                if t < tcand[i]:
                    kind = CROSS
                    partner = -1
                    aux = direction_of(E[i, KIND])
                else:
                    kind = kind_of(E[i, KIND])
                    partner = E[i, PARTNER]
                    aux = E[i, AUX]
            # Disks whose events must be predicted afresh once this event is handled.
            redo0 = -1
            redo1 = -1
            direction = -1  # of a cell crossing of i, for a partial prediction
            stale = False
            mark = -1  # (where the rests this event causes start in the log)
            if log_cap > 0 and kind != CROSS:
                pvx, pvy = velocity_at(i, t, S, gravity)
                if kind == DISK:
                    qvx, qvy = velocity_at(partner, t, S, gravity)

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
                elif response.stalls(i, j, t, invm, contact):
                    info[0] = i
                    info[1] = j
                    status = ERR_STALLED
                    break
                else:
                    if shear is not None:
                        sheared.flight(i, t, S, invm, shear)
                        sheared.flight(j, t, S, invm, shear)
                    if helfand is not None:
                        _helfand.flight(i, t, S, invm, helfand)
                        _helfand.flight(j, t, S, invm, helfand)
                    drift(i, t, S, gravity)
                    drift(j, t, S, gravity)
                    still = False  # (j at rest, and staying so)
                    if rest is not None:
                        still = resting.meet(i, j, t, aux, S, E, tcand, stamp, qt, hv, qhead,
                                             qs, qf, invm, gi, gf, head, nxt, wa, wb, wstart,
                                             wwall, wsx, wsy, acc, counts, heated, gravity,
                                             rest)
                        mark = log_n[0]
                    if rest is not None and still:
                        if resting.collide_static(i, j, t, aux, S, E, invm, gi, gf, head,
                                                  nxt, wa, wb, wstart, wwall, wsx, wsy, acc,
                                                  contact, heated, gravity, rest):
                            # (Wedged: at rest there if held, else it leaves j.)
                            if not resting.settle(i, t, S, E, tcand, stamp, qt, hv, qhead, qs,
                                                  qf, invm, gi, gf, head, nxt, wa, wb, wstart,
                                                  wwall, wsx, wsy, acc, counts, heated,
                                                  gravity, rest):
                                resting.lift_pair(i, j, aux, S, invm, acc, gf, gravity, rest)
                        stamp[i] += 1
                        redo0 = i
                    else:
                        # A contact that rounding left not approaching exchanges nothing but
                        # is a processed contact event like any other (as for walls, and as
                        # in the reference): counted, logged, both disks re-predicted.
                        if rest is not None:
                            # (The walls each slid on before the collision: it may
                            # release a disk that it pushes into its wall.)
                            held_i = gravity.support[i]
                            held_j = gravity.support[j]
                        if helfand is not None:
                            e_before = _helfand.energy(i, S, invm)
                        if rough is not None:
                            sticks = not _rough.smooth(i, j, t, contact)
                            vix, viy, vjx, vjy = S[i, VX], S[i, VY], S[j, VX], S[j, VY]
                        response.collide_pair(i, j, t, aux, S, invm, acc, gf, contact,
                                              gravity, growth, shear)
                        if rough is not None and sticks:
                            _rough.pair(i, j, t, aux, gf, vix, viy, vjx, vjy, S, invm, acc,
                                        rough)
                        if helfand is not None:
                            _helfand.heat(i, j, aux, e_before, S, invm, gf, helfand)
                        if rest is not None:
                            resting.part(i, j, aux, held_i, held_j, S, invm, acc, gf,
                                         gravity, rest)
                        stamp[i] += 1
                        stamp[j] += 1
                        redo0 = i
                        redo1 = j
                    counts[C_COLLISIONS] += 1
                    n_coll += 1
                    if rest is not None:
                        # Both disks of a pair are examined, and the first again if only
                        # the second came to rest (it may be the support the first
                        # lacked): what comes to rest does not depend on which of the
                        # two disks' predictions fired.
                        first = second = False
                        for k in range(3 if redo1 >= 0 else 1):
                            if k == 2 and (first or not second):
                                break
                            rested = resting.settle(j if k == 1 else i, t, S, E, tcand, stamp,
                                                    qt, hv, qhead, qs, qf, invm, gi, gf, head,
                                                    nxt, wa, wb, wstart, wwall, wsx, wsy, acc,
                                                    counts, heated, gravity, rest)
                            if k == 0:
                                first = rested
                            elif k == 1:
                                second = rested
            elif kind == SEGMENT or kind == BOX:
                # (stalls(i, i, ...): a wall has no streak of its own; passing i again,
                # not a literal -1, spares a second compiled copy.)
                if invm[i] == 0.0 or response.stalls(i, i, t, invm, contact):
                    info[0] = i
                    info[1] = partner if kind == SEGMENT else -1 - aux
                    status = ERR_IMMOVABLE_WALL if invm[i] == 0.0 else ERR_STALLED
                    break
                drift(i, t, S, gravity)
                if rest is not None:
                    # (Its collision before this one, for resting.slide.)
                    before = contact.t_last[i] if contact is not None else -INF
                if rough is not None:
                    sticks = (not _rough.smooth(i, i, t, contact)
                              and not response.hot(kind, partner, aux, heated))
                    vix, viy = S[i, VX], S[i, VY]
                # (One call site: each inlined copy lengthens the first compilation.)
                response.collide_wall(i, t, kind, partner, aux, S, invm, acc, wacc, gf,
                                      wa, wb, contact, heated, uniforms, gravity, growth,
                                      motion)
                if rough is not None and sticks:
                    _rough.wall(i, t, kind, partner, aux, vix, viy, S, invm, acc, wacc, gf,
                                wa, wb, rough, motion)
                stamp[i] += 1
                redo0 = i
                counts[C_WALL] += 1
                if rest is not None:
                    mark = log_n[0]
                    rest.t_static[i] = t
                    if not response.hot(kind, partner, aux, heated):
                        if kind == BOX:
                            resting.slide(i, aux, t, before, S, invm, acc, contact,
                                          gravity, rest)
                        else:
                            resting.lift_segment(i, partner, aux, S, invm, acc, gf, wa, wb,
                                                 gravity, rest)
                        resting.settle(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm,
                                       gi, gf, head, nxt, wa, wb, wstart, wwall, wsx, wsy,
                                       acc, counts, heated, gravity, rest)
            elif thermostat is not None and kind == KICK:
                if rest is not None:
                    resting.wake(i, t, i, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi,
                                 gf, head, nxt, wa, wb, wstart, wwall, wsx, wsy, acc,
                                 counts, heated, gravity, rest)
                if shear is not None:
                    sheared.flight(i, t, S, invm, shear)
                if helfand is not None:
                    _helfand.flight(i, t, S, invm, helfand)
                drift(i, t, S, gravity)
                response.redraw(i, S, invm, acc, thermostat, uniforms, gravity, shear)
                if rough is not None:
                    _rough.redraw(i, t, thermostat.kt, response.gaussian(uniforms), acc,
                                  rough)
                stamp[i] += 1
                redo0 = i
                counts[C_KICKS] += 1
            elif shear is not None and kind == SLIDE:
                slid = sheared.column_shift(shear, ncx)
                npred = sheared.slide(shear, gi, gf, head, nxt)
                if wide is not None:
                    npred = _wide.slide(npred, slid, sheared.column_shift(shear, ncx), gi,
                                        wide, shear.rows)
            else:  # CROSS
                if shear is not None:
                    sheared.flight(i, t, S, invm, shear)
                if helfand is not None:
                    _helfand.flight(i, t, S, invm, helfand)
                drift(i, t, S, gravity)
                if wide is not None and wide.index[i] >= 0:
                    # (A wide disk's footprint changes, or its centre wraps.)
                    direction = _wide.cross(i, t, aux, S, E, stamp, image, gi, gf, wide,
                                            shear)
                    redo0 = i
                else:
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
                        if shear is not None and axis == 1:
                            cx = sheared.wrap(i, t, wrap > 0, S, image, gi, gf, shear)
                    remove(i, c, head, nxt, prv)
                    c = cx + ncx * cy
                    insert(i, c, head, nxt, prv)
                    E[i, CELL] = c
                    if wrapped:
                        # Other disks' predictions hold i's image shift: invalidate
                        # them, and the kept candidate of i is in the old frame: predict
                        # afresh.
                        stamp[i] += 1
                        redo0 = i
                    else:
                        redo0 = i
                        direction = aux
                        if shear is not None and (cy == 0 or cy == ncy - 1):
                            direction = -1  # (an edge row: its neighbours slide)
                counts[C_CROSSINGS] += 1

            if not (shear is not None and sliding):
                npred = 0 if redo0 < 0 else (1 if redo1 < 0 else 2)

        # (One call site each for the prediction and the queue update: both are
        # compiled into the loop, and a second copy would lengthen compilation.)
        # Both disks are predicted before either is re-queued, so that the queue lines
        # the first update needs are loading while the second disk is predicted.
        for k in range(npred):
            if mode == PREDICT_ALL:
                d = k
                dk = -1
            elif shear is not None and sliding:
                d = shear.rows[k]
                dk = -1
            else:
                d = redo0 if k == 0 else redo1
                dk = direction if k == 0 else -1
            t_new = predict(d, t, dk, S, E, tcand, stamp, gi, gf, head, nxt,
                            wa, wb, wstart, wwall, wsx, wsy, gravity, growth, shear, wide,
                            motion)
            E[d, STAGED] = 0  # (a new event: no stage of the lookahead yet)
            if mode == PREDICT_ALL:
                qt[d] = t_new
            elif shear is not None and sliding:
                shear.times[k] = t_new
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
            if shear is not None and sliding:
                queue.set_time(shear.rows[k], shear.times[k], qt, E, hv, qhead, qs, qf)
            else:
                queue.set_time(redo0 if k == 0 else redo1,
                               t_redo0 if k == 0 else t_redo1, qt, E, hv, qhead, qs, qf)
        if stale:
            counts[C_STALE] += 1
            continue

        n_ev += 1
        out[0] = t
        if kind != CROSS and log_cap > 0 and not (shear is not None and sliding):
            k = log_n[0]
            if k < log_t.shape[0]:
                slot = k
                if 0 <= mark < k:
                    # The rests the event caused are logged: it goes before them.
                    _make_room(mark, k, log_t, log_e, log_j)
                    slot = mark
                _log_event(slot, t, kind, i, partner, aux, pvx, pvy, qvx, qvy, S, invm,
                           order, log_t, log_e, log_j, gravity, rest)
            log_n[0] = k + 1
            if log_n[0] >= log_cap and n_coll < max_collisions:
                status = LOG_FULL  # (return for the log to be emptied, then go on)
                break
        if n_coll >= max_collisions:
            status = REACHED_COLLISIONS
            break
    return status
