"""Prediction: a disk's next event, from a scan of its grid neighbourhood.

A disk's event is the earliest of its candidates: contacts with the disks in its 3x3
neighbour cells, with the wall segments listed for its cell and with the box walls
(:mod:`.predict` gives each contact time), and leaving its cell.  The best candidate
that is not a cell crossing is kept in the disk's bookkeeping row (the "kept
candidate": kind, partner, aux, the partner's stamp, and its time ``tcand``); the
scheduled event is the crossing if it comes first.

Why a cell crossing only needs the newly exposed cells: the kept candidate is the
earliest contact with everything in the old neighbourhood (still exact if its
partner's stamp is unchanged); disks that entered the old neighbourhood since then
predicted against ``i`` themselves; so only the row of cells that comes into range
must be scanned.  A wrap, or a stale kept candidate, falls back to a full scan.

Moving wall segments (:mod:`.moving`) are listed wherever their path comes near; a
disk's contact with one is searched up to its cell exit at the latest, which a full or
partial scan after the crossing takes up again.

Wide disks (:mod:`.wide`): a narrow disk also scans the wide disks listed in its own
cell (:func:`_scan_wide_list`); a wide disk is predicted by :func:`_predict_wide`, over
the cells of its footprint, and schedules the next change of its footprint instead
of a cell crossing.
"""

from __future__ import annotations

from .._jit import njit
from . import moving as _moving
from . import prefetch, sheared
from .flight import acceleration, position_at, velocity_at
from .grid import neighbour
from .layout import (
    AUX,
    BOX,
    CELL,
    DISK,
    FIXED,
    KIND,
    NONE,
    PARTNER,
    PSTAMP,
    RESTING,
    SEGMENT,
    VX,
    VY,
    R,
    kind_of,
    pack_kind,
    pack_segment,
    pack_shift,
)
from .predict import (
    INF,
    box_wall_time,
    box_wall_time_accel,
    box_wall_time_grow,
    exit_time,
    exit_time_accel,
    growth_factor,
    pair_time,
    pair_time_grow,
    point_time,
    segment_time,
    segment_time_accel,
    segment_time_grow,
)
from .wide import HIGH, LOW, columns


@njit
def _pair_time_accel(j, t, dx, dy, vx, vy, gxi, gyi, r, S, gravity, best):
    """Under gravity: the contact time of a disk (separation ``d``, velocity ``v``,
    acceleration ``g_i`` at time ``t``) with disk ``j``.  (Not inlined into the scan:
    the straight-line loop would otherwise carry this code through numba's inlining
    before pruning it, which lengthened its compilation.)"""
    vxj, vyj = velocity_at(j, t, S, gravity)
    gxj, gyj = acceleration(j, gravity)
    if gxi == gxj and gyi == gyj:
        return pair_time(dx, dy, vx - vxj, vy - vyj, r + S[j, R])
    return point_time(dx, dy, vx - vxj, vy - vyj, gxi - gxj, gyi - gyj, r + S[j, R], best)


