"""Disks at rest: a settled disk stops being simulated until something moves it.

Under gravity, inelastic disks that settle into a bed would otherwise bounce on each
other for ever, each bounce shorter than the last (an inelastic collapse: unboundedly
many collisions in a finite time).  A disk is therefore *put to rest* after a collision
when it is slow and held (:func:`settle`):

- its speed is at most ``rest.speed``;
- its supports, the static bodies it touches to within ``rest.gap`` (resting disks,
  immovable disks at rest, wall segments and their end points, box walls; not heated
  walls), can hold it without friction: the direction against gravity lies strictly
  inside the cone of their normals (a support on each side of it, less than half a
  turn apart), or one of them is a flat wall whose normal points against gravity.

Disks that hold one another up (an arch, a cluster in a bed) are found as groups by
the Python layer, every ``Resting.every`` time units (``_balance.py``), and put to rest
together (:func:`rest_group`).

Its velocity is then set to 0 (the kinetic energy removed counts as dissipated), its
flag ``RESTING`` is set in the support column (``layout.S_SUPPORT``, beside the box
walls a disk slides on), its supports are kept (``rest.supports``, up to
``MAX_SUPPORTS``), and it holds no event: a resting disk is not predicted, not even
against other resting disks, so a settled bed costs nothing per unit of time.  For the
disks in flight a resting disk is a fixed circle (their parabola against it:
``predict.point_time``); the flying disks around one that comes to rest are predicted
afresh at once, since a contact with it may now come sooner than their next event.

A resting disk wakes (:func:`wake`):

- when a flying disk hits it with a normal speed above ``rest.wake``: it then takes
  part in that collision with its own mass.  A softer impact leaves it at rest: the
  flying disk bounces off it as off a fixed body (:func:`collide_static`; the bed
  takes the momentum, as a wall does).  So does an impact up to ``rest.press`` that
  its static contacts can take (it pushes the disk into the cone of their normals,
  :func:`_cone`): the bed under it counts as rigid;
- when one of its supports wakes: the disks it holds wake in turn, a cascade upwards;
- when a thermostat redraws its velocity; the Python layer wakes every disk when the
  velocities, positions, gravity or walls are set.

A woken disk starts from rest and falls, or is carried off by the collision that woke
it.  Waking and the forced predictions use the loop's own machinery: a disk to be
predicted afresh gets an event now whose partner stamp cannot match (:func:`mark_stale`),
so the loop predicts it at its single prediction site.

Rests and wakes are counted (``C_RESTS``, ``C_WAKES``) and, where events are
streamed, logged as events of their own (:func:`_log`).

Box walls: under gravity a bounce on a box wall that gravity presses the disk into,
with a normal speed below ``rest.speed``, leaves the disk sliding along the wall
(``flight``: the wall holds gravity's normal component), as the TC model's ``hold``
does; without it a disk sliding along a floor would bounce ever lower for ever.

The disks a disk meets as supports, wakes in a cascade or has predicted afresh are
those near it on the grid (:func:`.wide.near`: its 3x3 cells, and with wide disks the
footprints), a symmetric relation: a disk that found a support near it is found near
that support again when the support wakes.

Supports are coded as disk rows (``>= 0``), box walls ``-2 - side`` and wall segments
``-6 - k``; ``-1`` is an empty slot.
"""

from __future__ import annotations

import math

from .._jit import njit
from . import queue
from .flight import drift, position_at, sliding_acceleration
from .layout import (
    A_DISSIPATED,
    A_VIRIAL,
    A_VIRIAL_XX,
    A_VIRIAL_XY,
    A_VIRIAL_YY,
    C_RESTS,
    C_WAKES,
    DISK,
    KIND,
    PARTNER,
    PSTAMP,
    REST,
    RESTING,
    VX,
    VY,
    WAKE,
    R,
    T,
    X,
    Y,
    pack_kind,
    unpack_segment,
    unpack_shift,
)
from .predict import _segment_frame
from .response import (
    INSTANT,
    _hold_on_wall,
    _note_collision,
    _pair_impulse,
    _release,
    _wall_normals,
)
from .wide import block, cell, near

