"""Collision responses: what a contact does to the velocities.

A contact exchanges an impulse ``J`` along the unit normal ``n`` at the contact point.
With ``vn`` the normal relative velocity (< 0 when approaching), ``w = 1/m`` the
inverse masses (0 for an immovable disk) and ``e`` the coefficient of restitution,
``J = -(1 + e) vn / (w_i + w_j)`` reverses ``vn`` and scales it by ``e``: ``e = 1`` is
elastic (energy conserved), ``e < 1`` loses ``(1 - e^2) vn^2 / (2 (w_i + w_j))`` of
kinetic energy.  A wall is a partner with ``w = 0``.

The physics comes in families (the named tuples of :mod:`.layout`), each an argument
that is ``None`` when unused, so that the elastic default compiles to the plain
elastic formulas (the arrays are an ``edmd2d.models.Model``'s own, rows in the engine's
internal order):

- ``contact`` (``layout.Contact``): ``table[a, b]``, the coefficient for a pair of
  species ``a, b``; ``species[i]`` per disk; ``wall``, the coefficient against box
  walls and wall segments; the TC model (Luding and McNamara 1998): a collision is
  elastic when a movable disk involved collided less than ``tc`` ago, ``t_last[i]``
  the time of disk ``i``'s last collision (-inf before the first; never set for
  immovable disks, which act as walls); ``streak[i]``, how many collisions in a row
  of disk ``i`` each came at the same time as the one before it, to within a
  relative ``INSTANT``: an inelastic collapse that the TC model does not stop
  (``tc`` = 0) makes a streak grow without end, and :func:`stalls` stops the run at
  ``STALL_COLLISIONS``; ``hold``, the ``tc`` with which box walls hold disks at rest
  under gravity (:func:`_rest`; 0 for elastic disks, which never come to rest);
  ``soft``, the normal speed below which an impact is elastic (where disks come to
  rest, :mod:`.resting`; 0 otherwise);
- ``heated`` (``layout.HeatedWalls``): ``kt[k]``, the temperature ``kT`` of box wall
  ``k`` (0-3) or of segment ``k - 4``; a heated wall (``kT > 0``) sends a disk back
  with a velocity drawn afresh (:func:`_heat`) instead of reflecting it;
- ``thermostat`` (``layout.Thermostat``): the Andersen thermostat, redraws of a
  random disk's velocity at ``kt`` (:func:`kick`, :func:`redraw`) at the events of a
  Poisson process of ``rate`` (over all rows), the next at ``t_next[0]``;
- ``uniforms`` (``layout.Uniforms``): uniform random numbers in ``[0, 1)`` from the
  model's generator, ``buffer``, and the next one to use, ``cursor[0]``, for both
  heated walls and the thermostat; the loop returns for a refill when fewer than
  ``RANDOM_PER_EVENT`` are left;
- ``gravity`` (``layout.Gravity``, see :mod:`.flight`) and ``growth``
  (``layout.Growth``) change the flight and the contact distance.
"""

from __future__ import annotations

import math

from .._jit import njit
from . import moving as _moving
from . import sheared
from .flight import acceleration
from .layout import (
    A_BOX,
    A_DISSIPATED,
    A_HEAT_BOX,
    A_SEGMENTS,
    A_THERMOSTAT,
    A_VIRIAL,
    A_VIRIAL_XX,
    A_VIRIAL_XY,
    A_VIRIAL_YY,
    A_WORK,
    BOX,
    FIXED,
    M_DX,
    M_DY,
    SEGMENT,
    VX,
    VY,
    W_CONTACTS,
    W_ENDS,
    W_FX,
    W_FY,
    W_HEAT,
    W_LEFT,
    W_RIGHT,
    W_WORK,
    R,
    X,
    Y,
    unpack_segment,
    unpack_shift,
)
from .predict import _segment_frame, growth_factor