@njit(inline="always")
def _scan_disks(i, t, x, y, vx, vy, r, cx, cy, ox0, ox1, oy0, oy1,
                S, stamp, gi, gf, head, nxt, best, partner, aux, pst, gravity, growth,
                shear):
    """Earliest contact of disk ``i`` (at ``x, y`` with velocity ``vx, vy`` at time
    ``t``) with the disks in the cells at offsets ``[ox0, ox1] x [oy0, oy1]`` from
    ``(cx, cy)``, if before ``best`` (a time interval from ``t``).

    Under gravity two movable disks (or two immovable ones) share their acceleration:
    their relative motion is a straight line and :func:`pair_time` holds; a movable
    disk against an immovable one is a parabola against a fixed point
    (:func:`point_time`).

    Under growth ``r`` is the stored radius ``S[i, R]``, and the contact distance
    ``(r + S[j, R])`` times :func:`growth_factor` grows at ``(r + S[j, R]) rate``.

    Under shear the rows across the sliding boundary are scanned by
    :func:`.sheared.scan_across`, after the others."""
    gxi, gyi = acceleration(i, gravity)
    f = growth_factor(t, growth)
    ncx = gi[0]
    for ox in range(ox0, ox1 + 1):
        nxc, sx = neighbour(cx, ox, ncx, gi[2] != 0)
        if nxc < 0:
            continue
        for oy in range(oy0, oy1 + 1):
            nyc, sy = neighbour(cy, oy, gi[1], gi[3] != 0)
            if nyc < 0:
                continue
            if shear is not None and sy != 0:
                continue
            j = head[nxc + ncx * nyc]
            while j >= 0:
                if j != i:
                    xj, yj = position_at(j, t, S, gravity)
                    dx = x - (xj + sx * gf[0])
                    dy = y - (yj + sy * gf[1])
                    if growth is not None:
                        rr = r + S[j, R]
                        dtc = pair_time_grow(dx, dy, vx - S[j, VX], vy - S[j, VY], rr * f,
                                             rr * growth.rate)
                    elif gravity is None:
                        dtc = pair_time(dx, dy, vx - S[j, VX], vy - S[j, VY], r + S[j, R])
                    else:
                        dtc = _pair_time_accel(j, t, dx, dy, vx, vy, gxi, gyi, r, S, gravity,
                                               best)
                    if dtc < best:
                        best = dtc
                        partner = j
                        aux = pack_shift(sx, sy)
                        pst = stamp[j]
                j = nxt[j]
    if shear is not None:
        best, partner, aux, pst = sheared.scan_across(i, t, x, y, vx, vy, r, cx, cy, oy0,
                                                      oy1, S, stamp, gi, gf, head, nxt,
                                                      best, partner, aux, pst, shear)
    return best, partner, aux, pst


@njit(inline="always")
def _scan_walls(x, y, vx, vy, gx, gy, r, dr, c, gf, wa, wb, wstart, wwall, wsx, wsy,
                best, partner, aux, gravity, growth):
    """Earliest contact with the wall segments listed for cell ``c``, if before ``best``
    (``gx, gy``: the disk's acceleration under gravity; ``dr``: its radius's growth
    speed under growth)."""
    if wa.shape[0] == 0:  # no segments: spare the bucket lookup (a cache miss at large N)
        return best, partner, aux
    for k in range(wstart[c], wstart[c + 1]):
        w = wwall[k]
        shx = wsx[k] * gf[0]
        shy = wsy[k] * gf[1]
        if growth is not None:
            dtw, part = segment_time_grow(x, y, vx, vy, r, dr,
                                          wa[w, 0] + shx, wa[w, 1] + shy,
                                          wb[w, 0] + shx, wb[w, 1] + shy)
        elif gravity is None or (gx == 0.0 and gy == 0.0):
            dtw, part = segment_time(x, y, vx, vy, r,
                                     wa[w, 0] + shx, wa[w, 1] + shy,
                                     wb[w, 0] + shx, wb[w, 1] + shy)
        else:
            dtw, part = segment_time_accel(x, y, vx, vy, gx, gy, r,
                                           wa[w, 0] + shx, wa[w, 1] + shy,
                                           wb[w, 0] + shx, wb[w, 1] + shy, best)
        if dtw < best:
            best = dtw
            partner = w
            aux = pack_segment(part, pack_shift(wsx[k], wsy[k]))
    return best, partner, aux


