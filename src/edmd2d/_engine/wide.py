"""Wide disks: disks far larger than the grid's cells, listed in every cell near them.

The uniform grid's cell must be as wide as the largest diameter, so that a few large
disks make every small disk's prediction scan many neighbours.  Where the radii differ
enough, the grid's cells are sized for the *narrow* disks instead (at least their
largest diameter), and each disk wider than that is a *wide* disk
(``layout.Wide``): it is in no cell's list of disks; instead it is listed, through one
*node* per cell, in every cell of its **footprint**, the cells that meet the interval
``[x - r - h, x + r + h]`` along each axis, with ``h`` half a cell side (at least the
largest narrow radius, with the grid's rounding margin).

Why that finds every contact: a narrow disk ``i`` touching a wide disk ``j`` has its
centre within ``r_i + r_j <= h + r_j`` of ``j``'s along each axis, so ``i``'s cell is
in ``j``'s footprint, and ``i`` meets ``j`` in its own cell's list of wide disks; two
wide disks that touch have footprints that overlap, so each meets the other in the
wide lists of its footprint's cells.  A pair is *linked* while that holds; a link
forms only at an event of one of the two disks, which then predicts against the
other:

- a narrow disk crossing into a cell scans that cell's wide list (every prediction of
  a narrow disk scans its own cell's wide list, besides its 3x3 cells of disks);
- a wide disk's footprint grows by a column or a row when the edge ``x + r + h`` (or
  ``x - r - h``, ``y +- (r + h)``) crosses a cell boundary: that crossing is an event
  of the wide disk (a cell crossing, ``CROSS``), which lists it in the new cells and
  scans their disks and wide lists.  An edge that leaves a cell shrinks the footprint
  (no scan: what left the footprint cannot be met through it).

So the grid stays exact as for narrow disks, and a wide disk's prediction scans the
cells of its footprint: about ``(2 r / s + 2)^2`` list heads and the narrow disks
around its rim, where the uniform grid would scan nine cells of a diameter each for
every disk.

Periodic axes: a footprint is kept in unwrapped cell coordinates; a node on the cell
``u`` (wrapped to ``u mod n``) records the image shift ``k = floor(u / n)``: the disk's
image over that cell lies at ``x - k L``.  A wide disk's centre wraps when it leaves
the box, which is an event of its own (its footprint and every node's shift move by a
period, and every prediction against it is invalidated).  Walled axes clamp the
footprint to the grid; an edge beyond the last cell schedules nothing.

Under shear (:mod:`.sheared`) the images across the top and bottom slide along x by
the offset ``delta = (k + f) w`` (``k`` the column shift, ``0 <= f <= 1``): a row of
a footprint across the boundary is listed where the disk's image is, ``k`` columns
over, with one more column for ``f`` (:func:`columns`), and at each slide (``k``
steps) those rows are listed afresh and their disks predicted again (:func:`slide`),
as the narrow disks of the two edge rows are.  The image of a disk listed across the
boundary lies ``sy`` offsets along x, at ``sy U`` more velocity.  Two disks in contact
are less than half a width apart (a sheared box is more than four largest diameters
wide), so their collision takes the nearest image, as the narrow disks' does.

Their predictions are in :mod:`.scan` (``_predict_wide``, ``_scan_wide_list``), beside
the narrow disks', whose wall scans they share; this module keeps the lists.

A wide disk's scheduled crossing is coded in the high bits of ``E[i, KIND]`` as
``4 * what + direction`` (direction 0-3: +x, -x, +y, -y; ``what``: 0 the low edge,
1 the high edge, 2 the centre's wrap).  Node ``m`` of wide disk ``k`` for the unwrapped
cell ``(u, v)`` is ``base[k] + (u mod kw) + kw (v mod kh)``: a footprint never spans
more than ``kw x kh`` cells, so the nodes of its cells are distinct.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import kernel, njit
from . import sheared
from .grid import insert, neighbour, remove
from .layout import (
    CELL,
    R,
    Wide,
    X,
    Y,
)

LOW = 0  # the footprint's low edge crossed a cell boundary
HIGH = 1  # its high edge
WRAP = 2  # the centre left the box (periodic axis)


@njit(inline="always")
def footprint(x, reach, side, ncell, periodic):
    """The first and last cell (unwrapped) that ``[x - reach, x + reach]`` meets;
    clamped to the grid on a walled axis."""
    lo = int(math.floor((x - reach) / side))
    hi = int(math.floor((x + reach) / side))
    if not periodic:
        lo = max(lo, 0)
        hi = min(hi, ncell - 1)
    return lo, hi


@njit(inline="always")
def _slot(k, u, v, wide):
    kw = wide.span[k, 0]
    kh = wide.span[k, 1]
    return wide.base[k] + (u % kw) + kw * (v % kh)


@njit(inline="always")
def columns(u0, u1, v, gi, slid):
    """The unwrapped columns of row ``v`` of a footprint whose columns are ``[u0,
    u1]``: those, except across a sheared boundary (``slid >= 0`` the images' column
    shift, :func:`.sheared.column_shift`; -1 without shear), where the disk's image
    below (a row above the box) lies ``slid + f`` cells to the left, ``0 <= f <= 1``,
    and its image above ``slid + f`` to the right: one more column covers ``f``."""
    if slid < 0:
        return u0, u1
    ky = v // gi[1]
    if ky > 0:
        return u0 - slid - 1, u1 - slid
    if ky < 0:
        return u0 + slid, u1 + slid + 1
    return u0, u1


@njit
def _list_rows(k, v0, v1, gi, wide, slid, put):
    """List wide disk ``k`` in (``put``) or take it out of every cell of its footprint's
    rows ``[v0, v1]``."""
    for v in range(v0, v1 + 1):
        c0, c1 = columns(wide.rect[k, 0], wide.rect[k, 1], v, gi, slid)
        for u in range(c0, c1 + 1):
            if put:
                _put(k, u, v, gi, wide)
            else:
                _take(k, u, v, wide)


@njit(inline="always")
def cell(u, v, gi):
    """The cell of the unwrapped cell ``(u, v)`` and the periods ``(kx, ky)`` by which
    it lies outside the grid (0 on a walled axis)."""
    kx = u // gi[0] if gi[2] != 0 else 0
    ky = v // gi[1] if gi[3] != 0 else 0
    return (u - kx * gi[0]) + gi[0] * (v - ky * gi[1]), kx, ky


@njit
def _put(k, u, v, gi, wide):
    """List wide disk ``k`` in the unwrapped cell ``(u, v)``."""
    c, kx, ky = cell(u, v, gi)
    m = _slot(k, u, v, wide)
    wide.nsx[m] = kx
    wide.nsy[m] = ky
    wide.ncell[m] = c
    insert(m, c, wide.bhead, wide.nnext, wide.nprev)


@njit
def _take(k, u, v, wide):
    """Take wide disk ``k`` out of the unwrapped cell ``(u, v)``."""
    m = _slot(k, u, v, wide)
    remove(m, wide.ncell[m], wide.bhead, wide.nnext, wide.nprev)
    wide.ncell[m] = -1


@njit
def _centre_cell(k, gi, wide):
    """A cell near the middle of wide disk ``k``'s footprint (``E[i, CELL]``: a hint
    for the lookahead and the order of the rows, never a list it is in)."""
    u = (wide.rect[k, 0] + wide.rect[k, 1]) // 2
    v = (wide.rect[k, 2] + wide.rect[k, 3]) // 2
    return (u % gi[0]) + gi[0] * (v % gi[1])


@kernel
def fill(S, E, gi, gf, wide, head, nxt, prv, grown, slid):
    """List every wide disk in the cells of its footprint (from its stored position,
    its radius ``grown`` times the stored one; across a sheared boundary shifted by
    the images' column shift ``slid``, -1 without shear) and take it out of the list of
    disks of its cell, where ``grid.build_cells`` put it.  Every prediction must be
    made afresh afterwards."""
    wide.bhead[:] = -1
    wide.ncell[:] = -1
    for k in range(wide.disk.shape[0]):
        i = wide.disk[k]
        remove(i, np.int64(E[i, CELL]), head, nxt, prv)
        reach = S[i, R] * grown + wide.half
        x0, x1 = footprint(S[i, X], reach, gf[2], gi[0], gi[2] != 0)
        y0, y1 = footprint(S[i, Y], reach, gf[3], gi[1], gi[3] != 0)
        wide.rect[k, 0] = x0
        wide.rect[k, 1] = x1
        wide.rect[k, 2] = y0
        wide.rect[k, 3] = y1
        _list_rows(k, y0, y1, gi, wide, slid, True)
        E[i, CELL] = _centre_cell(k, gi, wide)


@kernel
def detach(E, wide, head, nxt, prv):
    """Take every wide disk out of the list of disks of its (hint) cell, after the
    lists were rebuilt from ``E[:, CELL]``."""
    for k in range(wide.disk.shape[0]):
        i = wide.disk[k]
        remove(i, np.int64(E[i, CELL]), head, nxt, prv)


@njit
def cross(i, t, code, S, E, stamp, image, gi, gf, wide, shear):
    """Carry out wide disk ``i``'s crossing ``code`` at ``t`` (the disk already moved
    there): grow or shrink its footprint by a column or row, or wrap its centre into
    the box (under shear, through the top or bottom: its x and x velocity change as
    a narrow disk's, :func:`.sheared.wrap`, and its footprint is listed afresh).
    Returns the code for a partial prediction, or -1 for a full one (a wrap, after
    which every prediction against ``i`` is stale: its stamp is raised)."""
    k = wide.index[i]
    slid = -1 if shear is None else sheared.column_shift(shear, gi[0])
    what = code >> 2
    direction = code & 3
    axis = direction >> 1
    up = (direction & 1) == 0
    x0 = wide.rect[k, 0]
    x1 = wide.rect[k, 1]
    y0 = wide.rect[k, 2]
    y1 = wide.rect[k, 3]
    if what == WRAP:
        n = gi[axis]
        shift = 1 if up else -1
        _list_rows(k, y0, y1, gi, wide, slid, False)
        if axis == 0:
            S[i, X] -= shift * gf[0]
        else:
            S[i, Y] -= shift * gf[1]
        image[i, axis] += shift
        if shear is not None and axis == 1:
            # (x moves by the images' offset: the footprint is found afresh.)
            sheared.wrap(i, t, up, S, image, gi, gf, shear)
            reach = S[i, R] + wide.half
            u0, u1 = footprint(S[i, X], reach, gf[2], gi[0], True)
            v0, v1 = footprint(S[i, Y], reach, gf[3], gi[1], True)
            wide.rect[k, 0] = u0
            wide.rect[k, 1] = u1
            wide.rect[k, 2] = v0
            wide.rect[k, 3] = v1
        else:
            # The same cells, one period lower (or higher) in unwrapped coordinates.
            wide.rect[k, 2 * axis] -= shift * n
            wide.rect[k, 2 * axis + 1] -= shift * n
        _list_rows(k, wide.rect[k, 2], wide.rect[k, 3], gi, wide, slid, True)
        stamp[i] += 1
        E[i, CELL] = _centre_cell(k, gi, wide)
        return -1
    col = 2 * axis + (0 if what == LOW else 1)
    old = wide.rect[k, col]
    new = old + (1 if up else -1)
    grown = (what == HIGH) == up
    if axis == 0:
        # Each row gains or loses the one column by which its range moves.
        n0 = new if what == LOW else x0
        n1 = new if what == HIGH else x1
        for v in range(y0, y1 + 1):
            a0, a1 = columns(x0, x1, v, gi, slid)
            b0, b1 = columns(n0, n1, v, gi, slid)
            for u in range(min(a0, b0), max(a1, b1) + 1):
                before = a0 <= u <= a1
                after = b0 <= u <= b1
                if after and not before:
                    _put(k, u, v, gi, wide)
                elif before and not after:
                    _take(k, u, v, wide)
    else:
        c0, c1 = columns(x0, x1, new if grown else old, gi, slid)
        for u in range(c0, c1 + 1):
            if grown:
                _put(k, u, new, gi, wide)
            else:
                _take(k, u, old, wide)
    wide.rect[k, col] = new
    E[i, CELL] = _centre_cell(k, gi, wide)
    return code


@njit
def slide(n, slid_old, slid_new, gi, wide, rows):
    """At a slide of the sheared boundary (the images' column shift from ``slid_old``
    to ``slid_new``): list afresh the rows across the boundary of every wide disk whose
    footprint crosses it, and add those disks to the ``n`` disks of ``rows`` to be
    predicted afresh (the cells they meet there have changed).  Returns how many."""
    ncy = gi[1]
    for k in range(wide.disk.shape[0]):
        v0 = wide.rect[k, 2]
        v1 = wide.rect[k, 3]
        if v0 >= 0 and v1 < ncy:
            continue
        for v in range(v0, v1 + 1):
            if not 0 <= v < ncy:
                _list_rows(k, v, v, gi, wide, slid_old, False)
                _list_rows(k, v, v, gi, wide, slid_new, True)
        rows[n] = wide.disk[k]
        n += 1
    return n


@njit
def near(d, E, gi, head, nxt, wide, out):
    """The disks near disk ``d`` on the grid, those whose contacts with ``d`` it
    finds: on the uniform grid (``wide`` ``None``) and for a narrow disk, the disks in
    the 3x3 cells around its cell, then the wide disks listed in its own cell; for a
    wide disk, the narrow disks in its footprint's cells and the other wide disks
    listed there, each image once.  Written to ``out`` as rows ``(j, sx, sy)``: ``j``'s
    image at ``x_j + (sx, sy) L`` is the one near ``d``.  Returns how many (``out``
    holds them all: :func:`near_rows`).

    The relation is symmetric (``j`` is near ``d`` if and only if ``d`` is near ``j``,
    through the opposite shift): the 3x3 block is; a narrow and a wide disk are near
    when the narrow one's cell is in the wide one's footprint; two wide disks when
    their footprints share a cell.  So a disk that finds a support near it is found
    near that support again when the support wakes."""
    n = 0
    if wide is None or wide.index[d] < 0:
        c = E[d, CELL]
        ncx = gi[0]
        cy = c // ncx
        cx = c - cy * ncx
        for ox in range(-1, 2):
            nxc, sx = neighbour(cx, ox, ncx, gi[2] != 0)
            if nxc < 0:
                continue
            for oy in range(-1, 2):
                nyc, sy = neighbour(cy, oy, gi[1], gi[3] != 0)
                if nyc < 0:
                    continue
                m = head[nxc + ncx * nyc]
                while m >= 0:
                    if m != d:
                        out[n, 0] = m
                        out[n, 1] = sx
                        out[n, 2] = sy
                        n += 1
                    m = nxt[m]
        if wide is not None:
            m = wide.bhead[c]
            while m >= 0:
                out[n, 0] = wide.disk[wide.nk[m]]
                out[n, 1] = -wide.nsx[m]
                out[n, 2] = -wide.nsy[m]
                n += 1
                m = wide.nnext[m]
        return n
    k = wide.index[d]
    for v in range(wide.rect[k, 2], wide.rect[k, 3] + 1):
        for u in range(wide.rect[k, 0], wide.rect[k, 1] + 1):
            c, kx, ky = cell(u, v, gi)
            j = head[c]
            while j >= 0:
                out[n, 0] = j
                out[n, 1] = kx
                out[n, 2] = ky
                n += 1
                j = nxt[j]
            m = wide.bhead[c]
            while m >= 0:
                kk = wide.nk[m]
                sx = kx - wide.nsx[m]
                sy = ky - wide.nsy[m]
                if kk != k and -1 <= sx <= 1 and -1 <= sy <= 1:
                    j = wide.disk[kk]
                    seen = False
                    for q in range(n):
                        if out[q, 0] == j and out[q, 1] == sx and out[q, 2] == sy:
                            seen = True
                            break
                    if not seen:
                        out[n, 0] = j
                        out[n, 1] = sx
                        out[n, 2] = sy
                        n += 1
                m = wide.nnext[m]
    return n


@njit
def block(d, E, gi, wide):
    """The block of cells ``(u0, u1, v0, v1)`` whose wall segments disk ``d`` meets, and
    whether it is a wide disk's footprint (in unwrapped cells; its cell for a narrow
    disk)."""
    if wide is None or wide.index[d] < 0:
        c = E[d, CELL]
        v = c // gi[0]
        u = c - v * gi[0]
        return u, u, v, v, False
    k = wide.index[d]
    return wide.rect[k, 0], wide.rect[k, 1], wide.rect[k, 2], wide.rect[k, 3], True


def near_rows(n, gi, wide, segments=0) -> int:
    """Rows enough for :func:`near` with ``n`` disks on the grid ``gi``: each disk
    once per image of its cell in a 3x3 block (three on an axis of one cell, two on a
    periodic axis of two), and each wide disk in up to nine images; at least nine
    images of each of ``segments`` wall segments (for a list of those met)."""
    images = 1
    for axis in range(2):
        cells = int(gi[axis])
        images *= 3 if cells == 1 else (2 if cells == 2 else 1)
    return max(n * images + (0 if wide is None else 9 * len(wide.disk)), 9 * segments)


@kernel
def first_overlap(pos, rad, gi, gf, head, nxt, wide, tol, slid, offset):
    """The first pair ``(i, j, distance)`` of a wide disk and a disk (narrow or wide)
    listed in its footprint's cells that overlap by more than ``tol`` of their contact
    distance; ``(-1, -1, 0.0)`` for none.  (Narrow pairs are checked on the cells.)
    Under shear ``slid`` is the images' column shift and ``offset`` their offset (-1 and
    0 without)."""
    for k in range(wide.disk.shape[0]):
        i = wide.disk[k]
        for v in range(wide.rect[k, 2], wide.rect[k, 3] + 1):
            c0, c1 = columns(wide.rect[k, 0], wide.rect[k, 1], v, gi, slid)
            for u in range(c0, c1 + 1):
                c, kx, ky = cell(u, v, gi)
                j = head[c]
                while j >= 0:
                    dx = pos[i, 0] - (pos[j, 0] + kx * gf[0] + ky * offset)
                    dy = pos[i, 1] - (pos[j, 1] + ky * gf[1])
                    d = math.sqrt(dx * dx + dy * dy)
                    if d < (rad[i] + rad[j]) * (1.0 - tol):
                        return i, j, d
                    j = nxt[j]
                m = wide.bhead[c]
                while m >= 0:
                    kk = wide.nk[m]
                    if kk != k:
                        j = wide.disk[kk]
                        dx = pos[i, 0] - (pos[j, 0] + (kx - wide.nsx[m]) * gf[0]
                                          + (ky - wide.nsy[m]) * offset)
                        dy = pos[i, 1] - (pos[j, 1] + (ky - wide.nsy[m]) * gf[1])
                        d = math.sqrt(dx * dx + dy * dy)
                        if d < (rad[i] + rad[j]) * (1.0 - tol):
                            return i, j, d
                    m = wide.nnext[m]
    return -1, -1, 0.0


# ------------------------------------------------------------------ choice and set-up
# Below this ratio of the largest to the smallest diameter the uniform grid is kept
# without asking the cost model (equal disks and the usual binary mixtures stay bit for
# bit what they were); above it the cost model decides.
MIN_RATIO = 2.5


def _work(d, area, s, narrow_d, margin):
    """Estimated work per unit time of the predictions on a grid of cells of side
    ``s`` for disks of diameters ``d``, those wider than ``narrow_d`` wide (all narrow
    for the uniform grid, ``narrow_d = inf``): list heads and pair tests, counted per
    prediction and weighted by how often each disk predicts (after each of its
    collisions, at a rate growing with ``r_i + r_mean``, and at its crossings, at a
    rate ``1 / s``, with a partial scan).  A guide for the choice, not a measurement:
    on the gases of ``benchmarks/sizes.py`` it ranks the grids as they measure."""
    n = len(d)
    narrow = d <= narrow_d
    dens = float(narrow.sum()) / area  # narrow disks per unit area
    reach = 0.5 * d[~narrow] + 0.5 * narrow_d + margin * (s + narrow_d)
    side = 2.0 * reach / s + 1.0  # cells along a footprint's side
    nodes = float((side * side).sum()) * s * s / area  # wide nodes per cell
    per_cell = 1.0 + dens * s * s + nodes  # a list head, its disks, its wide nodes
    collide = (0.5 * d + 0.5 * float(d.mean())) * (n / area) * 2.0  # (vs crossings)
    cross = 1.6 / s
    work = (collide[narrow] * (9.0 * per_cell)).sum() + narrow.sum() * cross * (
        3.0 * per_cell)
    if (~narrow).any():
        work += (collide[~narrow] * side * side * per_cell).sum() + (
            2.0 * cross * 0.5 * side * per_cell).sum()
    return float(work)


def choose(rad, width, height, periodic, margin, force=False, extra=0.0, sheared=False):
    """The narrow diameter of the grid (cells sized for disks up to it, wider disks
    wide), or ``None`` for the uniform grid: from an estimate of the work of
    predictions (:func:`_work`) over candidate splits, the uniform grid unless a split
    is estimated at least 30 % cheaper (``force``: the cheapest split whatever).  On a
    periodic axis a wide disk's footprint and two cells must fit in the period (so
    that a footprint holds one image of each cell, and the images of two footprints
    over one cell are at most a period apart), its margin widened by ``extra`` (the
    gap of disks at rest; under shear, ``sheared``, with one more column, where the
    images slide).  ``None`` also where no split fits."""
    d = 2.0 * np.asarray(rad, float)
    dmax = float(d.max())
    if not force and dmax < MIN_RATIO * float(d.min()):
        return None
    area = width * height
    dilute = math.sqrt(area / (2.0 * len(d)))  # (the grid's widening of dilute cells)
    uniform = _work(d, area, max(dmax * (1.0 + margin), dilute), math.inf, margin)
    best, split = math.inf, None
    sizes = np.unique(d)
    if len(sizes) > 64:
        sizes = np.unique(np.quantile(d, np.linspace(0.0, 1.0, 65)))
    limit = min([length for length, p in zip((width, height), periodic) if p],
                default=math.inf)
    for dn in sizes[sizes < dmax]:
        s = max(float(dn) * (1.0 + margin), dilute)
        half = 0.5 * float(dn) + margin * (s + float(dn)) + extra
        if 2.0 * (0.5 * dmax + half) + (3.0 if sheared else 2.0) * s >= limit:
            continue
        work = _work(d, area, s, float(dn), margin)
        if work < best:
            best, split = work, float(dn)
    if split is None or (not force and best > 0.7 * uniform):
        return None
    return split


def allocate(rad, narrow, gi, gf, half, sheared=False):
    """A ``layout.Wide`` for the disks wider than ``narrow`` (their footprints to be
    filled by :func:`fill`; under shear, ``sheared``, a row across the boundary has
    one more column)."""
    index = np.full(len(rad), -1, np.int64)
    disk = np.flatnonzero(2.0 * np.asarray(rad) > narrow).astype(np.int64)
    index[disk] = np.arange(len(disk))
    reach = np.asarray(rad)[disk] + half
    span = np.empty((len(disk), 2), np.int64)
    span[:, 0] = np.floor(2.0 * reach / gf[2]).astype(np.int64) + (3 if sheared else 2)
    span[:, 1] = np.floor(2.0 * reach / gf[3]).astype(np.int64) + 2
    size = span[:, 0] * span[:, 1]
    base = np.zeros(len(disk), np.int64)
    base[1:] = np.cumsum(size)[:-1]
    nodes = int(size.sum())
    nk = np.repeat(np.arange(len(disk)), size).astype(np.int32)
    return Wide(index, disk, np.zeros((len(disk), 4), np.int64), base, span, float(half),
                np.full(int(gi[0] * gi[1]), -1, np.int32), np.full(nodes, -1, np.int32),
                np.full(nodes, -1, np.int32), nk, np.zeros(nodes, np.int32),
                np.zeros(nodes, np.int32), np.full(nodes, -1, np.int32))