#: The supports kept per resting disk.
MAX_SUPPORTS = 4
# Support codes of the walls (disk rows are >= 0; -1 is an empty slot).
BOX_SUPPORT = -2  # box wall ``side``: -2 - side
SEGMENT_SUPPORT = -6  # wall segment ``k``: -6 - k
#: The largest gap, relative to the disk's diameter, of a static body that a wedged
#: disk touches (:func:`wedge`): far above the rounding of a contact and far below any
#: gap a disk crosses at one instant.
WEDGE_TOUCH = 1e-9
#: The bodies within the gap examined when a disk is put to rest, beyond the disks
#: around it (:func:`candidates`): walls, and room to spare.
CANDIDATES = 32


def candidates(r_max, r_min):
    """Room for the static bodies within the gap of a disk (``Rest.codes``): a disk of
    radius ``r_max`` touches fewer than ``2 pi (r_max / r_min + 1)`` disks of radius
    ``r_min`` or more (each takes an angle ``2 asin(r_min / (r_max + r_min))`` of its
    rim), and :data:`CANDIDATES` more."""
    return CANDIDATES + int(math.ceil(2.0 * math.pi * (r_max / r_min + 1.0)))


@njit
def is_resting(i, gravity):
    """Whether disk ``i`` is at rest."""
    return (gravity.support[i] & RESTING) != 0


@njit
def _log(kind, d, t, vx, vy, invm, rest):
    """Log the rest or the wake (``kind``) of disk ``d`` at ``t`` where events are
    streamed, its impulse the momentum it lost or regained (velocity ``v``).  The log
    has room beyond its capacity for every disk (``layout.Log``)."""
    log = rest.log
    if log.capacity > 0:
        k = log.count[0]
        if k < log.times.shape[0]:
            log.times[k] = t
            log.events[k, 0] = kind
            log.events[k, 1] = rest.order[d]
            log.events[k, 2] = -1
            log.impulses[k] = math.hypot(vx, vy) / invm[d]
        log.count[0] = k + 1


@njit
def at_once(t, before, rest):
    """Whether a contact at ``t`` and one at ``before`` came at one instant: within a
    few units of rounding of the clock and ``rest.instant`` of each other (contact
    times at one instant differ by rounding, which a window of rounding size alone
    would split by its last bits)."""
    return t - before <= INSTANT * abs(t) + rest.instant


@njit
def mark_stale(k, t, E, tcand, stamp, qt, hv, qhead, qs, qf):
    """Give disk ``k`` an event at ``t`` whose partner stamp cannot match, so that the
    loop predicts it afresh then (a full prediction, at its one prediction site)."""
    tcand[k] = t
    E[k, KIND] = pack_kind(DISK, 0)
    E[k, PARTNER] = k
    E[k, PSTAMP] = stamp[k] - 1
    queue.set_time(k, t, qt, E, hv, qhead, qs, qf)


@njit
def wake(j, t, skip, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, gf, head, nxt,
         wa, wb, wstart, wwall, wsx, wsy, acc, counts, heated, gravity, rest):
    """Wake resting disk ``j`` at time ``t`` and, in cascade, every resting disk that
    one woken disk supported and the others no longer hold (:func:`held`).  Each
    woken disk resumes the velocity it came to rest with, leaves the box walls it slid
    on, and is predicted afresh (:func:`mark_stale`) except ``skip`` (the
    loop's own disk of the event, which it predicts itself)."""
    support = gravity.support
    sup = rest.supports
    stack = rest.stack
    n = 0
    if support[j] & RESTING:
        _wake_one(j, t, skip, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, acc, counts,
                  gravity, rest)
        stack[0] = j
        n = 1
    around = rest.near[0]
    while n > 0:
        n -= 1
        d = stack[n]
        for k in range(near(d, E, gi, head, nxt, rest.wide, around)):
            m = around[k, 0]
            if support[m] & RESTING:
                for s in range(MAX_SUPPORTS):
                    if sup[m, s] == d:
                        # Still held by the others (their supports renewed), or woken
                        # in turn.
                        if not held(m, t, S, E, invm, gi, gf, head, nxt, wa, wb, wstart,
                                    wwall, wsx, wsy, heated, gravity, rest):
                            _wake_one(m, t, skip, S, E, tcand, stamp, qt, hv, qhead, qs,
                                      qf, invm, acc, counts, gravity, rest)
                            stack[n] = m
                            n += 1
                        break