@njit(inline="always")
def _box_walls(x, y, vx, vy, gx, gy, r, dr, gi, gf, gravity, growth):
    """Earliest contact with the box walls of the walled axes: ``(dt, kind, side)``,
    ``kind`` ``BOX`` or ``NONE`` (``r``: the radius now; ``dr``: its growth speed
    under growth; ``gx, gy``: the acceleration under gravity)."""
    best = INF
    kind = NONE
    aux = 0
    if gi[2] == 0:
        if growth is not None:
            dtw, side = box_wall_time_grow(x, vx, r, dr, gf[0])
        elif gravity is None:
            dtw, side = box_wall_time(x, vx, r, gf[0])
        else:
            dtw, side = box_wall_time_accel(x, vx, gx, r, gf[0])
        if dtw < best:
            best = dtw
            kind = BOX
            aux = side
    if gi[3] == 0:
        if growth is not None:
            dtw, side = box_wall_time_grow(y, vy, r, dr, gf[1])
        elif gravity is None:
            dtw, side = box_wall_time(y, vy, r, gf[1])
        else:
            dtw, side = box_wall_time_accel(y, vy, gy, r, gf[1])
        if dtw < best:
            best = dtw
            kind = BOX
            aux = 2 + side
    return best, kind, aux


@njit(inline="always")
def _schedule(i, t, x, y, vx, vy, gx, gy, cx, cy, tcand, E, gi, gf, gravity):
    """The time of disk ``i``'s next event: the earlier of its kept candidate and
    leaving its cell (whose direction is recorded in ``E[i, KIND]``)."""
    if gravity is None:
        dtx, dirx = exit_time(x, vx, cx, gf[2], gi[0], gi[2] != 0)
        dty, diry = exit_time(y, vy, cy, gf[3], gi[1], gi[3] != 0)
    else:
        dtx, dirx = exit_time_accel(x, vx, gx, cx, gf[2], gi[0], gi[2] != 0)
        dty, diry = exit_time_accel(y, vy, gy, cy, gf[3], gi[1], gi[3] != 0)
    if dty < dtx:
        dtx = dty
        aux = 2 if diry > 0 else 3
    else:
        aux = 0 if dirx > 0 else 1
    E[i, KIND] = pack_kind(kind_of(E[i, KIND]), aux)
    return min(tcand[i], t + dtx)