# Two collisions of a disk count as simultaneous when their times differ by at most
# this fraction of the time: a few units of rounding (a collapse drives the intervals
# to zero in floating point; any physical interval is far longer).
INSTANT = 8.0 * 2.0 ** -52
# Simultaneous collisions in a row of one disk at which the run stops: a finite
# number of disks in elastic contact resolve in far fewer.
STALL_COLLISIONS = 10_000
# The most random numbers one event uses: a thermostat redraw takes one for the disk,
# one for the time of the next redraw and two for each of two Gaussians.
RANDOM_PER_EVENT = 6


@njit
def _uniform(uniforms):
    """The next uniform random number ``u`` in ``[0, 1)`` of the buffer (so ``1 - u``
    is never 0, and its logarithm is finite)."""
    cursor = uniforms.cursor
    u = uniforms.buffer[cursor[0]]
    cursor[0] += 1
    return u


@njit
def _thermal(uniforms):
    """``sqrt(-2 ln(1 - u))``: a Rayleigh deviate of unit scale (one uniform)."""
    return math.sqrt(-2.0 * math.log(1.0 - _uniform(uniforms)))


@njit
def gaussian(uniforms):
    """A standard normal deviate (Box-Muller, the cosine branch: two uniforms)."""
    r = _thermal(uniforms)
    return r * math.cos(2.0 * math.pi * _uniform(uniforms))


@njit
def needs_random(uniforms):
    """Whether the buffer of random numbers is too low for the next event."""
    buffer = uniforms.buffer
    return buffer.shape[0] > 0 and uniforms.cursor[0] + RANDOM_PER_EVENT > buffer.shape[0]


@njit
def kick(n, thermostat, uniforms):
    """A thermostat event: the row whose velocity is redrawn (uniform over the ``n``
    rows); the time of the next event is drawn (an exponential waiting time)."""
    k = min(int(_uniform(uniforms) * n), n - 1)
    thermostat.t_next[0] -= math.log(1.0 - _uniform(uniforms)) / thermostat.rate
    return k


@njit
def redraw(k, S, invm, acc, thermostat, uniforms, gravity, shear):
    """Draw the velocity of movable disk ``k`` from the Maxwell-Boltzmann distribution
    at the thermostat's ``kT`` (each component Gaussian with variance ``kT / m``), and
    add the kinetic energy gained to the thermostat's tally.  Under gravity it leaves
    any wall it rested on.  Under shear the draw is the peculiar velocity, relative to
    the flow ``rate (y - height / 2)`` at the disk, and the tally counts the peculiar
    kinetic energy."""
    s = math.sqrt(thermostat.kt * invm[k])
    if shear is not None:
        flow = shear.rate * (S[k, Y] - shear.half)
        ux = S[k, VX] - flow
        before = ux * ux + S[k, VY] * S[k, VY]
        ux = s * gaussian(uniforms)
        S[k, VX] = ux + flow
        S[k, VY] = s * gaussian(uniforms)
        acc[A_THERMOSTAT] += 0.5 * (ux * ux + S[k, VY] * S[k, VY] - before) / invm[k]
    else:
        before = S[k, VX] * S[k, VX] + S[k, VY] * S[k, VY]
        S[k, VX] = s * gaussian(uniforms)
        S[k, VY] = s * gaussian(uniforms)
        acc[A_THERMOSTAT] += (0.5 * (S[k, VX] * S[k, VX] + S[k, VY] * S[k, VY] - before)
                              / invm[k])
    if gravity is not None:
        gravity.support[k] = 0