@njit
def _wake_one(d, t, skip, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, acc, counts,
              gravity, rest):
    """Wake disk ``d``: it resumes the velocity it came to rest with, whose kinetic
    energy leaves the dissipated tally again."""
    gravity.support[d] = 0
    for s in range(MAX_SUPPORTS):
        rest.supports[d, s] = -1
    vx = rest.frozen[d, 0]
    vy = rest.frozen[d, 1]
    acc[A_DISSIPATED] -= 0.5 * (vx * vx + vy * vy) / invm[d]
    S[d, VX] = vx
    S[d, VY] = vy
    rest.frozen[d, 0] = 0.0
    rest.frozen[d, 1] = 0.0
    S[d, T] = t  # (at rest its position holds at any time)
    stamp[d] += 1
    counts[C_WAKES] += 1
    _log(WAKE, d, t, vx, vy, invm, rest)
    if d != skip:
        mark_stale(d, t, E, tcand, stamp, qt, hv, qhead, qs, qf)


@njit
def meet(i, j, t, aux, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, gf, head, nxt,
         wa, wb, wstart, wwall, wsx, wsy, acc, counts, heated, gravity, rest):
    """Flying disk ``i`` meets disk ``j`` (both at ``t``; ``j`` through the image shift
    ``aux``): whether ``j`` is at rest and stays so, the impact being no faster than
    ``rest.wake``, or no faster than ``rest.press`` and held by ``j``'s static
    contacts.  Any other impact, and any by an immovable disk, wakes ``j`` (and what
    it supports) first."""
    if not is_resting(j, gravity):
        return False
    if invm[i] == 0.0:
        # An immovable disk (a piston) cannot bounce off it: it carries it along.
        wake(j, t, j, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, gf, head, nxt,
             wa, wb, wstart, wwall, wsx, wsy, acc, counts, heated, gravity, rest)
        return False
    sx, sy = unpack_shift(aux)
    dx = S[i, X] - (S[j, X] + sx * gf[0])
    dy = S[i, Y] - (S[j, Y] + sy * gf[1])
    s = S[i, VX] * dx + S[i, VY] * dy  # (j does not move)
    # The normal speed of the impact is -s / |d|: compared squared (s < 0 to count).
    w = rest.wake
    dd = dx * dx + dy * dy
    if s < 0.0 and s * s > w * w * dd:
        if s * s <= rest.press * rest.press * dd:
            ln = math.sqrt(dd)
            if _cone(j, t, dx / ln, dy / ln, False, S, E, invm, gi, gf, head, nxt, wa, wb,
                     wstart, wwall, wsx, wsy, heated, gravity, rest):
                return True
        wake(j, t, j, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, gf, head, nxt,
             wa, wb, wstart, wwall, wsx, wsy, acc, counts, heated, gravity, rest)
        return False
    return True


@njit
def collide_static(i, j, t, aux, S, E, invm, gi, gf, head, nxt, wa, wb, wstart, wwall, wsx,
                   wsy, acc, contact, heated, gravity, rest):
    """Flying disk ``i`` bounces off resting disk ``j`` as off a fixed circle (``j``
    keeps still: the impulse uses ``w_j = 0``), with the pair's coefficient of
    restitution, and leaves it at the parting speed at least (:func:`lift`); or, if
    it is wedged, it stops where the static bodies hold it and otherwise loses the
    velocity that drives it into them (:func:`wedge`).  The virial counts the bounce
    as any contact.  Returns whether it was wedged."""
    sx, sy = unpack_shift(aux)
    dx = S[i, X] - (S[j, X] + sx * gf[0])
    dy = S[i, Y] - (S[j, Y] + sy * gf[1])
    dd = dx * dx + dy * dy
    s = S[i, VX] * dx + S[i, VY] * dy
    wedged = at_once(t, rest.t_static[i], rest)
    rest.t_static[i] = t
    if s < 0.0:
        wi = invm[i]
        if wedged:
            wedge(i, t, dx, dy, S, E, invm, gi, gf, head, nxt, wa, wb, wstart, wwall, wsx,
                  wsy, acc, heated, gravity, rest)
        else:
            k = _pair_impulse(i, j, t, s, dd, wi, 0.0, acc, contact)
            S[i, VX] += k * wi * dx
            S[i, VY] += k * wi * dy
            acc[A_VIRIAL] += k * dd
            acc[A_VIRIAL_XX] += k * dx * dx
            acc[A_VIRIAL_YY] += k * dy * dy
            acc[A_VIRIAL_XY] += k * dx * dy
    if not wedged:
        lift(i, dx, dy, S, invm, acc, gravity, rest)
    _note_collision(i, t, invm, contact)
    _release(i, S, gravity.support)
    return wedged


