"""Start-up checks on the grid: overlapping disks, disks overlapping wall segments."""

from __future__ import annotations

import math

from .._jit import njit
from .grid import neighbour


@njit
def first_disk_overlap(pos, rad, gi, gf, cell, head, nxt, tol, across):
    """The first pair ``(i, j)`` whose centre distance is below ``(r_i + r_j)(1 - tol)``.

    Returns ``(-1, -1, 0.0)`` if there is none, else ``(i, j, distance)``.  Without
    ``across`` the pairs through the boundary along y are left out (a sheared box,
    whose images there slide: checked by the caller).
    """
    ncx = gi[0]
    ncy = gi[1]
    for i in range(pos.shape[0]):
        c = cell[i]
        cx = c % ncx
        cy = c // ncx
        for ox in range(-1, 2):
            nxc, sx = neighbour(cx, ox, ncx, gi[2] != 0)
            if nxc < 0:
                continue
            for oy in range(-1, 2):
                nyc, sy = neighbour(cy, oy, ncy, gi[3] != 0)
                if nyc < 0 or (sy != 0 and not across):
                    continue
                j = head[nxc + ncx * nyc]
                while j >= 0:
                    if j > i or (j == i and (sx != 0 or sy != 0)):
                        dx = pos[i, 0] - pos[j, 0] - sx * gf[0]
                        dy = pos[i, 1] - pos[j, 1] - sy * gf[1]
                        d = (rad[i] + rad[j]) * (1.0 - tol)
                        if dx * dx + dy * dy < d * d:
                            return i, j, math.sqrt(dx * dx + dy * dy)
                    j = nxt[j]
    return -1, -1, 0.0


@njit
def first_wall_overlap(pos, rad, gf, cell, wa, wb, wstart, wwall, wsx, wsy, tol):
    """The first disk ``i`` closer than ``r_i (1 - tol)`` to a wall segment ``w``.

    Returns ``(i, w, distance)`` or ``(-1, -1, 0.0)``.
    """
    for i in range(pos.shape[0]):
        c = cell[i]
        for k in range(wstart[c], wstart[c + 1]):
            w = wwall[k]
            ax = wa[w, 0] + wsx[k] * gf[0]
            ay = wa[w, 1] + wsy[k] * gf[1]
            ux = wb[w, 0] - wa[w, 0]
            uy = wb[w, 1] - wa[w, 1]
            px = pos[i, 0] - ax
            py = pos[i, 1] - ay
            s = (px * ux + py * uy) / (ux * ux + uy * uy)
            s = min(max(s, 0.0), 1.0)
            dx = px - s * ux
            dy = py - s * uy
            d = rad[i] * (1.0 - tol)
            if dx * dx + dy * dy < d * d:
                return i, w, math.sqrt(dx * dx + dy * dy)
    return -1, -1, 0.0
