"""Uniform grid: cell index, per-cell doubly linked lists, walls bucketed by cell.

Geometry is passed as two small arrays:

``gi = [ncx, ncy, periodic_x, periodic_y]`` (int64) and
``gf = [width, height, cell_width, cell_height]`` (float64).

Cells are numbered ``cx + ncx * cy``.  Every cell is at least one largest diameter
wide, so two disks in contact sit in the same or in neighbouring cells; neighbours
across a periodic edge are reached with an image shift of one box length.  Because the
shift is taken from the cell offset (not from a minimum-image search), boxes with only
1 or 2 cells on a periodic axis are handled exactly: each (cell, shift) pair visited is
a distinct image.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import kernel, njit


@njit
def neighbour(c, offset, ncell, periodic):
    """Cell index ``c + offset`` on one axis and the image shift (-1, 0, +1), or -1."""
    n = c + offset
    if n < 0:
        if periodic:
            return n + ncell, -1
        return -1, 0
    if n >= ncell:
        if periodic:
            return n - ncell, 1
        return -1, 0
    return n, 0


@kernel
def insert(i, c, head, nxt, prv):
    """Put disk ``i`` at the front of cell ``c``'s list."""
    h = head[c]
    nxt[i] = h
    prv[i] = -1
    if h >= 0:
        prv[h] = i
    head[c] = i


@kernel
def remove(i, c, head, nxt, prv):
    """Take disk ``i`` out of cell ``c``'s list."""
    p = prv[i]
    n = nxt[i]
    if p >= 0:
        nxt[p] = n
    else:
        head[c] = n
    if n >= 0:
        prv[n] = p


def build_cells(pos, gi, gf, cell, head, nxt, prv):
    """Assign every disk to the cell of its centre (``floor(x / cell side)``, clipped to
    the grid against rounding at the far edge) and build the lists.  Plain numpy: one
    compiled kernel less to build on first use."""
    cx = np.clip(np.floor(pos[:, 0] / gf[2]), 0, gi[0] - 1).astype(np.int64)
    cy = np.clip(np.floor(pos[:, 1] / gf[3]), 0, gi[1] - 1).astype(np.int64)
    cell[:] = cx + gi[0] * cy
    build_lists(cell, head, nxt, prv)


@njit(inline="always")
def _segment_hits_rect(ax, ay, bx, by, x0, y0, x1, y1):
    """Does the segment a->b meet the closed rectangle [x0,x1]x[y0,y1]? (slab clipping)"""
    t0 = 0.0
    t1 = 1.0
    d = (bx - ax, by - ay)
    lo = (x0 - ax, y0 - ay)
    hi = (x1 - ax, y1 - ay)
    for k in range(2):
        if d[k] == 0.0:
            if lo[k] > 0.0 or hi[k] < 0.0:
                return False
        else:
            ta = lo[k] / d[k]
            tb = hi[k] / d[k]
            if ta > tb:
                ta, tb = tb, ta
            if ta > t0:
                t0 = ta
            if tb < t1:
                t1 = tb
            if t0 > t1:
                return False
    return True


@njit(inline="always")
def _swept_hits_rect(ax, ay, bx, by, px, py, x0, y0, x1, y1):
    """Does the parallelogram swept by the segment a->b shifted by up to ``p`` meet
    the closed rectangle ``[x0,x1]x[y0,y1]``?  (Separating axes: x, y and the normals of
    the two edge directions.)"""
    for k in range(2):
        ex = (bx - ax) if k == 0 else px
        ey = (by - ay) if k == 0 else py
        nx = -ey
        ny = ex
        if nx == 0.0 and ny == 0.0:
            continue
        lo = math.inf
        hi = -math.inf
        for c in range(4):
            qx = (ax if c < 2 else bx) + (px if c % 2 == 1 else 0.0)
            qy = (ay if c < 2 else by) + (py if c % 2 == 1 else 0.0)
            v = qx * nx + qy * ny
            lo = min(lo, v)
            hi = max(hi, v)
        rlo = math.inf
        rhi = -math.inf
        for c in range(4):
            v = (x0 if c < 2 else x1) * nx + (y0 if c % 2 == 0 else y1) * ny
            rlo = min(rlo, v)
            rhi = max(rhi, v)
        if hi < rlo or rhi < lo:
            return False
    # (The axes x and y: the caller's range of cells is the swept box's.)
    return True