@njit
def wedge(i, t, nx, ny, S, E, invm, gi, gf, head, nxt, wa, wb, wstart, wwall, wsx, wsy,
          acc, heated, gravity, rest):
    """Disk ``i`` meets a static body (normal ``n`` towards the disk, not normalised)
    at the instant it met one before, so it touches static bodies on two sides:
    bouncing between them would take unboundedly many collisions in no time.  If the
    static bodies within ``rest.gap`` hold it (:func:`held`, the criterion of rest)
    it stops, to come to rest there (settle).  Otherwise its velocity becomes the one
    nearest to it that drives it into none of the static bodies it touches (this
    one, and those within ``WEDGE_TOUCH`` of their contact distance): a perfectly
    inelastic impact with all of them at once, which keeps the velocity along them
    (a disk caught against a static body by a row that a falling disk pushes still
    falls), and it leaves this body at the parting speed (lift).  The kinetic energy
    removed is dissipated; the impulse is left out of the virial and the walls'
    tallies (it may be shared by two bodies)."""
    g = math.hypot(gravity.gx, gravity.gy)
    if _cone(i, t, -gravity.gx / g, -gravity.gy / g, False, S, E, invm, gi, gf, head, nxt,
             wa, wb, wstart, wwall, wsx, wsy, heated, gravity, rest):
        acc[A_DISSIPATED] += 0.5 * (S[i, VX] * S[i, VX] + S[i, VY] * S[i, VY]) / invm[i]
        S[i, VX] = 0.0
        S[i, VY] = 0.0
        return
    m, _ = _statics(i, t, 1.0, 0.0, WEDGE_TOUCH * 2.0 * S[i, R], S, E, invm, gi, gf, head,
                    nxt, wa, wb, wstart, wwall, wsx, wsy, heated, gravity, rest)
    angles = rest.angles
    vx = S[i, VX]
    vy = S[i, VY]
    ln = math.sqrt(nx * nx + ny * ny)
    ux = nx / ln
    uy = ny / ln
    # The velocity nearest to v in the cone {u : u.n_k >= 0}: v itself, its projection
    # on the line of one contact that it drives into, or 0 (in two dimensions one of
    # these is the projection).
    eps = 1e-12 * math.sqrt(vx * vx + vy * vy)
    best_x = 0.0
    best_y = 0.0
    best = vx * vx + vy * vy
    for k in range(-1, m):
        if k < 0:
            ax = ux
            ay = uy
        else:
            ax = math.cos(angles[k])
            ay = math.sin(angles[k])
        vn = vx * ax + vy * ay
        if vn >= 0.0 or vn * vn >= best:
            continue
        px = vx - vn * ax
        py = vy - vn * ay
        ok = px * ux + py * uy >= -eps
        for q in range(m):
            if not ok:
                break
            ok = px * math.cos(angles[q]) + py * math.sin(angles[q]) >= -eps
        if ok:
            best = vn * vn
            best_x = px
            best_y = py
    acc[A_DISSIPATED] += 0.5 * (vx * vx + vy * vy - best_x * best_x - best_y * best_y) / (
        invm[i])
    S[i, VX] = best_x
    S[i, VY] = best_y


@njit
def parting_speed(pressing, gravity, rest):
    """The speed at which :func:`lift` and :func:`part` make bodies leave each other
    that an acceleration ``pressing`` (along their normal) presses together:
    ``rest.soft pressing / |g|``.  Leaving at it, they meet again after ``2 rest.soft
    / |g|`` whatever the slope of their contact.  (A fixed speed would throw a disk
    off a contact that gravity barely presses, nearly level, far and fast: the disk
    at the end of a row lying on a bed would be thrown along the row, into the
    disks beyond, which push it back at once.)"""
    return rest.soft * pressing / math.sqrt(gravity.gx * gravity.gx
                                            + gravity.gy * gravity.gy)