@njit
def _pair_impulse(i, j, t, s, dd, wi, wj, acc, contact):
    """The impulse of an approaching pair as a multiple ``k`` of the separation ``d``
    (the impulse is ``k d``, its magnitude ``J = k |d|``), from ``s = dv.d < 0`` and
    ``dd = d.d``: the normal relative velocity is ``vn = s / |d|``, so
    ``J = -(1 + e) vn / (w_i + w_j)`` is ``k = -(1 + e) s / (dd (w_i + w_j))``."""
    if contact is None:
        # Momentum k d moves from j to i; with the reduced mass this reverses the
        # normal relative velocity (elastic).
        return -2.0 * s / (dd * (wi + wj))
    species = contact.species
    tc = contact.tc
    t_last = contact.t_last
    e = contact.table[species[i], species[j]]
    if t - t_last[i] < tc or t - t_last[j] < tc:
        e = 1.0  # the TC model: a disk still "in contact" collides elastically
    soft = contact.soft
    if s * s < soft * soft * dd:
        e = 1.0  # a soft impact (normal speed -s / |d| below ``soft``): elastic
    acc[A_DISSIPATED] += 0.5 * (1.0 - e * e) * s * s / (dd * (wi + wj))
    return -(1.0 + e) * s / (dd * (wi + wj))


@njit
def _wall_factor(i, t, vn2, wi, acc, contact):
    """``1 + e`` for disk ``i`` approaching a wall with the square ``vn2`` of its
    normal velocity."""
    if contact is None:
        return 2.0
    e = contact.wall
    if t - contact.t_last[i] < contact.tc or vn2 < contact.soft * contact.soft:
        e = 1.0
    acc[A_DISSIPATED] += 0.5 * (1.0 - e * e) * vn2 / wi
    return 1.0 + e


@njit
def _simultaneous(t, before):
    return t - before <= INSTANT * abs(t)


@njit
def stalls(i, j, t, invm, contact):
    """Whether the collision of disk ``i`` with disk ``j`` (``j = i`` or ``-1``: a
    wall) at time ``t`` would make a streak of ``STALL_COLLISIONS`` simultaneous
    collisions: the run must stop (an inelastic collapse).  Never for elastic disks."""
    if contact is None:
        return False
    t_last = contact.t_last
    streak = contact.streak
    if invm[i] > 0.0 and _simultaneous(t, t_last[i]) and streak[i] + 1 >= STALL_COLLISIONS:
        return True
    return (j >= 0 and invm[j] > 0.0 and _simultaneous(t, t_last[j])
            and streak[j] + 1 >= STALL_COLLISIONS)


@njit
def _note_collision(i, t, invm, contact):
    """Record that movable disk ``i`` collided at ``t`` (the TC model's clock)."""
    if contact is None:
        return
    t_last = contact.t_last
    streak = contact.streak
    if invm[i] > 0.0:
        streak[i] = streak[i] + 1 if _simultaneous(t, t_last[i]) else 0
        t_last[i] = t


@njit
def wall_normal(i, t, kind, partner, aux, S, gf, wa, wb, motion):
    """The normal ``n`` from the wall of a BOX (side ``aux``) or SEGMENT (``partner``,
    its side or end point and image shift packed in ``aux``; where it is at time ``t``,
    under ``motion``) event into disk ``i``'s side, not normalised for a segment (as for
    a pair, see :func:`collide_pair`): ``(nx, ny, nn, col)`` with ``nn = n.n`` (exactly
    1 at a box wall) and ``col`` the segment's tally of that contact (``W_LEFT``,
    ``W_RIGHT`` or ``W_ENDS``; unused for a box wall)."""
    if kind == BOX:
        # Lower wall: normal +e; upper wall: normal -e.
        sign = 1.0 if aux % 2 == 0 else -1.0
        nx = sign if aux < 2 else 0.0
        ny = 0.0 if aux < 2 else sign
        return nx, ny, 1.0, W_LEFT
    part, code = unpack_segment(aux)
    sx, sy = unpack_shift(code)
    shx = sx * gf[0]
    shy = sy * gf[1]
    if motion is not None and motion.kind[partner] != FIXED:
        moved = _moving.shift(partner, t, motion)
        shx += moved * motion.par[partner, M_DX]
        shy += moved * motion.par[partner, M_DY]
    ax = wa[partner, 0] + shx
    ay = wa[partner, 1] + shy
    bx = wb[partner, 0] + shx
    by = wb[partner, 1] + shy
    if part == 0:
        nx = ay - by
        ny = bx - ax
        col = W_LEFT
        if (S[i, X] - ax) * nx + (S[i, Y] - ay) * ny < 0.0:
            nx = -nx
            ny = -ny
            col = W_RIGHT
    else:
        ex = ax if part == 1 else bx
        ey = ay if part == 1 else by
        nx = S[i, X] - ex
        ny = S[i, Y] - ey
        col = W_ENDS
    return nx, ny, nx * nx + ny * ny, col


