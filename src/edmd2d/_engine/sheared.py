"""Lees-Edwards (sliding-brick) boundaries: a box periodic on both axes whose images
above and below slide along x.

The images one box above move at ``U = rate * height`` relative to the box and are
shifted along x by the offset ``delta(t)``; the images below at ``-U``, by
``-delta(t)``.  A disk seen through the boundary (image shift ``sy = +-1``) is therefore
at ``x_j + sy delta(t)`` (up to whole widths: which image, below) with the velocity
``v_j + (sy U, 0)``: its contact with a disk of the box is again a straight-line
problem (:func:`.predict.pair_time`), and its collision an ordinary one between the
disk and that image.  A disk that leaves through the top re-enters at the bottom with
``x - delta(t)`` and ``v_x - U`` (through the bottom: ``+ delta``, ``+ U``), so that
its velocity relative to the flow ``u_x = v_x - rate (y - height / 2)``, the
*peculiar* velocity, is continuous.

The grid stays exact as the images slide.  A disk in the top or bottom row of cells
meets disks of the other edge row through the boundary; with the images shifted by
``delta = (k + f) w`` (``w`` the cell width, ``0 <= f <= 1``) those that can touch it
lie in four columns of that row, fixed while ``k`` is.  ``k`` steps by one each time
the offset grows (or shrinks) by a cell width: at that instant, a *slide*, every disk
of the two edge rows is predicted afresh (:func:`slide`), the only event the sliding
adds.  The offset is kept as ``delta_base + U (t - t_base)`` from the last slide, so
it is computed from a time difference shorter than ``w / |U|``, to full precision at
any time of a long run; and each slide's time is computed afresh from a fixed origin,
``t_origin + (m w - D_origin) / U`` for the ``m``-th cell edge of the unreduced offset
``D``, so that the rounding of the clock does not pile up over millions of slides.

Which image along x: a scanned column ``c`` (taken modulo ``ncx``) stands for its own
image, shifted by whole widths as ``c`` leaves ``0 .. ncx - 1``, plus ``sy delta``:
within the four columns there is one image of each disk, and that is the one that
can reach the disk's neighbourhood before the next slide.  (The nearest image at the
time of the prediction is not always that one: the two disks may each move a cell and
the images slide a cell before they touch, three cells in all, more than half of a box
four or five cells wide.)  At contact the x separation is below a cell width, so the
collision takes the nearest image (:func:`separation`), unique in a box at least four
cells wide.

The bundle (``layout.Shear``) holds ``rate``, ``speed = U``, ``half = height / 2``;
``clock = (t_base, t_next, delta_base, t_origin, D_origin)``, the time of the last
slide, of the next, the offset at the last, and the time and unreduced offset where
the shear started; ``slides[0] = m``, the cell edges of ``D`` passed (from 0: ``m =
floor(D / w)`` while ``D`` grows, one less at an edge while it shrinks), whose
remainder ``m mod ncx`` is ``k``; room for the disks of a slide (``rows``) and
their predicted times (``times``); ``idle``, the slides in a row with no event of a
disk ahead (after one pass of the images over the width, nothing can happen any
more: every disk is at rest); and ``flights``, the exact time integrals
over every free flight of ``sum m u_x^2``, ``sum m u_y^2`` and ``sum m u_x u_y`` (the
kinetic part of the pressure tensor; ``u`` changes in flight, ``du_x/dt = -rate
v_y``), added as each disk is moved (:func:`flight`).
"""

from __future__ import annotations

import math

from .._jit import njit
from .layout import VX, VY, R, T, X, Y, pack_shift
from .predict import pair_time

# clock entries
T_BASE = 0
T_NEXT = 1
DELTA_BASE = 2
T_ORIGIN = 3
D_ORIGIN = 4
# flights entries
F_XX = 0
F_YY = 1
F_XY = 2


@njit
def offset(t, shear):
    """The offset ``delta(t)`` of the images above (between 0 and the box width, up to
    rounding at a slide)."""
    return shear.clock[DELTA_BASE] + shear.speed * (t - shear.clock[T_BASE])


@njit
def column_shift(shear, ncx):
    """``k = m mod ncx``: whole cell widths of the offset since it was last 0."""
    k = shear.slides[0] % ncx
    return k + ncx if k < 0 else k


@njit
def nearest_x(dx, width):
    """``dx`` moved by whole box widths to the nearest image (``|dx| <= width / 2``)."""
    return dx - width * math.floor(dx / width + 0.5)