@njit
def lift(i, nx, ny, S, invm, acc, gravity, rest):
    """After disk ``i`` met a static body with normal ``n`` (towards the disk, not
    normalised) that gravity presses it into: make it leave at the soft speed, scaled
    by the share of gravity that presses it (:func:`parting_speed`), at least.  A disk
    that meets a static body with no normal speed (sliding along it, or starting from
    rest on it) would otherwise meet it again at once, for ever; leaving at that speed,
    it returns after ``2 rest.soft / |g|`` whatever the slope, so it bounces along the
    body elastically at most ``|g| / (2 rest.soft)`` times per unit time, until it comes
    to rest or leaves.  The kinetic energy added is taken from the dissipated tally, so
    the energy books hold."""
    pressed = gravity.gx * nx + gravity.gy * ny
    if pressed >= 0.0:
        return
    ln = math.sqrt(nx * nx + ny * ny)
    w = (S[i, VX] * nx + S[i, VY] * ny) / ln
    target = parting_speed(-pressed / ln, gravity, rest)
    if w >= target:
        return
    vx0 = S[i, VX]
    vy0 = S[i, VY]
    q = (target - w) / ln
    S[i, VX] += q * nx
    S[i, VY] += q * ny
    acc[A_DISSIPATED] -= 0.5 * (S[i, VX] * S[i, VX] + S[i, VY] * S[i, VY]
                               - vx0 * vx0 - vy0 * vy0) / invm[i]


@njit
def slide(i, side, t, before, S, invm, acc, contact, gravity, rest):
    """After disk ``i`` bounced off box wall ``side`` at ``t`` (its collision before
    that at ``before``): if gravity presses it into that wall and it leaves with a
    normal speed below ``rest.speed``, it slides along the wall instead (its normal
    velocity, counted as dissipated, removed) -- unless a disk pushed it into the wall
    at that same instant (its collision before this one came at once, :func:`at_once`)
    and it bounces faster than a thousandth of ``rest.soft`` (a slower one slides).
    That stays a bounce: removing the bounce of a disk under another would leave the
    one above pressing on it, with no time between their contacts."""
    axis, g_n, vn = _wall_normals(i, side, S, gravity)
    if g_n >= 0.0:
        return
    if vn > 1e-3 * rest.soft and contact is not None and at_once(t, before, rest):
        return  # (pushed: its collision before this one came at the same time)
    if vn < rest.speed:
        _hold_on_wall(i, side, axis, vn, S, invm, acc, gravity)


@njit
def part(i, j, aux, held_i, held_j, S, invm, acc, gf, gravity, rest):
    """After flying disks ``i`` and ``j`` (through the image shift ``aux``) collided:
    if gravity presses them together (one of them slid on a box wall before the
    collision, ``held_i`` and ``held_j`` its bits, so their accelerations differ) and
    they part slower than :func:`parting_speed`, make them part at it, by an impulse
    along their normal (momentum conserved; the kinetic energy added taken from the
    dissipated tally, as in :func:`lift`).  The walls are those before the collision:
    a collision that pushes a sliding disk into its wall releases it (it bounces off
    the wall at once), but the wall still held the pair's push; without it a disk
    sinking between a disk at rest and one sliding on the floor would meet that one
    ever faster, at one instant in the end."""
    wi = invm[i]
    wj = invm[j]
    if wi == 0.0 or wj == 0.0:
        return
    sx, sy = unpack_shift(aux)
    nx = S[i, X] - (S[j, X] + sx * gf[0])
    ny = S[i, Y] - (S[j, Y] + sy * gf[1])
    gxi, gyi = sliding_acceleration(held_i, gravity)
    gxj, gyj = sliding_acceleration(held_j, gravity)
    pressed = (gxi - gxj) * nx + (gyi - gyj) * ny
    if pressed >= 0.0:
        return
    ln = math.sqrt(nx * nx + ny * ny)
    w = ((S[i, VX] - S[j, VX]) * nx + (S[i, VY] - S[j, VY]) * ny) / ln
    target = parting_speed(-pressed / ln, gravity, rest)
    if w >= target:
        return
    before = (S[i, VX] * S[i, VX] + S[i, VY] * S[i, VY]) / wi + (
        S[j, VX] * S[j, VX] + S[j, VY] * S[j, VY]) / wj
    jn = (target - w) / ((wi + wj) * ln)  # (the impulse over |n|)
    S[i, VX] += jn * wi * nx
    S[i, VY] += jn * wi * ny
    S[j, VX] -= jn * wj * nx
    S[j, VY] -= jn * wj * ny
    after = (S[i, VX] * S[i, VX] + S[i, VY] * S[i, VY]) / wi + (
        S[j, VX] * S[j, VX] + S[j, VY] * S[j, VY]) / wj
    acc[A_DISSIPATED] -= 0.5 * (after - before)
    _release(i, S, gravity.support)  # (a box wall held it only while it did not leave)
    _release(j, S, gravity.support)


