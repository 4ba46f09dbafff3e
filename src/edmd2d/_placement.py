"""Compiled kernel of :func:`edmd2d.random_packing`: random sequential addition on a
cell grid.

The kernel takes flat arrays only and reports how far it got with a status code; the
random numbers come from the caller (a NumPy ``Generator``), so that a seed gives the
same placement with or without compilation.
"""

from __future__ import annotations

import math

import numpy as np

from ._engine.grid import neighbour
from ._jit import njit

__all__ = ["DONE", "NEED_RANDOM", "STALLED", "place_disks"]

DONE = 0         # every disk placed
NEED_RANDOM = 1  # the random numbers ran out: call again with fresh ones
STALLED = 2      # a disk found no room in max_attempts consecutive attempts


@njit
def place_disks(pos, rad, lo, span, start, fails, u, width, height, px, py, contact_scale,
                head, nxt, ncx, ncy, max_attempts):
    """Place disks ``start, start + 1, ...`` in order, each at the first candidate that
    overlaps no placed disk.

    Candidate ``m`` for disk ``k`` is ``lo[k] + u[m] * span[k]`` (per axis), so that on
    walled axes the centre stays inside its margin.  Two disks overlap when their
    centres (minimum image on periodic axes) are closer than ``contact_scale`` times
    the sum of their radii.  Placed disks are kept in a cell grid (``head`` per cell,
    ``nxt`` per disk, -1 ending a list) of cells at least one largest diameter wide,
    so that only the 3 x 3 cells around a candidate can hold a disk it overlaps.

    Returns ``(next disk, random numbers used, consecutive failures, status)``.
    """
    n = len(rad)
    k = start
    m = 0
    cw = width / ncx
    ch = height / ncy
    while k < n:
        if m == len(u):
            return k, m, fails, NEED_RANDOM
        x = lo[k, 0] + u[m, 0] * span[k, 0]
        y = lo[k, 1] + u[m, 1] * span[k, 1]
        m += 1
        if _fits(pos, rad, k, x, y, width, height, px, py, contact_scale, head, nxt,
                 ncx, ncy, cw, ch):
            pos[k, 0] = x
            pos[k, 1] = y
            c = _cell(x, cw, ncx) + ncx * _cell(y, ch, ncy)
            nxt[k] = head[c]
            head[c] = k
            k += 1
            fails = 0
        else:
            fails += 1
            if fails >= max_attempts:
                return k, m, fails, STALLED
    return k, m, fails, DONE


@njit
def _cell(x, size, count):
    c = int(math.floor(x / size))
    return min(max(c, 0), count - 1)


@njit
def _fits(pos, rad, k, x, y, width, height, px, py, contact_scale, head, nxt, ncx, ncy,
          cw, ch):
    cx = _cell(x, cw, ncx)
    cy = _cell(y, ch, ncy)
    # With fewer than 3 cells on a periodic axis the 3 neighbours would repeat cells:
    # every cell is searched once instead.
    if px and ncx < 3:
        x0, x1 = 0, ncx - 1
    else:
        x0, x1 = cx - 1, cx + 1
    if py and ncy < 3:
        y0, y1 = 0, ncy - 1
    else:
        y0, y1 = cy - 1, cy + 1
    for gy in range(y0, y1 + 1):
        ry, _ = neighbour(0, gy, ncy, py)  # (the grid's own wrap: -1 past a wall)
        if ry < 0:
            continue
        for gx in range(x0, x1 + 1):
            rx, _ = neighbour(0, gx, ncx, px)
            if rx < 0:
                continue
            j = head[rx + ncx * ry]
            while j >= 0:
                dx = pos[j, 0] - x
                dy = pos[j, 1] - y
                if px:
                    dx -= width * np.rint(dx / width)
                if py:
                    dy -= height * np.rint(dy / height)
                reach = (rad[j] + rad[k]) * contact_scale
                if dx * dx + dy * dy < reach * reach:
                    return False
                j = nxt[j]
    return True