@njit(inline="always")
def predict(i, t, direction, S, E, tcand, stamp, gi, gf, head, nxt,
            wa, wb, wstart, wwall, wsx, wsy, gravity, growth, shear, wide, motion):
    """Predict disk ``i``'s next event from time ``t``, keep its best non-crossing
    candidate, and return the time of the scheduled event.

    ``direction = -1``: a full prediction (all 9 neighbour cells, the walls listed for
    its cell, the box walls).  ``direction`` 0-3: ``i`` has just crossed into its
    current cell (not wrapped) in direction +x, -x, +y, -y; if its kept candidate is
    still valid only the newly exposed row of 3 cells (and the cell's walls) is
    scanned against it, otherwise the prediction is a full one.

    ``growth``: ``None``, or radii that grow (``layout.Growth``, :func:`growth_factor`).
    ``shear``: ``None``, or Lees-Edwards boundaries (``layout.Shear``, :mod:`.sheared`).
    ``motion``: ``None``, or wall segments that move (``layout.Motion``,
    :mod:`.moving`).
    ``wide``: ``None``, or disks wider than the cells (``layout.Wide``,
    :mod:`.wide`): a wide disk is predicted by :func:`.wide.predict` (``direction``
    then the code of its crossing), and a narrow one also scans its own cell's list of
    wide disks.

    (One function for both, compiled into the event loop at a single place.)
    """
    if gravity is not None and gravity.support[i] & RESTING:
        # At rest: no event of its own (flying disks hold their contacts with it), and
        # a wide disk's footprint holds still.
        tcand[i] = INF
        E[i, KIND] = NONE
        return INF
    if wide is not None and wide.index[i] >= 0:
        return _predict_wide(i, t, direction, S, E, tcand, stamp, gi, gf, head, nxt, wa,
                             wb, wstart, wwall, wsx, wsy, gravity, growth, wide, motion,
                             shear)
    partial = direction >= 0 and not (
        kind_of(E[i, KIND]) == DISK and stamp[E[i, PARTNER]] != E[i, PSTAMP])
    if gravity is None:
        vx = S[i, VX]
        vy = S[i, VY]
        gx = 0.0
        gy = 0.0
    else:
        vx, vy = velocity_at(i, t, S, gravity)
        gx, gy = acceleration(i, gravity)
    x, y = position_at(i, t, S, gravity)
    r = S[i, R]
    dr = 0.0
    if growth is not None:
        dr = r * growth.rate
        r *= growth_factor(t, growth)
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
        best = tcand[i] - t
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
        best, kind, aux = _box_walls(x, y, vx, vy, gx, gy, r, dr, gi, gf, gravity, growth)
    partner = -1
    pst = 0
    bd, pd, ad, ps = _scan_disks(i, t, x, y, vx, vy, S[i, R], cx, cy, ox0, ox1, oy0, oy1,
                                 S, stamp, gi, gf, head, nxt, best, -1, 0, 0, gravity,
                                 growth, shear)
    if bd < best:
        best = bd
        kind = DISK
        partner = pd
        aux = ad
        pst = ps
    if wide is not None:
        bd, pd, ad, ps = _scan_wide_list(i, t, x, y, vx, vy, S[i, R], c, S, stamp, gf,
                                         wide, best, -1, 0, 0, gravity, growth, shear)
        if bd < best:
            best = bd
            kind = DISK
            partner = pd
            aux = ad
            pst = ps
    if motion is not None:
        bw, pw, aw = _moving.scan_walls(t, x, y, vx, vy, gx, gy, r, c, cx, cy, gi, gf, wa,
                                        wb, wstart, wwall, wsx, wsy, best, gravity, motion)
    else:
        bw, pw, aw = _scan_walls(x, y, vx, vy, gx, gy, r, dr, c, gf, wa, wb, wstart, wwall,
                                 wsx, wsy, best, -1, 0, gravity, growth)
    if bw < best:
        best = bw
        kind = SEGMENT
        partner = pw
        aux = aw
        pst = 0
    if not partial or kind != NONE:
        tcand[i] = t + best
        E[i, KIND] = kind
        E[i, PARTNER] = partner
        E[i, AUX] = aux
        E[i, PSTAMP] = pst
    return _schedule(i, t, x, y, vx, vy, gx, gy, cx, cy, tcand, E, gi, gf, gravity)


# --------------------------------------------------------------------------- wide disks
@njit
def _scan_wide_list(i, t, x, y, vx, vy, r, c, S, stamp, gf, wide, best, partner, aux,
                    pst, gravity, growth, shear):
    """Earliest contact of the narrow disk ``i`` (at ``x, y`` with velocity ``vx, vy``
    at time ``t``) with the wide disks listed in its cell ``c``, if before ``best``."""
    gxi, gyi = acceleration(i, gravity)
    m = wide.bhead[c]
    while m >= 0:
        j = wide.disk[wide.nk[m]]
        sx = wide.nsx[m]
        sy = wide.nsy[m]
        dtc = _wide_pair(i, j, t, x, y, vx, vy, gxi, gyi, r, -sx, -sy, S, gf, gravity,
                         growth, shear, best)
        if dtc < best:
            best = dtc
            partner = j
            aux = pack_shift(-sx if shear is None or sy == 0 else 0, -sy)
            pst = stamp[j]
        m = wide.nnext[m]
    return best, partner, aux, pst


