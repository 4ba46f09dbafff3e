"""The event loop (seed section 3), one scheduled event per disk.

Each disk ``i`` keeps its own earliest predicted event in ``ev_t[i]`` and
``ev_i[i] = (kind, partner, aux, partner_stamp)``; the disks sit in an indexed heap keyed
by that time.  ``stamp[i]`` (the invalidation counter) grows whenever disk ``i``'s
trajectory changes (a collision) or its stored coordinates jump (a periodic wrap).

Why one event per disk is enough: the event of ``i`` is the minimum over all of ``i``'s
candidate events.  If a partner ``j`` changes course, ``j`` itself is re-predicted against
all its neighbours, ``i`` included, so any new ``i``-``j`` contact is held by ``j``.  The
other candidates of ``i`` are all later than ``i``'s stale event, so when a stale event
reaches the top (partner stamp changed) it suffices to re-predict ``i`` then.

Positions are "delayed states": ``pos[i]`` is valid at ``tloc[i]``; only the disks of an
event are moved to its time.
"""

from __future__ import annotations

import math

from .._jit import njit
from . import queue
from .grid import insert, neighbour, remove
from .predict import INF, box_wall_time, exit_time, pair_time, segment_time

# Event kinds (ev_i[:, 0])
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
# impulse delivered to each box wall (x=0, x=W, y=0, y=H) and to all wall segments.
A_VIRIAL = 0
A_BOX = 1  # 1..4
A_SEGMENTS = 5
N_ACC = 6

# Status codes returned by run()
REACHED_TIME = 0
REACHED_COLLISIONS = 1
REACHED_EVENT_LIMIT = 2
NO_EVENTS = 3
ERR_IMMOVABLE_PAIR = 10
ERR_IMMOVABLE_WALL = 11


@njit
def predict_disk(i, t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                 wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i):
    """Find the earliest event of disk ``i`` from time ``t`` on and store it."""
    ncx = gi[0]
    ncy = gi[1]
    perx = gi[2] != 0
    pery = gi[3] != 0
    width = gf[0]
    height = gf[1]
    lx = gf[2]
    ly = gf[3]

    dt0 = t - tloc[i]
    vx = vel[i, 0]
    vy = vel[i, 1]
    x = pos[i, 0] + dt0 * vx
    y = pos[i, 1] + dt0 * vy
    r = rad[i]
    c = cell[i]
    cx = c % ncx
    cy = c // ncx

    # Leaving the cell.
    best, direction = exit_time(x, vx, cx, lx, ncx, perx)
    kind = CROSS
    partner = -1
    aux = 0 if direction > 0 else 1
    pst = 0
    dty, diry = exit_time(y, vy, cy, ly, ncy, pery)
    if dty < best:
        best = dty
        aux = 2 if diry > 0 else 3
    if best == INF:
        kind = NONE

    # The box walls of non-periodic axes.
    if not perx:
        dtw, side = box_wall_time(x, vx, r, width)
        if dtw < best:
            best = dtw
            kind = BOX
            aux = side
            partner = -1
    if not pery:
        dtw, side = box_wall_time(y, vy, r, height)
        if dtw < best:
            best = dtw
            kind = BOX
            aux = 2 + side
            partner = -1

    # Disks in the 3x3 neighbourhood (each (cell, image shift) visited once).
    for ox in range(-1, 2):
        nxc, sx = neighbour(cx, ox, ncx, perx)
        if nxc < 0:
            continue
        for oy in range(-1, 2):
            nyc, sy = neighbour(cy, oy, ncy, pery)
            if nyc < 0:
                continue
            j = head[nxc + ncx * nyc]
            while j >= 0:
                if j != i:
                    dtj = t - tloc[j]
                    vjx = vel[j, 0]
                    vjy = vel[j, 1]
                    dx = x - (pos[j, 0] + dtj * vjx + sx * width)
                    dy = y - (pos[j, 1] + dtj * vjy + sy * height)
                    dtc = pair_time(dx, dy, vx - vjx, vy - vjy, r + rad[j])
                    if dtc < best:
                        best = dtc
                        kind = DISK
                        partner = j
                        aux = (sx + 1) * 3 + (sy + 1)
                        pst = stamp[j]
                j = nxt[j]

    # Wall segments (and their periodic images) near this cell.
    for k in range(wstart[c], wstart[c + 1]):
        w = wwall[k]
        shx = wsx[k] * width
        shy = wsy[k] * height
        dtw, part = segment_time(x, y, vx, vy, r,
                                 wa[w, 0] + shx, wa[w, 1] + shy,
                                 wb[w, 0] + shx, wb[w, 1] + shy)
        if dtw < best:
            best = dtw
            kind = SEGMENT
            partner = w
            aux = part + 3 * ((wsx[k] + 1) * 3 + (wsy[k] + 1))

    ev_t[i] = t + best
    ev_i[i, 0] = kind
    ev_i[i, 1] = partner
    ev_i[i, 2] = aux
    ev_i[i, 3] = pst


