"""Disks that would collide unboundedly often at one instant: one inelastic impact.

Under gravity, with disks at rest, a few flying disks can be caught between static
bodies with no room to move: a row of disks lying end to end between two disks at rest
(the gaps closed to rounding), nearly level, whose middle disks fall onto the row's
contacts.  Each pair collision then sends a pulse along the row, the static bodies at
its ends send it back, and the collisions come at one instant, for ever: the
coefficient of restitution cannot damp them (their normal speeds are below the soft
speed, where impacts are elastic, and the TC model makes them elastic too), and no
disk is slow *and* held, so none comes to rest.  The engine stops such a streak after
``STALL_COLLISIONS`` collisions of one disk at one instant.

The bodies in contact then act as one, and their impact is resolved as rigid bodies'
are (Moreau's perfectly inelastic impact, the least kinetic energy change in the metric
of the masses): the velocities after it are the ones closest to those before,

    minimise  sum_k m_k |v'_k - v_k|^2 / 2   subject to   n_c . (v'_a - v'_b) >= 0

for every contact ``c`` (unit normal ``n_c`` from body ``b`` to disk ``a``; a static
body's velocity is 0): no contact keeps closing, and what was not pushed keeps its
velocity.  Its dual is a non-negative least-squares problem in the contact impulses
``J_c >= 0``, ``v' = v + M^-1 A^T J``, solved exactly by :func:`scipy.optimize.nnls`
(active sets).  The kinetic energy it removes is dissipated.  A member left touching
a static disk or a wall segment that gravity presses it into then leaves it at the
parting speed (:func:`lift`), as after any contact with a static body.

The group is found from the two disks of the collision that stalled: the flying disks
joined to them by contacts (gaps at most ``TOUCH`` of the contact distance) form it, up
to ``MAX_MEMBERS``, and their contacts with static bodies (disks at rest, immovable
disks standing still, box walls, wall segments that are not open) hold it.
"""

from __future__ import annotations

import numpy as np

from ._gaps import _candidates
from .geometry import Box

#: The largest gap, relative to the contact distance, of a contact in an impact: far
#: above the rounding of a contact (1e-16 of the box) and far below any gap a disk
#: crosses at one instant.
TOUCH = 1e-9
#: The most flying disks in one impact (the dual problem is dense: ``2 n`` by the
#: number of contacts).
MAX_MEMBERS = 400


def group(seeds, pos, rad, flying, static, box: Box, ends, cold_sides):
    """The flying disks joined to ``seeds`` by contacts, and every contact of theirs
    with each other and with static bodies: disks (``static``), the box walls
    ``cold_sides`` allows and the wall segments ``ends`` (a segment left out has
    non-finite ends: open, or heated, which holds nothing).

    Returns ``(members, a, b, box_side, segment, normal, distance)``: the members; for
    each contact ``c`` the member ``a[c]``, its body ``b[c]`` (another member ``>= 0``,
    a static disk ``-2 - row``, or ``-1`` for a box wall ``box_side[c]`` or a segment
    ``segment[c]``, the others ``-1``), the unit normal from the body to ``a[c]`` and
    the distance between the centres (for a wall, the radius).  Contacts with flying
    disks outside the group (beyond ``MAX_MEMBERS``) are left out: they collide as
    usual."""
    from scipy import sparse
    from scipy.sparse import csgraph

    n = len(pos)
    cand = _candidates(pos, rad, box, ends, TOUCH)
    pa, pb = cand.pairs[:, 0], cand.pairs[:, 1]
    touch = cand.gaps <= TOUCH * cand.pair_scale
    mutual = touch & flying[pa] & flying[pb]
    graph = sparse.coo_matrix((np.ones(int(mutual.sum())), (pa[mutual], pb[mutual])),
                              shape=(n, n)).tocsr()
    seeds = np.unique(np.asarray(seeds, np.int64))
    seeds = seeds[flying[seeds]]
    if len(seeds) == 0:
        return None
    order = csgraph.breadth_first_order(graph, int(seeds[0]), directed=False,
                                        return_predecessors=False)
    members = np.unique(np.concatenate([seeds, order[:MAX_MEMBERS]]))[:MAX_MEMBERS]
    inside = np.zeros(n, bool)
    inside[members] = True

    # Disk contacts: a member a, pushed along the unit normal from b.
    keep_ab = touch & inside[pa] & (inside[pb] | static[pb])
    keep_ba = touch & inside[pb] & static[pa]
    a = np.concatenate([pa[keep_ab], pb[keep_ba]])
    other = np.concatenate([pb[keep_ab], pa[keep_ba]])
    vec = np.concatenate([cand.pair_vec[keep_ab], -cand.pair_vec[keep_ba]])  # (a to b)
    dist = np.hypot(vec[:, 0], vec[:, 1])
    normal = -vec / dist[:, None]
    b = np.where(inside[other], other, -2 - other)
    # Box walls and segments.
    bd, side = cand.box[:, 0], cand.box[:, 1]
    bk = (cand.box_gaps <= TOUCH * cand.box_scale) & inside[bd] & cold_sides[side]
    sd, seg = cand.segs[:, 0], cand.segs[:, 1]
    sk = (cand.seg_gaps <= TOUCH * cand.seg_scale) & inside[sd]
    svec = cand.seg_vec[sk]
    box_normals = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])
    nb, ns = int(bk.sum()), int(sk.sum())
    a = np.concatenate([a, bd[bk], sd[sk]])
    b = np.concatenate([b, np.full(nb + ns, -1, np.int64)])
    box_side = np.concatenate([np.full(len(dist), -1), side[bk], np.full(ns, -1)])
    segment = np.concatenate([np.full(len(dist) + nb, -1), seg[sk]])
    normal = np.concatenate([normal, box_normals[side[bk]],
                             svec / np.hypot(svec[:, 0], svec[:, 1])[:, None]])
    distance = np.concatenate([dist, rad[bd[bk]], rad[sd[sk]]])
    return members, a, b.astype(np.int64), box_side.astype(np.int64), \
        segment.astype(np.int64), normal, distance