@njit(inline="always")
def collide_pair(i, j, t, aux, S, invm, acc, gf, contact, gravity, growth, shear):
    """Resolve the contact of disks ``i`` and ``j`` (both at time ``t``; ``j`` seen
    through the periodic image shift ``aux``), and add its impulse to the collision
    virial.  A contact that rounding left not approaching exchanges nothing.  Under
    gravity a disk leaves a wall it rested on (:func:`_rest`) if the collision gives
    it a velocity along the wall's normal.

    Under growth (``rate``) the contact distance grows at ``dd = (R_i + R_j) rate``:
    with ``vn`` the normal relative velocity (the rate at which the centres part), the
    gap closes at ``dd - vn``; the collision reverses that rate, ``vn' - dd = dd - vn``,
    so that the disks part (elastic in the frame of the growing rims; it adds kinetic
    energy, the work of the growth).

    Under shear ``j`` may be seen through the sliding boundary (:mod:`.sheared`): the
    separation and relative velocity are then those of its sliding image."""
    sx, sy = unpack_shift(aux)
    if shear is not None and sy != 0:
        dx, dy, dvx, dvy = sheared.separation(i, j, sy, t, S, gf, shear)
        s = dvx * dx + dvy * dy
    else:
        dx = S[i, X] - (S[j, X] + sx * gf[0])
        dy = S[i, Y] - (S[j, Y] + sy * gf[1])
        s = (S[i, VX] - S[j, VX]) * dx + (S[i, VY] - S[j, VY]) * dy
    # The impulse is along the separation d itself, not along a unit normal d / |d|,
    # whose computed squared length misses 1 by a rounding that is positive on
    # average and makes the energy drift upwards; with d and d.d the rounding errors
    # average out, and no square root is taken (docs/performance-notes.md, section 4).
    dd = dx * dx + dy * dy
    if growth is not None:
        s = _closing_pair(i, j, t, s, S, growth)
    if s < 0.0:
        wi = invm[i]
        wj = invm[j]
        k = _pair_impulse(i, j, t, s, dd, wi, wj, acc, contact)
        S[i, VX] += k * wi * dx
        S[i, VY] += k * wi * dy
        S[j, VX] -= k * wj * dx
        S[j, VY] -= k * wj * dy
        # The virial J |d| (n_x^2, n_y^2, n_x n_y), J = k |d|.
        acc[A_VIRIAL] += k * dd
        acc[A_VIRIAL_XX] += k * dx * dx
        acc[A_VIRIAL_YY] += k * dy * dy
        acc[A_VIRIAL_XY] += k * dx * dy
    _note_collision(i, t, invm, contact)
    _note_collision(j, t, invm, contact)
    if gravity is not None:
        _release(i, S, gravity.support)
        _release(j, S, gravity.support)


@njit
def _closing_pair(i, j, t, s, S, growth):
    """Under growth: ``s = dv.d`` of a pair less ``d(t) dd``, with ``d(t)`` its contact
    distance and ``dd`` that distance's growth speed: negative while the gap closes.
    The arithmetic of the prediction's ``b`` (``predict.pair_time_grow``), so that
    the two never disagree on whether a pair touching by rounding still closes (a
    contact predicted now that the response found not closing would come again at
    once, without end)."""
    rr = S[i, R] + S[j, R]
    return s - (rr * growth_factor(t, growth)) * (rr * growth.rate)