@njit
def _bucket_walls(wa, wb, sweep, gi, gf, reach, start, wall, sx, sy, fill):
    ncx = gi[0]
    ncy = gi[1]
    width = gf[0]
    height = gf[1]
    lx = gf[2]
    ly = gf[3]
    rx = 1 if gi[2] else 0
    ry = 1 if gi[3] else 0
    count = 0
    for w in range(wa.shape[0]):
        px = sweep[w, 0]
        py = sweep[w, 1]
        swept = px != 0.0 or py != 0.0
        for ix in range(-rx, rx + 1):
            for iy in range(-ry, ry + 1):
                ax = wa[w, 0] + ix * width
                ay = wa[w, 1] + iy * height
                bx = wb[w, 0] + ix * width
                by = wb[w, 1] + iy * height
                cx0 = int(math.floor((min(ax, bx) + min(px, 0.0) - reach) / lx))
                cx1 = int(math.floor((max(ax, bx) + max(px, 0.0) + reach) / lx))
                cy0 = int(math.floor((min(ay, by) + min(py, 0.0) - reach) / ly))
                cy1 = int(math.floor((max(ay, by) + max(py, 0.0) + reach) / ly))
                cx0 = max(cx0, 0)
                cy0 = max(cy0, 0)
                cx1 = min(cx1, ncx - 1)
                cy1 = min(cy1, ncy - 1)
                for cy in range(cy0, cy1 + 1):
                    for cx in range(cx0, cx1 + 1):
                        r0x = cx * lx - reach
                        r0y = cy * ly - reach
                        r1x = (cx + 1) * lx + reach
                        r1y = (cy + 1) * ly + reach
                        if swept:
                            hit = _swept_hits_rect(ax, ay, bx, by, px, py, r0x, r0y, r1x,
                                                   r1y)
                        else:
                            hit = _segment_hits_rect(ax, ay, bx, by, r0x, r0y, r1x, r1y)
                        if hit:
                            c = cx + ncx * cy
                            if fill:
                                k = start[c + 1]
                                wall[k] = w
                                sx[k] = ix
                                sy[k] = iy
                                start[c + 1] = k + 1
                            else:
                                start[c + 1] += 1
                            count += 1
    return count


def bucket_walls(wa, wb, gi, gf, reach, sweep=None):
    """CSR lists of the walls (and their periodic images) near each cell.

    A disk whose centre is in cell ``c`` can only touch a wall entry listed in
    ``wall[start[c]:start[c+1]]``; entry ``k`` is wall ``wall[k]`` shifted by
    ``(sx[k] * width, sy[k] * height)``.  ``reach`` is the largest radius (plus a
    rounding margin): a wall is listed for every cell whose rectangle grown by ``reach``
    it meets.  A segment that moves is given from one end of its path, ``sweep`` (shape
    (S, 2), zero for a fixed one) the shift to the other: it is listed wherever the
    parallelogram it sweeps comes that near.  Without walls ``start`` is ``[0]``, not
    one entry per cell: callers must not look up cells then.
    """
    empty = np.zeros(0, dtype=np.int64)
    if wa.shape[0] == 0:
        # Nothing to bucket (and nothing to compile).  No per-cell array either (6 bytes
        # a disk at packing 0.5): every reader skips the lookup when there are no walls.
        return np.zeros(1, dtype=np.int32), empty, empty, empty
    if sweep is None:
        sweep = np.zeros((wa.shape[0], 2))
    ncell = int(gi[0] * gi[1])
    start = np.zeros(ncell + 1, dtype=np.int32)  # per cell: keep it small
    _bucket_walls(wa, wb, sweep, gi, gf, reach, start, empty, empty, empty, False)
    np.cumsum(start, out=start)
    total = int(start[-1])
    wall = np.empty(total, dtype=np.int64)
    sx = np.empty(total, dtype=np.int64)
    sy = np.empty(total, dtype=np.int64)
    cursor = start.copy()
    cursor[1:] = start[:-1]
    _bucket_walls(wa, wb, sweep, gi, gf, reach, cursor, wall, sx, sy, True)
    return start, wall, sx, sy


def morton_rank(ncx: int, ncy: int) -> np.ndarray:
    """Rank of every cell along a Z-order (Morton) curve over the grid.

    Cells close in space get close ranks in both directions, so ordering disks by the
    rank of their cell keeps a disk's 3x3 neighbourhood in few memory regions.
    """
    cx = np.arange(ncx, dtype=np.uint64)
    cy = np.arange(ncy, dtype=np.uint64)
    key = _spread_bits(cx)[None, :] | (_spread_bits(cy)[:, None] << np.uint64(1))
    order = np.argsort(key.ravel(), kind="stable")  # cell index cx + ncx * cy
    rank = np.empty(ncx * ncy, np.int32)
    rank[order] = np.arange(ncx * ncy)
    return rank


def _spread_bits(v: np.ndarray) -> np.ndarray:
    """Insert a zero bit between the bits of each value (for 32-bit inputs)."""
    v = v & np.uint64(0xFFFFFFFF)
    for shift, mask in ((16, 0x0000FFFF0000FFFF), (8, 0x00FF00FF00FF00FF),
                        (4, 0x0F0F0F0F0F0F0F0F), (2, 0x3333333333333333),
                        (1, 0x5555555555555555)):
        v = (v | (v << np.uint64(shift))) & np.uint64(mask)
    return v


@njit
def order_by_cell(cell, rank, nrank):
    """Permutation (new position -> old disk) sorting disks by ``rank[cell]``; a stable
    counting sort, O(N + cells)."""
    n = cell.shape[0]
    count = np.zeros(nrank + 1, np.int64)
    for i in range(n):
        count[rank[cell[i]] + 1] += 1
    for k in range(nrank):
        count[k + 1] += count[k]
    perm = np.empty(n, np.int64)
    for i in range(n):
        r = rank[cell[i]]
        perm[count[r]] = i
        count[r] += 1
    return perm


@njit
def build_lists(cell, head, nxt, prv):
    """Rebuild the per-cell lists from ``cell`` (each list in ascending disk order)."""
    head[:] = -1
    for i in range(cell.shape[0] - 1, -1, -1):
        insert(i, np.int64(cell[i]), head, nxt, prv)