@njit
def lift_pair(i, j, aux, S, invm, acc, gf, gravity, rest):
    """:func:`lift` off disk ``j`` (seen through the image shift ``aux``)."""
    sx, sy = unpack_shift(aux)
    lift(i, S[i, X] - (S[j, X] + sx * gf[0]), S[i, Y] - (S[j, Y] + sy * gf[1]), S, invm,
         acc, gravity, rest)
    _release(i, S, gravity.support)


@njit
def lift_segment(i, partner, aux, S, invm, acc, gf, wa, wb, gravity, rest):
    """:func:`lift` after disk ``i`` met wall segment ``partner`` (its side or an end
    point, and its image shift, packed in ``aux``)."""
    part, code = unpack_segment(aux)
    sx, sy = unpack_shift(code)
    ax = wa[partner, 0] + sx * gf[0]
    ay = wa[partner, 1] + sy * gf[1]
    bx = wb[partner, 0] + sx * gf[0]
    by = wb[partner, 1] + sy * gf[1]
    if part == 0:
        _, _, _, nx, ny, h, _ = _segment_frame(S[i, X], S[i, Y], 0.0, 0.0, ax, ay, bx, by)
        if h < 0.0:
            nx = -nx
            ny = -ny
    else:
        nx = S[i, X] - (ax if part == 1 else bx)
        ny = S[i, Y] - (ay if part == 1 else by)
    lift(i, nx, ny, S, invm, acc, gravity, rest)
    _release(i, S, gravity.support)


@njit
def settle(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, gf, head, nxt,
           wa, wb, wstart, wwall, wsx, wsy, acc, counts, heated, gravity, rest):
    """Put disk ``i`` (its state at ``t``) to rest if it is slow and held (see the module
    notes); then predict the flying disks around it afresh.  Returns whether it was."""
    support = gravity.support
    if invm[i] == 0.0 or support[i] & RESTING:
        return False
    vx = S[i, VX]
    vy = S[i, VY]
    v2 = vx * vx + vy * vy
    if v2 > rest.speed * rest.speed:
        return False
    if not held(i, t, S, E, invm, gi, gf, head, nxt, wa, wb, wstart, wwall, wsx, wsy,
                heated, gravity, rest):
        return False
    _put_to_rest(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head, nxt, acc,
                 counts, gravity, rest)
    return True


@njit
def rest_group(t, n, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head, nxt, acc,
               counts, gravity, rest):
    """Put the ``n`` flying disks ``rest.stack[:n]`` to rest at ``t`` (no earlier than
    their local times, no later than their next events), their supports already in
    ``rest.supports``: a group that holds itself, found by the Python layer
    (``_balance.py``).  Each is moved to ``t`` and gets an event then whose partner
    stamp cannot match, at which the loop finds it at rest and schedules nothing."""
    for k in range(n):
        i = rest.stack[k]
        drift(i, t, S, gravity)
        _put_to_rest(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head, nxt,
                     acc, counts, gravity, rest)
        mark_stale(i, t, E, tcand, stamp, qt, hv, qhead, qs, qf)


@njit
def impact_group(t, n, vel, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head, nxt,
                 gravity, rest):
    """Give the ``n`` flying disks ``rest.stack[:n]`` the velocities ``vel`` at ``t``
    (one inelastic impact found by the Python layer, ``_impacts.py``): each is moved to
    ``t``, leaves the box walls it no longer slides on, and is predicted afresh, as is
    every flying disk around it (a contact with it may now come sooner)."""
    support = gravity.support
    for k in range(n):
        i = rest.stack[k]
        drift(i, t, S, gravity)
        S[i, VX] = vel[k, 0]
        S[i, VY] = vel[k, 1]
        _release(i, S, support)
        stamp[i] += 1
    for k in range(n):
        i = rest.stack[k]
        mark_stale(i, t, E, tcand, stamp, qt, hv, qhead, qs, qf)
        _predict_around(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head,
                        nxt, gravity, rest)