@njit
def _closing_wall(i, t, box, end, vn, nx, ny, nn, S, wa, wb, partner, aux, gf, growth):
    """Under growth, the closing rate of disk ``i`` on a wall in the prediction's
    arithmetic (see :func:`_closing_pair`), and the normal to reflect it along:
    ``(vn, nx, ny, nn)``.  A box wall (unit normal): ``vn - dr``; an end point (``n``
    the separation): ``n.v - r(t) dr``; a segment's side: the unit normal and normal
    velocity of ``predict._segment_frame``, towards the disk's side, less ``dr``."""
    dr = S[i, R] * growth.rate
    if box:
        return vn - dr, nx, ny, nn
    if end:
        return vn - (S[i, R] * growth_factor(t, growth)) * dr, nx, ny, nn
    sx, sy = unpack_shift(unpack_segment(aux)[1])
    ax = wa[partner, 0] + sx * gf[0]
    ay = wa[partner, 1] + sy * gf[1]
    _, _, _, unx, uny, h, w = _segment_frame(S[i, X], S[i, Y], S[i, VX], S[i, VY], ax, ay,
                                             wb[partner, 0] + sx * gf[0],
                                             wb[partner, 1] + sy * gf[1])
    if h >= 0.0:
        return w - dr, unx, uny, 1.0
    return -w - dr, -unx, -uny, 1.0


@njit
def _release(i, S, support):
    """After a collision, disk ``i`` stays held only by the walls along whose normal it
    still does not move (see :func:`_rest`)."""
    rest = support[i]
    if rest != 0:
        if S[i, VX] != 0.0:
            rest &= ~3
        if S[i, VY] != 0.0:
            rest &= ~12
        support[i] = rest


@njit
def _rest(i, side, S, invm, acc, contact, gravity):
    """Put disk ``i``, just reflected by box wall ``side``, to rest on it if gravity
    presses it into that wall and it would be back within the TC model's ``tc``: its
    bounces would go on shrinking (or, elastic under the TC rule, never end), so the
    wall holds it instead.  The normal velocity left (its kinetic energy counted as
    dissipated) is removed, and the disk slides along the wall from now on (see
    :mod:`.flight`).  Only for an inelastic model
    with ``tc > 0`` (``hold``)."""
    if contact is None or gravity is None:
        return
    axis, g_n, vn = _wall_normals(i, side, S, gravity)
    if g_n >= 0.0:
        return
    if 2.0 * vn < -g_n * contact.hold:
        _hold_on_wall(i, side, axis, vn, S, invm, acc, gravity)


@njit
def _wall_normals(i, side, S, gravity):
    """For disk ``i`` at box wall ``side``: the wall's axis, and gravity's and the
    disk's velocity's components along the wall's normal into the box."""
    axis = side >> 1
    inward = 1.0 if side % 2 == 0 else -1.0  # the wall's normal, into the box
    return (axis, (gravity.gx if axis == 0 else gravity.gy) * inward,
            S[i, VX + axis] * inward)


@njit
def _hold_on_wall(i, side, axis, vn, S, invm, acc, gravity):
    """Disk ``i`` slides along box wall ``side`` from now on: its normal velocity
    ``vn`` is removed (its kinetic energy counted as dissipated), and the wall holds
    gravity's normal component (see :mod:`.flight`)."""
    acc[A_DISSIPATED] += 0.5 * vn * vn / invm[i]
    S[i, VX + axis] = 0.0
    gravity.support[i] |= 1 << side


@njit
def _heated_contact(i, kind, partner, aux, nx, ny, nn, vn, slot, col, S, invm, acc, wacc,
                    heated, uniforms):
    """The contact of disk ``i`` with a heated wall (normal ``n``, not normalised,
    ``nn = n.n``; ``vn = v.n``): if approaching, the disk leaves with a velocity drawn
    from the wall (:func:`_heat`), and the impulse goes into the wall's tallies as at
    any wall."""
    if vn >= 0.0:
        return
    ln = math.sqrt(nn)
    k = aux if kind == BOX else 4 + partner
    impulse, jx, jy = _heat(i, k, nx / ln, ny / ln, S, invm, acc, wacc, kind, partner,
                            heated, uniforms)
    acc[slot] += impulse
    if kind != BOX:
        wacc[partner, W_FX] -= jx
        wacc[partner, W_FY] -= jy
        wacc[partner, col] += impulse