@njit
def _wide_pair(i, j, t, x, y, vx, vy, gxi, gyi, r, sx, sy, S, gf, gravity, growth, shear,
               best):
    """Contact time of ``i`` (stored radius ``r``) with the image ``(sx, sy)`` of ``j``
    (as the narrow scan computes it: with gravity's parabola against an immovable
    disk, or growing radii; under shear an image across the sliding boundary, ``sy !=
    0``, lies ``sy`` offsets along x and moves at ``sy U`` more)."""
    xj, yj = position_at(j, t, S, gravity)
    dx = x - (xj + sx * gf[0])
    dy = y - (yj + sy * gf[1])
    if shear is not None and sy != 0:
        dx -= sy * sheared.offset(t, shear)
        return pair_time(dx, dy, vx - (S[j, VX] + sy * shear.speed), vy - S[j, VY],
                         r + S[j, R])
    if growth is not None:
        rr = r + S[j, R]
        return pair_time_grow(dx, dy, vx - S[j, VX], vy - S[j, VY],
                              rr * growth_factor(t, growth), rr * growth.rate)
    if gravity is None:
        return pair_time(dx, dy, vx - S[j, VX], vy - S[j, VY], r + S[j, R])
    return _pair_time_accel(j, t, dx, dy, vx, vy, gxi, gyi, r, S, gravity, best)


@njit
def _scan_footprint(i, k, t, x, y, vx, vy, gx, gy, r, u0, u1, v0, v1, S, stamp, gi, gf,
                    head, nxt, wa, wb, wstart, wwall, wsx, wsy, wide, best, kind, partner,
                    aux, pst, gravity, growth, motion, horizon, shear):
    """Earliest contact of wide disk ``i`` (index ``k``, stored radius ``r``) with the
    narrow disks, the wide disks and the wall segments listed in the unwrapped cells
    ``[u0, u1] x [v0, v1]`` of its footprint (under shear, the rows across the
    boundary shifted as :func:`.wide.columns` gives them); a moving segment
    (``motion``) searched up to ``horizon`` at the latest, the footprint's next change
    (a full prediction then takes the search up again)."""
    f = growth_factor(t, growth)
    dr = 0.0 if growth is None else r * growth.rate
    ncx = gi[0]
    # (A segment is listed in many cells of a footprint: the contact time of the image
    # last computed is kept for the next cells that list it; a fixed segment's, only
    # while the limit it was found under holds, which keeps every result as it was.)
    last_w = -1
    last_qx = 0
    last_qy = 0
    last_best = INF
    last_dt = INF
    last_part = 0
    slid = -1 if shear is None else sheared.column_shift(shear, ncx)
    for v in range(v0, v1 + 1):
        ky = 0
        if gi[3] != 0:
            ky = v // gi[1]
        cy = v - ky * gi[1]
        c0, c1 = columns(u0, u1, v, gi, slid)
        for u in range(c0, c1 + 1):
            kx = 0
            if gi[2] != 0:
                kx = u // ncx
            c = (u - kx * ncx) + ncx * cy
            # The narrow disks of the cell, seen from i's image over it (x - k L).
            j = head[c]
            while j >= 0:
                dtc = _wide_pair(i, j, t, x, y, vx, vy, gx, gy, r, kx, ky, S, gf, gravity,
                                 growth, shear, best)
                if dtc < best:
                    best = dtc
                    kind = DISK
                    partner = j
                    aux = pack_shift(kx if shear is None or ky == 0 else 0, ky)
                    pst = stamp[j]
                j = nxt[j]
            # The other wide disks listed there: j's image is at x_j - k' L.
            m = wide.bhead[c]
            while m >= 0:
                kk = wide.nk[m]
                if kk != k:
                    j = wide.disk[kk]
                    sx = kx - wide.nsx[m]
                    sy = ky - wide.nsy[m]
                    # (Across a sheared boundary the offset adds up to a width: the
                    # image may lie two widths over, and the collision takes the
                    # nearest image, as the narrow disks' does.)
                    across = shear is not None and sy != 0
                    if (-1 <= sx <= 1 or (across and -2 <= sx <= 2)) and -1 <= sy <= 1:
                        dtc = _wide_pair(i, j, t, x, y, vx, vy, gx, gy, r, sx, sy, S, gf,
                                         gravity, growth, shear, best)
                        if dtc < best:
                            best = dtc
                            kind = DISK
                            partner = j
                            aux = pack_shift(0 if across else sx, sy)
                            pst = stamp[j]
                m = wide.nnext[m]
            # The segments listed for the cell, shifted as for a centre in it: i's image
            # over the cell is one (kx, ky) periods away from i itself.
            if wa.shape[0] > 0:
                for q in range(wstart[c], wstart[c + 1]):
                    w = wwall[q]
                    qx = wsx[q] + kx
                    qy = wsy[q] + ky
                    ax = wa[w, 0] + qx * gf[0]
                    ay = wa[w, 1] + qy * gf[1]
                    bx = wb[w, 0] + qx * gf[0]
                    by = wb[w, 1] + qy * gf[1]
                    moves = motion is not None and motion.kind[w] != FIXED
                    if (w == last_w and qx == last_qx and qy == last_qy
                            and (moves or best == last_best)):
                        dtw = last_dt  # (a fixed segment: the same search, same limit)
                        part = last_part
                    else:
                        if moves:
                            dtw, part = _moving.contact_time(t, x, y, vx, vy, gx, gy, r, ax,
                                                             ay, bx, by, w, motion,
                                                             min(best, horizon))
                        elif growth is not None:
                            dtw, part = segment_time_grow(x, y, vx, vy, r * f, dr, ax, ay,
                                                          bx, by)
                        elif gravity is None or (gx == 0.0 and gy == 0.0):
                            dtw, part = segment_time(x, y, vx, vy, r, ax, ay, bx, by)
                        else:
                            dtw, part = segment_time_accel(x, y, vx, vy, gx, gy, r, ax, ay,
                                                           bx, by, best)
                        last_w = w
                        last_qx = qx
                        last_qy = qy
                        last_best = best
                        last_dt = dtw
                        last_part = part
                    if dtw < best and -1 <= qx <= 1 and -1 <= qy <= 1:
                        best = dtw
                        kind = SEGMENT
                        partner = w
                        aux = pack_segment(part, pack_shift(qx, qy))
                        pst = 0
    return best, kind, partner, aux, pst