@njit
def _predict_around(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head, nxt,
                    gravity, rest):
    """Predict afresh, at ``t``, the disks in flight near disk ``i``: a contact with it
    may now come sooner than their next events."""
    support = gravity.support
    around = rest.near[0]
    for k in range(near(i, E, gi, head, nxt, rest.wide, around)):
        m = around[k, 0]
        if (support[m] & RESTING) == 0 and (
                invm[m] > 0.0 or S[m, VX] != 0.0 or S[m, VY] != 0.0):
            mark_stale(m, t, E, tcand, stamp, qt, hv, qhead, qs, qf)


@njit
def _put_to_rest(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head, nxt, acc,
                 counts, gravity, rest):
    """Put disk ``i`` (its state at ``t``) to rest, its supports already written, and
    predict the flying disks around it afresh."""
    support = gravity.support
    vx = S[i, VX]
    vy = S[i, VY]
    acc[A_DISSIPATED] += 0.5 * (vx * vx + vy * vy) / invm[i]
    rest.frozen[i, 0] = vx
    rest.frozen[i, 1] = vy
    S[i, VX] = 0.0
    S[i, VY] = 0.0
    support[i] = RESTING
    stamp[i] += 1
    counts[C_RESTS] += 1
    _log(REST, i, t, vx, vy, invm, rest)
    _predict_around(i, t, S, E, tcand, stamp, qt, hv, qhead, qs, qf, invm, gi, head, nxt,
                    gravity, rest)


@njit
def held(i, t, S, E, invm, gi, gf, head, nxt, wa, wb, wstart, wwall, wsx, wsy, heated,
         gravity, rest):
    """Whether disk ``i`` (at ``t``) is held by the static bodies within ``rest.gap``
    of it (see the module notes); if so its supports are written to
    ``rest.supports[i]``."""
    g = math.hypot(gravity.gx, gravity.gy)
    return _cone(i, t, -gravity.gx / g, -gravity.gy / g, True, S, E, invm, gi, gf, head,
                 nxt, wa, wb, wstart, wwall, wsx, wsy, heated, gravity, rest)


@njit
def _cone(i, t, upx, upy, write, S, E, invm, gi, gf, head, nxt, wa, wb, wstart, wwall, wsx,
          wsy, heated, gravity, rest):
    """Whether the static bodies within ``rest.gap`` of disk ``i`` (at ``t``) hold it
    against a push opposite to the unit vector ``up`` without friction: ``up`` lies
    strictly inside the cone of their normals, or one of them is a flat wall whose
    normal is ``up``.  If so, and ``write``, its supports are written to
    ``rest.supports[i]``."""
    n, flat_k = _statics(i, t, upx, upy, rest.gap, S, E, invm, gi, gf, head, nxt, wa, wb,
                         wstart, wwall, wsx, wsy, heated, gravity, rest)
    codes = rest.codes
    angles = rest.angles
    # The best supports on each side of "up" (angles from it, counterclockwise
    # positive), and a flat wall under the disk.
    neg = -math.inf
    pos = math.inf
    neg_k = -1
    pos_k = -1
    for k in range(n):
        a = angles[k]
        if a < 0.0 and a > neg:
            neg = a
            neg_k = k
        elif a > 0.0 and a < pos:
            pos = a
            pos_k = k
    held = flat_k >= 0 or (neg_k >= 0 and pos_k >= 0 and pos - neg < math.pi)
    if not held or not write:
        return held
    # At rest: keep the supports that hold it first, then the others that fit.
    sup = rest.supports
    for s in range(MAX_SUPPORTS):
        sup[i, s] = -1
    if flat_k >= 0:
        # A flat wall holds it alone: no other support leaving can move it.
        sup[i, 0] = codes[flat_k]
    else:
        sup[i, 0] = codes[neg_k]
        sup[i, 1] = codes[pos_k]
        kept = 2
        for k in range(n):
            if kept >= MAX_SUPPORTS:
                break
            if k != neg_k and k != pos_k:
                sup[i, kept] = codes[k]
                kept += 1
    return True


@njit(inline="always")
def _seen(seen, n, w, qx, qy):
    """Whether the image ``(qx, qy)`` of segment ``w`` is among the first ``n`` rows of
    ``seen``."""
    for k in range(n):
        if seen[k, 0] == w and seen[k, 1] == qx and seen[k, 2] == qy:
            return True
    return False