@njit
def _heat(i, k, nx, ny, S, invm, acc, wacc, kind, partner, heated, uniforms):
    """Disk ``i`` leaves heated wall ``k`` (box wall 0-3 or segment ``k - 4``; unit
    normal ``n`` into the gas) with a velocity drawn from the wall's temperature: the
    normal speed from the flux-weighted distribution ``(m vn / kT) exp(-m vn^2 / 2kT)``
    (``sqrt(-2 ln u)`` thermal speeds), the tangential component Gaussian with variance
    ``kT / m``.  The kinetic energy gained is added to the wall's heat tally.  Returns
    the normal impulse ``J = m (vn' - vn)`` and the momentum ``m (v' - v)`` the disk
    received."""
    s = math.sqrt(heated.kt[k] * invm[i])
    vx0 = S[i, VX]
    vy0 = S[i, VY]
    vn_old = vx0 * nx + vy0 * ny
    vn = s * _thermal(uniforms)
    vt = s * gaussian(uniforms)
    S[i, VX] = vn * nx - vt * ny
    S[i, VY] = vn * ny + vt * nx
    gained = 0.5 * (S[i, VX] * S[i, VX] + S[i, VY] * S[i, VY]
                    - vx0 * vx0 - vy0 * vy0) / invm[i]
    if kind == BOX:
        acc[A_HEAT_BOX + k] += gained
    else:
        wacc[partner, W_HEAT] += gained
    return ((vn - vn_old) / invm[i], (S[i, VX] - vx0) / invm[i],
            (S[i, VY] - vy0) / invm[i])


@njit
def hot(kind, partner, aux, heated):
    """Whether the wall of a ``kind`` BOX (side ``aux``) or SEGMENT (``partner``) event
    is heated."""
    if heated is None:
        return False
    return heated.kt[aux if kind == BOX else 4 + partner] > 0.0


@njit
def _moving_contact(i, t, partner, aux, S, invm, acc, wacc, gf, wa, wb, contact, gravity,
                    motion):
    """:func:`collide_wall` for the moving segment ``partner``: the normal velocity
    relative to the segment's, ``u``, is reflected (times ``e``, with the TC model as at
    a fixed wall), an oscillating segment sends the disk off at the parting speed at
    least (:func:`.moving.parting`), and the segment does the work ``J.u`` (with the
    parting push, the kinetic energy gained plus what was dissipated) on the disk
    (``acc[A_WORK]``, ``wacc[partner, W_WORK]``)."""
    nx, ny, nn, col = wall_normal(i, t, SEGMENT, partner, aux, S, gf, wa, wb, motion)
    wacc[partner, W_CONTACTS] += 1.0
    vn_lab = S[i, VX] * nx + S[i, VY] * ny  # (|n| times the normal velocity)
    us = _moving.speed(partner, t, motion)
    vn = vn_lab - us * (motion.par[partner, M_DX] * nx + motion.par[partner, M_DY] * ny)
    gx, gy = acceleration(i, gravity)
    v_min = _moving.parting(S[i, R], partner, gx, gy, motion) * math.sqrt(nn)
    if vn < v_min:  # (approaching, or leaving slower than the parting speed, >= 0)
        diss = acc[A_DISSIPATED]
        f = _wall_factor(i, t, vn * vn / nn, invm[i], acc, contact) if vn < 0.0 else 0.0
        q = -f * vn / nn  # the velocity change is q n
        if vn + q * nn < v_min:
            q = (v_min - vn) / nn  # (leaving touching: pushed to the parting speed)
        S[i, VX] += q * nx
        S[i, VY] += q * ny
        impulse = q * math.sqrt(nn) / invm[i]
        acc[A_SEGMENTS] += impulse
        wacc[partner, W_FX] -= q * nx / invm[i]
        wacc[partner, W_FY] -= q * ny / invm[i]
        wacc[partner, col] += impulse
        work = (q * (vn_lab + 0.5 * q * nn)) / invm[i] + (acc[A_DISSIPATED] - diss)
        wacc[partner, W_WORK] += work
        acc[A_WORK] += work
    _note_collision(i, t, invm, contact)
    if gravity is not None:
        _release(i, S, gravity.support)