@njit
def predict_all(t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i, heap, where):
    """Predict every disk's next event from time ``t`` and rebuild the queue."""
    for i in range(pos.shape[0]):
        predict_disk(i, t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                     wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i)
    queue.build(heap, where, ev_t)


@njit(inline="always")
def _advance(i, t, pos, vel, tloc):
    dt = t - tloc[i]
    pos[i, 0] += dt * vel[i, 0]
    pos[i, 1] += dt * vel[i, 1]
    tloc[i] = t


@njit(inline="always")
def _reflect(i, nx, ny, vel, invm, acc, slot):
    """Mirror the velocity of disk ``i`` in the unit normal ``n`` (if approaching)."""
    vn = vel[i, 0] * nx + vel[i, 1] * ny
    if vn < 0.0:
        vel[i, 0] -= 2.0 * vn * nx
        vel[i, 1] -= 2.0 * vn * ny
        acc[slot] += -2.0 * vn / invm[i]


@njit
def run(t_end, max_collisions, max_events,
        pos, vel, tloc, rad, invm, stamp, image,
        gi, gf, cell, head, nxt, prv,
        wa, wb, wstart, wwall, wsx, wsy,
        ev_t, ev_i, heap, where,
        counts, acc, out, info, log_t, log_e, log_n):
    """Process events in time order.

    Stops before the first event later than ``t_end``, right after the
    ``max_collisions``-th disk-disk collision of this call, or after ``max_events``
    processed events.  ``out[0]`` receives the time of the last processed event (or is
    left unchanged if none was processed).  Returns a status code; on an error the
    offending disks (or disk and wall) are written to ``info`` and the state is left as
    it was just before that event.

    If ``log_t`` has room, every disk-disk, segment and box-wall event is recorded as
    ``log_t[k]``, ``log_e[k] = (kind, i, partner)`` with ``log_n[0]`` counting them all.
    """
    ncx = gi[0]
    ncy = gi[1]
    width = gf[0]
    height = gf[1]
    log_cap = log_t.shape[0]
    n_coll = 0
    n_ev = 0
    status = REACHED_TIME
    while True:
        i = heap[0]
        t = ev_t[i]
        if t == INF:
            status = NO_EVENTS
            break
        if t > t_end:
            status = REACHED_TIME
            break
        if n_ev >= max_events:
            status = REACHED_EVENT_LIMIT
            break
        kind = ev_i[i, 0]
        partner = ev_i[i, 1]
        aux = ev_i[i, 2]

        if kind == DISK:
            j = partner
            if stamp[j] != ev_i[i, 3]:
                # The partner changed course since this was predicted: re-predict i only.
                predict_disk(i, t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                             wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i)
                queue.update(heap, where, ev_t, i)
                counts[C_STALE] += 1
                continue
            if invm[i] == 0.0 and invm[j] == 0.0:
                info[0] = i
                info[1] = j
                status = ERR_IMMOVABLE_PAIR
                break
            _advance(i, t, pos, vel, tloc)
            _advance(j, t, pos, vel, tloc)
            sx = aux // 3 - 1
            sy = aux % 3 - 1
            dx = pos[i, 0] - (pos[j, 0] + sx * width)
            dy = pos[i, 1] - (pos[j, 1] + sy * height)
            dist = math.sqrt(dx * dx + dy * dy)
            nx = dx / dist
            ny = dy / dist
            dvn = (vel[i, 0] - vel[j, 0]) * nx + (vel[i, 1] - vel[j, 1]) * ny
            if dvn < 0.0:
                # Impulse J along n: momentum J n moves from j to i; with the reduced
                # mass this reverses the normal relative velocity (elastic).
                impulse = -2.0 * dvn / (invm[i] + invm[j])
                vel[i, 0] += impulse * invm[i] * nx
                vel[i, 1] += impulse * invm[i] * ny
                vel[j, 0] -= impulse * invm[j] * nx
                vel[j, 1] -= impulse * invm[j] * ny
                acc[A_VIRIAL] += impulse * dist
            stamp[i] += 1
            stamp[j] += 1
            predict_disk(i, t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                         wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i)
            queue.update(heap, where, ev_t, i)
            predict_disk(j, t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                         wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i)
            queue.update(heap, where, ev_t, j)
            counts[C_COLLISIONS] += 1
            n_coll += 1
        elif kind == SEGMENT or kind == BOX:
            if invm[i] == 0.0:
                info[0] = i
                info[1] = partner if kind == SEGMENT else -1 - aux
                status = ERR_IMMOVABLE_WALL
                break
            _advance(i, t, pos, vel, tloc)
            if kind == BOX:
                axis = aux // 2
                # Lower wall: normal +e; upper wall: normal -e.
                sign = 1.0 if aux % 2 == 0 else -1.0
                if axis == 0:
                    _reflect(i, sign, 0.0, vel, invm, acc, A_BOX + aux)
                else:
                    _reflect(i, 0.0, sign, vel, invm, acc, A_BOX + aux)
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
                    if (pos[i, 0] - ax) * nx + (pos[i, 1] - ay) * ny < 0.0:
                        nx = -nx
                        ny = -ny
                else:
                    ex = ax if part == 1 else bx
                    ey = ay if part == 1 else by
                    nx = pos[i, 0] - ex
                    ny = pos[i, 1] - ey
                    ln = math.sqrt(nx * nx + ny * ny)
                    nx /= ln
                    ny /= ln
                _reflect(i, nx, ny, vel, invm, acc, A_SEGMENTS)
            stamp[i] += 1
            predict_disk(i, t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                         wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i)
            queue.update(heap, where, ev_t, i)
            counts[C_WALL] += 1
        else:  # CROSS
            _advance(i, t, pos, vel, tloc)
            c = cell[i]
            cx = c % ncx
            cy = c // ncx
            wrapped = False
            if aux == 0:
                cx += 1
                if cx == ncx:
                    cx = 0
                    pos[i, 0] -= width
                    image[i, 0] += 1
                    wrapped = True
            elif aux == 1:
                cx -= 1
                if cx < 0:
                    cx = ncx - 1
                    pos[i, 0] += width
                    image[i, 0] -= 1
                    wrapped = True
            elif aux == 2:
                cy += 1
                if cy == ncy:
                    cy = 0
                    pos[i, 1] -= height
                    image[i, 1] += 1
                    wrapped = True
            else:
                cy -= 1
                if cy < 0:
                    cy = ncy - 1
                    pos[i, 1] += height
                    image[i, 1] -= 1
                    wrapped = True
            if wrapped:
                # Events of other disks hold i's image shift: invalidate them.
                stamp[i] += 1
            remove(i, cell, head, nxt, prv)
            insert(i, cx + ncx * cy, cell, head, nxt, prv)
            predict_disk(i, t, pos, vel, tloc, rad, stamp, gi, gf, cell, head, nxt,
                         wa, wb, wstart, wwall, wsx, wsy, ev_t, ev_i)
            queue.update(heap, where, ev_t, i)
            counts[C_CROSSINGS] += 1

        n_ev += 1
        out[0] = t
        if kind != CROSS and log_cap > 0:
            k = log_n[0]
            if k < log_cap:
                log_t[k] = t
                log_e[k, 0] = kind
                log_e[k, 1] = i
                log_e[k, 2] = partner if kind != BOX else aux
            log_n[0] = k + 1
        if n_coll >= max_collisions:
            status = REACHED_COLLISIONS
            break
    return status


@njit
def synchronized_positions(t, pos, vel, tloc, gi, gf, out):
    """Positions of all disks at time ``t`` (>= every local time), wrapped into the box."""
    for i in range(pos.shape[0]):
        dt = t - tloc[i]
        x = pos[i, 0] + dt * vel[i, 0]
        y = pos[i, 1] + dt * vel[i, 1]
        if gi[2] != 0:
            x -= gf[0] * math.floor(x / gf[0])
        if gi[3] != 0:
            y -= gf[1] * math.floor(y / gf[1])
        out[i, 0] = x
        out[i, 1] = y