@njit
def _statics(i, t, upx, upy, tol, S, E, invm, gi, gf, head, nxt, wa, wb, wstart, wwall,
             wsx, wsy, heated, gravity, rest):
    """The static bodies within ``tol`` of disk ``i`` (at ``t``; not heated walls): their
    codes in ``rest.codes`` and the angles of their normals (towards the disk) from the
    unit vector ``up`` (counterclockwise positive) in ``rest.angles``.  Returns their
    number and the last flat wall among them whose normal is ``up`` (-1: none)."""
    support = gravity.support
    codes = rest.codes
    angles = rest.angles
    n = 0
    x = S[i, X]
    y = S[i, Y]
    r = S[i, R]
    flat_k = -1
    # Box walls (normals into the box).
    for side in range(4):
        axis = side >> 1
        if gi[2 + axis] != 0:
            continue
        if heated is not None and heated.kt[side] > 0.0:
            continue
        c = x if axis == 0 else y
        gap = c - r if side % 2 == 0 else gf[axis] - r - c
        if gap <= tol and n < codes.shape[0]:
            inward = 1.0 if side % 2 == 0 else -1.0
            nx = inward if axis == 0 else 0.0
            ny = 0.0 if axis == 0 else inward
            codes[n] = BOX_SUPPORT - side
            angles[n] = math.atan2(upx * ny - upy * nx, upx * nx + upy * ny)
            if angles[n] == 0.0:
                flat_k = n
            n += 1
    # Wall segments listed for the disk's cell (a wide disk: its footprint's cells,
    # each segment once): the side (flat) or an end point.
    u0, u1, v0, v1, spread = block(i, E, gi, rest.wide)
    seen = rest.near[1]  # (the segment images met, before the disks near it)
    n_seen = 0
    for v in range(v0, v1 + 1):
        for u in range(u0, u1 + 1):
            c, kx, ky = cell(u, v, gi)
            k0 = 0
            k1 = 0
            if wa.shape[0] > 0:  # (without segments the lists are not there)
                k0 = wstart[c]
                k1 = wstart[c + 1]
            for k in range(k0, k1):
                w = wwall[k]
                if heated is not None and heated.kt[4 + w] > 0.0:
                    continue
                qx = wsx[k] + kx
                qy = wsy[k] + ky
                if spread:
                    # (A segment is listed in many cells of a footprint: each image
                    # once.)
                    if abs(qx) > 1 or abs(qy) > 1 or _seen(seen, n_seen, w, qx, qy):
                        continue
                    seen[n_seen, 0] = w
                    seen[n_seen, 1] = qx
                    seen[n_seen, 2] = qy
                    n_seen += 1
                shx = qx * gf[0]
                shy = qy * gf[1]
                ax = wa[w, 0] + shx
                ay = wa[w, 1] + shy
                bx = wb[w, 0] + shx
                by = wb[w, 1] + shy
                ux, uy, ll, nx, ny, h, _ = _segment_frame(x, y, 0.0, 0.0, ax, ay, bx, by)
                along = ((x - ax) * ux + (y - ay) * uy) / ll
                flat = 0.0 <= along <= 1.0
                if flat:
                    gap = abs(h) - r
                    if h < 0.0:
                        nx = -nx
                        ny = -ny
                else:
                    ex = ax if along < 0.0 else bx
                    ey = ay if along < 0.0 else by
                    dist = math.hypot(x - ex, y - ey)
                    gap = dist - r
                    nx = (x - ex) / dist
                    ny = (y - ey) / dist
                if gap <= tol and n < codes.shape[0]:
                    codes[n] = SEGMENT_SUPPORT - w
                    angles[n] = math.atan2(upx * ny - upy * nx, upx * nx + upy * ny)
                    if flat and angles[n] == 0.0:
                        flat_k = n
                    n += 1
    # Disks at rest, and immovable disks standing still, near it on the grid.
    around = rest.near[1]
    for k in range(near(i, E, gi, head, nxt, rest.wide, around)):
        m = around[k, 0]
        static = (support[m] & RESTING) != 0 or (
            invm[m] == 0.0 and S[m, VX] == 0.0 and S[m, VY] == 0.0)
        if static:
            xm, ym = position_at(m, t, S, gravity)
            dx = x - (xm + around[k, 1] * gf[0])
            dy = y - (ym + around[k, 2] * gf[1])
            dist = math.hypot(dx, dy)
            if dist - (r + S[m, R]) <= tol and n < codes.shape[0]:
                codes[n] = m
                angles[n] = math.atan2(upx * dy - upy * dx, upx * dx + upy * dy)
                n += 1
    return n, flat_k