def resolve(members, vel, invm, a, b, normal):
    """The velocities of ``members`` after their impact and the contact impulses:
    ``(velocities, impulses, dissipated)`` (see the module notes)."""
    from scipy import optimize

    k = len(members)
    col = np.full(int(max(members.max(), a.max(initial=0), b.max(initial=0))) + 1, -1)
    col[members] = np.arange(k)
    m = len(a)
    # A: one row per contact, n . v_a - n . v_b (b a member) over the members' velocities.
    A = np.zeros((m, 2 * k))
    rows = np.arange(m)
    ia = col[a]
    A[rows, 2 * ia] = normal[:, 0]
    A[rows, 2 * ia + 1] = normal[:, 1]
    mutual = b >= 0
    ib = col[b[mutual]]
    A[rows[mutual], 2 * ib] = -normal[mutual, 0]
    A[rows[mutual], 2 * ib + 1] = -normal[mutual, 1]
    w = np.repeat(invm[members], 2)  # (the inverse masses, per velocity component)
    v = vel[members].reshape(-1)
    # min over J >= 0 of |W^1/2 A^T J + W^-1/2 v|^2: the dual of the projection.
    B = np.sqrt(w)[:, None] * A.T
    impulses, _ = optimize.nnls(B, -v / np.sqrt(w), maxiter=50 * max(m, 1))
    after = v + w * (A.T @ impulses)
    dissipated = 0.5 * float(np.sum((v * v - after * after) / w))
    return after.reshape(k, 2), impulses, dissipated


def lift(members, after, invm, a, b, side, normal, gravity, soft):
    """Make the members leave the static disks and wall segments that gravity presses
    them into at the parting speed at least (``soft`` times the share of gravity that
    presses them, as a disk that meets a static body does: ``_engine/resting.lift``),
    while driving into none of their static contacts: each member's velocity becomes
    the one nearest to it that does both (:func:`nearest`); returns the kinetic
    energy added.  Without it a member left touching such a body with no normal
    speed would meet it again at once, for ever.  (A box wall only bounds it: on a
    box wall it slides, as there.)"""
    g = float(np.hypot(*gravity))
    added = 0.0
    static = b < 0
    for k, d in enumerate(members):
        mine = np.flatnonzero(static & (a == d))
        if len(mine) == 0:
            continue
        n = normal[mine]
        pressing = -(n @ gravity)
        pressed = (pressing > 0.0) & (side[mine] < 0)
        if not pressed.any():
            continue
        target = np.where(pressed, soft * pressing / g, 0.0)
        u = nearest(after[k], n, target)
        if u is not None:
            added += 0.5 * (float(u @ u) - float(after[k] @ after[k])) / invm[d]
            after[k] = u
    return added


def nearest(v, n, target):
    """The vector nearest to ``v`` with ``n_c . u >= target_c`` for every row ``c`` (unit
    normals), or ``None`` if there is none.  In two dimensions it is ``v`` itself, its
    projection on the line of one constraint, or the crossing of two lines: the
    nearest of those that satisfy all constraints."""
    slack = 1e-12 * (float(np.hypot(*v)) + float(np.max(np.abs(target))))

    def allowed(u):
        return bool(np.all(n @ u >= target - slack))

    if allowed(v):
        return v
    options = [v + (target[c] - float(n[c] @ v)) * n[c] for c in range(len(n))]
    for c in range(len(n)):
        for e in range(c + 1, len(n)):
            pair = n[[c, e]]
            if abs(float(np.linalg.det(pair))) > 1e-12:
                options.append(np.linalg.solve(pair, target[[c, e]]))
    options = [u for u in options if allowed(u)]
    if not options:
        return None
    return min(options, key=lambda u: float((u - v) @ (u - v)))