@njit
def scan_across(i, t, x, y, vx, vy, r, cx, cy, oy0, oy1, S, stamp, gi, gf, head, nxt,
                best, partner, aux, pst, shear):
    """Earliest contact of disk ``i`` (at ``x, y``, velocity ``vx, vy`` at ``t``) with
    the disks seen through the sliding boundary in the rows at offsets ``[oy0, oy1]``
    from ``cy``, if before ``best``: the four columns whose images can reach its
    3x3 neighbourhood while ``k`` holds (module notes)."""
    ncx = gi[0]
    ncy = gi[1]
    k = column_shift(shear, ncx)
    d = offset(t, shear)
    for oy in range(oy0, oy1 + 1):
        ny = cy + oy
        if ny < 0:
            sy = -1
            ny += ncy
        elif ny >= ncy:
            sy = 1
            ny -= ncy
        else:
            continue
        # Images above sit k + f cells to the right: columns cx - k - 2 .. cx - k + 1;
        # below, k + f to the left: cx + k - 1 .. cx + k + 2.  Each column's image: the
        # whole widths by which it lies outside 0 .. ncx - 1, plus sy delta.
        first = cx - k - 2 if sy > 0 else cx + k - 1
        for q in range(4):
            col = (first + q) % ncx
            if col < 0:
                col += ncx
            shift = ((first + q - col) // ncx) * gf[0] + sy * d
            j = head[col + ncx * ny]
            while j >= 0:
                if j != i:
                    dt = t - S[j, T]
                    dx = x - (S[j, X] + dt * S[j, VX] + shift)
                    dy = y - (S[j, Y] + dt * S[j, VY] + sy * gf[1])
                    dtc = pair_time(dx, dy, vx - (S[j, VX] + sy * shear.speed),
                                    vy - S[j, VY], r + S[j, R])
                    if dtc < best:
                        best = dtc
                        partner = j
                        aux = pack_shift(0, sy)
                        pst = stamp[j]
                j = nxt[j]
    return best, partner, aux, pst


@njit
def separation(i, j, sy, t, S, gf, shear):
    """The separation of disk ``i`` from the image of ``j`` through the boundary
    (``sy = +-1``) and their relative velocity, both disks at time ``t``:
    ``(dx, dy, dvx, dvy)``."""
    dx = nearest_x(S[i, X] - (S[j, X] + sy * offset(t, shear)), gf[0])
    dy = S[i, Y] - (S[j, Y] + sy * gf[1])
    return (dx, dy, S[i, VX] - (S[j, VX] + sy * shear.speed), S[i, VY] - S[j, VY])


@njit
def wrap(i, t, up, S, image, gi, gf, shear):
    """Disk ``i`` (at time ``t``, its y already moved by a box height) has left through
    the top (``up``) or the bottom: shift its x by ``-+delta(t)`` and its x velocity by
    ``-+U``, bring x back into the box, and count the images so that ``x + image_x
    width + image_y D(t)``, with ``D`` the offset not reduced by box widths
    (:func:`unreduced_offset`), continues the disk's path.  Returns its new column."""
    ncx = gi[0]
    width = gf[0]
    sign = 1 if up else -1
    x = S[i, X] - sign * offset(t, shear)
    p = 0  # box widths added to bring x back
    while x < 0.0:
        x += width
        p += 1
    while x >= width:
        x -= width
        p -= 1
    S[i, X] = x
    S[i, VX] -= sign * shear.speed
    # D = delta + width * floor(m / ncx): the whole widths of D not in delta
    q = shear.slides[0] // ncx
    image[i, 0] -= p + sign * q
    c = int(math.floor(x / gf[2]))
    return min(max(c, 0), ncx - 1)


@njit
def next_slide(m, up, w, clock, speed):
    """The time at which the unreduced offset reaches the cell edge that ends cell
    ``m`` in the direction of flow (``(m + 1) w`` growing, ``m w`` shrinking),
    from the fixed origin."""
    edge = (m + 1) * w if up else m * w
    return clock[T_ORIGIN] + (edge - clock[D_ORIGIN]) / speed


@njit
def slide(shear, gi, gf, head, nxt):
    """The slide due at ``clock[T_NEXT]``: step ``k``, restart the offset's clock
    there, and list every disk of the two edge rows in ``rows`` for a fresh
    prediction.  Returns how many."""
    ncx = gi[0]
    ncy = gi[1]
    w = gf[2]
    up = shear.speed > 0.0
    shear.slides[0] += 1 if up else -1
    t = shear.clock[T_NEXT]
    k = column_shift(shear, ncx)
    shear.clock[T_BASE] = t
    shear.clock[DELTA_BASE] = k * w if up else (k + 1) * w
    shear.clock[T_NEXT] = next_slide(shear.slides[0], up, w, shear.clock, shear.speed)
    n = 0
    for row in (0, ncy - 1):
        for col in range(ncx):
            j = head[col + ncx * row]
            while j >= 0:
                shear.rows[n] = j
                n += 1
                j = nxt[j]
    return n


@njit
def _integrals(i, t, S, invm, rate, half):
    """Disk ``i``'s free flight from its local time to ``t`` in the integrals of the
    kinetic stress (module notes): with ``u_x(s) = u_x0 - rate v_y s``,
    ``int u_x^2 = u_x0^2 tau - rate v_y u_x0 tau^2 + rate^2 v_y^2 tau^3 / 3``,
    ``int u_y^2 = v_y^2 tau`` and ``int u_x u_y = v_y (u_x0 tau - rate v_y tau^2 / 2)``,
    times the mass: ``(xx, yy, xy)``."""
    tau = t - S[i, T]
    m = 1.0 / invm[i]
    vy = S[i, VY]
    ux = S[i, VX] - rate * (S[i, Y] - half)
    gv = rate * vy * tau
    return (m * tau * (ux * ux - gv * ux + gv * gv / 3.0), m * tau * vy * vy,
            m * tau * vy * (ux - 0.5 * gv))


@njit
def flight(i, t, S, invm, shear):
    """Add disk ``i``'s free flight from its local time to ``t`` to the integrals of
    the kinetic stress, as the engine moves it."""
    if t == S[i, T]:
        return
    xx, yy, xy = _integrals(i, t, S, invm, shear.rate, shear.half)
    shear.flights[F_XX] += xx
    shear.flights[F_YY] += yy
    shear.flights[F_XY] += xy


@njit
def pending(t, S, invm, rate, half):
    """The flights of every disk from its local time to ``t`` in the integrals of
    the kinetic stress, summed: ``(xx, yy, xy)`` (what the engine adds as it next
    moves each disk; for readouts between events)."""
    xx = yy = xy = 0.0
    for i in range(S.shape[0]):
        a, b, c = _integrals(i, t, S, invm, rate, half)
        xx += a
        yy += b
        xy += c
    return xx, yy, xy