@njit(inline="always")
def collide_wall(i, t, kind, partner, aux, S, invm, acc, wacc, gf, wa, wb, contact, heated,
                 uniforms, gravity, growth, motion):
    """Resolve the contact of disk ``i`` (at time ``t``) with box wall ``aux`` (``kind``
    BOX: x=0, x=width, y=0, y=height) or with the wall segment ``partner`` (its side or
    an end point, and its image shift, packed in ``aux``), and add the impulse to that
    wall's tally: ``acc[A_BOX + aux]`` for a box wall; ``acc[A_SEGMENTS]`` (all segments)
    and row ``partner`` of ``wacc`` (the segment's vector, side or end-point and contact
    tallies, ``layout.W_*``) for a segment.  Under gravity a disk may come to rest on
    a box wall (:func:`_rest`), and leaves a wall it rested on when a segment gives it
    a velocity along that wall's normal.  Under growth the disk's rim moves towards
    the wall at ``rate R_i``: the contact reverses the rate at which the gap closes
    (see :func:`collide_pair`).  A moving segment (``motion``): :func:`_moving_contact`."""
    if motion is not None:
        if kind != BOX and motion.kind[partner] != FIXED:
            _moving_contact(i, t, partner, aux, S, invm, acc, wacc, gf, wa, wb, contact,
                            gravity, motion)
            return
    nx, ny, nn, col = wall_normal(i, t, kind, partner, aux, S, gf, wa, wb, None)
    if kind == BOX:
        slot = A_BOX + aux
    else:
        slot = A_SEGMENTS
        wacc[partner, W_CONTACTS] += 1.0
    # Mirror the normal velocity (scaled by e), if approaching; or, at a heated wall,
    # send the disk back with a velocity drawn afresh.
    vn = S[i, VX] * nx + S[i, VY] * ny  # (|n| times the normal velocity)
    if growth is not None:
        vn, nx, ny, nn = _closing_wall(i, t, kind == BOX, col == W_ENDS, vn, nx, ny, nn, S,
                                       wa, wb, partner, aux, gf, growth)
    hot = False
    if heated is not None:
        hot = heated.kt[aux if kind == BOX else 4 + partner] > 0.0
    if heated is not None and hot:
        _heated_contact(i, kind, partner, aux, nx, ny, nn, vn, slot, col, S, invm, acc,
                        wacc, heated, uniforms)
    elif vn < 0.0:
        f = _wall_factor(i, t, vn * vn / nn, invm[i], acc, contact)
        q = -f * vn / nn  # the velocity change is q n
        S[i, VX] += q * nx
        S[i, VY] += q * ny
        if kind == BOX:
            acc[slot] += q / invm[i]  # (|n| = 1)
        else:
            impulse = q * math.sqrt(nn) / invm[i]
            acc[slot] += impulse
            # The disk receives the momentum q n / w, the segment its opposite.
            wacc[partner, W_FX] -= q * nx / invm[i]
            wacc[partner, W_FY] -= q * ny / invm[i]
            wacc[partner, col] += impulse
    _note_collision(i, t, invm, contact)
    if gravity is not None:
        if kind == BOX and not hot:
            _rest(i, aux, S, invm, acc, contact, gravity)
        else:
            _release(i, S, gravity.support)