@njit
def _edge_time(e, v, a, c, side, ncell, periodic, gravity):
    if gravity is None:
        return exit_time(e, v, c, side, ncell, periodic)
    return exit_time_accel(e, v, a, c, side, ncell, periodic)


@njit
def _moving_listed(u0, u1, v0, v1, gi, wa, wstart, wwall, motion):
    """Whether a moving segment is listed in a cell of the unwrapped block ``[u0, u1] x
    [v0, v1]``."""
    if wa.shape[0] == 0:
        return False
    for v in range(v0, v1 + 1):
        cy = v % gi[1] if gi[3] != 0 else v
        for u in range(u0, u1 + 1):
            c = (u % gi[0] if gi[2] != 0 else u) + gi[0] * cy
            for q in range(wstart[c], wstart[c + 1]):
                if motion.kind[wwall[q]] != FIXED:
                    return True
    return False


@njit
def _predict_wide(i, t, code, S, E, tcand, stamp, gi, gf, head, nxt, wa, wb, wstart, wwall,
                  wsx, wsy, gravity, growth, wide, motion, shear):
    """:func:`predict` for a wide disk (:mod:`.wide`): its next event from time ``t``.

    ``code`` -1: a full prediction (box walls and every cell of its footprint).
    Otherwise the crossing ``code`` (``4 * what + direction``) has just grown its
    footprint by the column or row it names, or shrunk it: if its kept candidate is
    still valid only the new cells are scanned against it (none for a shrink).  A
    moving segment (``motion``) is searched up to the footprint's next change only, so
    while one is listed in the footprint every prediction is full: it takes the
    search up again."""
    k = wide.index[i]
    if gravity is None:
        vx = S[i, VX]
        vy = S[i, VY]
        gx = 0.0
        gy = 0.0
    else:
        vx, vy = velocity_at(i, t, S, gravity)
        gx, gy = acceleration(i, gravity)
    x, y = position_at(i, t, S, gravity)
    r = S[i, R]
    # The next change of the footprint (or wrap of the centre).  Under growth an edge
    # moves at the velocity plus or minus the radius's growth speed.
    reach = r * growth_factor(t, growth) + wide.half
    grow = 0.0 if growth is None else r * growth.rate
    first = INF
    sched = 0
    for axis in range(2):
        side = gf[2 + axis]
        ncell = gi[axis]
        periodic = gi[2 + axis] != 0
        p = x if axis == 0 else y
        vel = vx if axis == 0 else vy
        a = gx if axis == 0 else gy
        lo = wide.rect[k, 2 * axis]
        hi = wide.rect[k, 2 * axis + 1]
        for what in range(3):
            if what == LOW:
                dt, sign = _edge_time(p - reach, vel - grow, a, lo, side, ncell, periodic,
                                      gravity)
            elif what == HIGH:
                dt, sign = _edge_time(p + reach, vel + grow, a, hi, side, ncell, periodic,
                                      gravity)
            elif periodic:
                dt, sign = _edge_time(p, vel, a, 0, gf[axis], 1, True, gravity)
            else:
                dt, sign = INF, 0
            if dt < first:
                first = dt
                sched = 4 * what + 2 * axis + (0 if sign > 0 else 1)
    x0 = wide.rect[k, 0]
    x1 = wide.rect[k, 1]
    y0 = wide.rect[k, 2]
    y1 = wide.rect[k, 3]
    partial = code >= 0 and code < 8 and not (
        kind_of(E[i, KIND]) == DISK and stamp[E[i, PARTNER]] != E[i, PSTAMP])
    if partial and motion is not None:
        partial = not _moving_listed(x0, x1, y0, y1, gi, wa, wstart, wwall, motion)
    kind = NONE
    partner = -1
    aux = 0
    pst = 0
    if partial:
        best = tcand[i] - t
        what = code >> 2
        direction = code & 3
        # (Grown: low edge moving down, or high edge moving up.)
        grown = (what == LOW and (direction & 1) == 1) or (what == HIGH and
                                                         (direction & 1) == 0)
        if grown:
            if direction < 2:
                u = x0 if what == LOW else x1
                best, kind, partner, aux, pst = _scan_footprint(
                    i, k, t, x, y, vx, vy, gx, gy, r, u, u, y0, y1, S, stamp, gi, gf,
                    head, nxt, wa, wb, wstart, wwall, wsx, wsy, wide, best, kind,
                    partner, aux, pst, gravity, growth, motion, first, shear)
            else:
                v = y0 if what == LOW else y1
                best, kind, partner, aux, pst = _scan_footprint(
                    i, k, t, x, y, vx, vy, gx, gy, r, x0, x1, v, v, S, stamp, gi, gf,
                    head, nxt, wa, wb, wstart, wwall, wsx, wsy, wide, best, kind,
                    partner, aux, pst, gravity, growth, motion, first, shear)
    else:
        dr = 0.0 if growth is None else r * growth.rate
        best, kind, aux = _box_walls(x, y, vx, vy, gx, gy, r * growth_factor(t, growth), dr,
                                     gi, gf, gravity, growth)
        best, kind, partner, aux, pst = _scan_footprint(
            i, k, t, x, y, vx, vy, gx, gy, r, x0, x1, y0, y1, S, stamp, gi, gf, head, nxt,
            wa, wb, wstart, wwall, wsx, wsy, wide, best, kind, partner, aux, pst, gravity,
            growth, motion, first, shear)
    if not partial or kind != NONE:
        tcand[i] = t + best
        E[i, KIND] = kind
        E[i, PARTNER] = partner
        E[i, AUX] = aux
        E[i, PSTAMP] = pst
    E[i, KIND] = pack_kind(kind_of(E[i, KIND]), sched)
    return min(tcand[i], t + first)
