"""Groups of slow disks that hold one another up: found by their contact forces.

The engine puts a disk to rest after a collision when its *static* supports (disks
already at rest, walls, pegs) hold it (``_engine/resting.py``).  Disks can also hold
one another: in a settling bed, clusters of tens of disks form in which no disk is
held by static bodies alone, so none comes to rest, and without friction they bounce
on each other for ever at a speed just below the soft one, at thousands of collisions
per unit time.

:func:`held_groups` finds them.  Among the slow flying disks (speed at most
``rest.speed``) it takes the contacts (gaps at most ``rest.gap``) with each other and
with static bodies, and splits the slow disks into the groups their contacts connect.
A group is held (:func:`_held`) when it is

- balanced: non-negative forces ``f`` along the contact normals balance every member's
  weight, ``A f = -m g``, to within ``tol`` of it; and
- stable: no motion lowers it.  For a motion ``u`` of the group, gravity's work is
  ``m g . u = -f . (A^T u)``: a motion that opens a loaded contact lifts the group.  A
  motion that keeps every loaded contact closed (a floppy mode) lowers it at second
  order by ``sum f |du_t|^2 / (2 l)`` over the loaded curved contacts (``du_t`` the
  relative motion across a contact, ``l`` its radius of curvature), unless it moves no
  curved contact sideways: two frictionless disks side by side, each leaning on a peg
  outside it, balance, but swing down together (an unstable arch), while a crystal
  sliding along a frictionless floor lowers nothing (a neutral motion, allowed as a
  disk on a flat floor is held).

A group that is not held may hold in part: in a settling bed a cluster of slow disks
often has a member lifted off its support for a moment, or leaning on a fast disk
outside the group, and nothing balances that member's weight.  :func:`_peel` drops
the members the least-squares balance leaves with more than ``UNHELD`` of their
weight, and the parts that the rest's mutual contacts still join are examined in
turn, up to ``PEELS`` in all per group (a member that loses its support this way is
dropped at the next try).  Each part held satisfies both conditions by itself.

Both come from one linear program, the balance that loads the most contacts
(``scipy.optimize.linprog``, HiGHS), and the singular values of the loaded contacts'
normals (the floppy modes) and their tangents.  The supports kept for each member are
its loaded contacts, those that push it most against gravity (the bodies under it)
first.

The balance is exact to rounding when it exists: in the clusters of the poured
300-disk bed (four seeds, 25 to 44 disks each, 59 to 102 contacts) the largest
residual was 1e-14 of a weight, while a group not held keeps a residual of the order
of the slope it would slide down.
"""

from __future__ import annotations

import numpy as np

from ._engine.resting import BOX_SUPPORT, MAX_SUPPORTS, SEGMENT_SUPPORT
from ._gaps import _candidates
from .geometry import Box

#: The residual force allowed on a member of a group held, relative to its weight: far
#: above the rounding of the balance (1e-14) and far below any slope a disk would slide
#: down in the time it is examined.
TOL = 1e-6
#: The largest group whose stability is decided (by the singular values of its loaded
#: contacts' normals: a dense problem); a larger one stays in flight.
RIGID_LIMIT = 1000
#: The singular value, relative to the largest, below which a motion keeps every loaded
#: contact closed (a floppy mode: of rounding size, 1e-15).
RIGID_TOL = 1e-9
#: The largest sideways motion of a curved contact in a floppy mode (of unit norm) that
#: counts as none: such a mode is neutral.
NEUTRAL_TOL = 1e-7
#: The residual force, relative to its weight, above which a member of a group not
#: held is peeled off it (:func:`_peel`): far above the residual of a group held (1e-14)
#: and of the balance's tolerance ``TOL``.
UNHELD = 1e-3
#: The most groups and parts of groups examined for each group found (each part peeled
#: off a group not held is examined in turn).
PEELS = 20
#: The inward unit normal of each box wall (x = 0, x = width, y = 0, y = height).
_BOX_NORMALS = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])


def held_groups(pos, vel, rad, mass, static, movable, box: Box, ends, cold_sides,
                cold_segments, gravity, speed: float, gap: float, tol: float):
    """The slow flying disks that hold one another up, and their supports.

    Parameters
    ----------
    pos, vel : ndarray, shape (N, 2)
        Positions (wrapped into the box) and velocities at one time.
    rad, mass : ndarray, shape (N,)
    static : ndarray of bool, shape (N,)
        The disks that hold others without moving: at rest, or immovable and still.
    movable : ndarray of bool, shape (N,)
        The disks of finite mass.
    box : Box
    ends : sequence of (a, b) pairs of ndarray, shape (2,)
        The wall segments.
    cold_sides, cold_segments : ndarray of bool
        The box walls (4) and segments that can hold a disk (not heated).
    gravity : ndarray, shape (2,)
    speed, gap, tol : float
        The fastest a disk may move, the widest gap to a support, and the residual force
        allowed, relative to a disk's weight.

    Returns
    -------
    rows : ndarray of int64
        The disks held, group by group.
    supports : ndarray of int32, shape (len(rows), 4)
        The supports of each, those that push it most against gravity first (see
        :func:`_supports`), coded as in ``_engine/resting.py``: disk rows, box walls
        ``-2 - side``, segments ``-6 - k``; ``-1`` pads.
    """
    from scipy import sparse
    from scipy.sparse import csgraph

    n = len(pos)
    slow = ~static & movable & ((vel * vel).sum(axis=1) <= speed * speed)
    none = (np.zeros(0, np.int64), np.zeros((0, MAX_SUPPORTS), np.int32))
    if not slow.any():
        return none
    sub = np.flatnonzero(slow | static)
    reach = gap / (2.0 * float(rad[sub].min()))
    cand = _candidates(pos[sub], rad[sub], box, ends, reach)

    # Contacts: a slow disk ``a`` pushed along the unit normal ``n`` by a body ``b``
    # (another slow disk, pushed back, or -1 for a static body: code ``c``).
    pa, pb = sub[cand.pairs[:, 0]], sub[cand.pairs[:, 1]]
    keep = (cand.gaps <= gap) & ((slow[pa] & (slow[pb] | static[pb]))
                                 | (static[pa] & slow[pb]))
    pa, pb, vec = pa[keep], pb[keep], cand.pair_vec[keep]
    flip = ~slow[pa]  # (then b is the slow one: make it a)
    pa, pb = np.where(flip, pb, pa), np.where(flip, pa, pb)
    vec = np.where(flip[:, None], -vec, vec)
    unit = -vec / np.hypot(vec[:, 0], vec[:, 1])[:, None]  # (from b to a)
    code = np.where(slow[pb], -1, pb)
    other = np.where(slow[pb], pb, -1)
    bd, side = sub[cand.box[:, 0]], cand.box[:, 1]
    bk = (cand.box_gaps <= gap) & slow[bd] & cold_sides[side]
    sd, seg = sub[cand.segs[:, 0]], cand.segs[:, 1]
    sk = (cand.seg_gaps <= gap) & slow[sd] & cold_segments[seg]
    svec = cand.seg_vec[sk]
    a = np.concatenate([pa, bd[bk], sd[sk]])
    b = np.concatenate([other, np.full(int(bk.sum() + sk.sum()), -1)])
    codes = np.concatenate([code, BOX_SUPPORT - side[bk], SEGMENT_SUPPORT - seg[sk]])
    seg_unit = svec / np.hypot(svec[:, 0], svec[:, 1])[:, None]
    normals = np.concatenate([unit, _BOX_NORMALS[side[bk]], seg_unit])
    # Curved contacts (with a disk, or a segment's end point) and flat ones (a box wall,
    # a segment's side: the normal is perpendicular to the segment).
    along = np.array([np.subtract(*ends[k][::-1]) for k in seg[sk]]).reshape(-1, 2)
    along /= np.maximum(np.hypot(along[:, 0], along[:, 1]), 1e-300)[:, None]
    curved = np.concatenate([np.ones(len(pa), bool), np.zeros(int(bk.sum()), bool),
                             np.abs((seg_unit * along).sum(axis=1)) > 1e-9])

    # The groups: slow disks joined by their contacts with each other.
    mutual = b >= 0
    graph = sparse.coo_matrix((np.ones(int(mutual.sum())), (a[mutual], b[mutual])),
                              shape=(n, n))
    _, label = csgraph.connected_components(graph, directed=False)
    rows_out, sup_out = [], []
    # (Members and contacts sorted by group, each group a slice of both.)
    slow_rows = np.flatnonzero(slow)
    slow_rows = slow_rows[np.argsort(label[slow_rows], kind="stable")]
    groups, starts = np.unique(label[slow_rows], return_index=True)
    ends_ = np.append(starts[1:], len(slow_rows))
    order = np.argsort(label[a], kind="stable")
    firsts = np.searchsorted(label[a][order], groups)
    lasts = np.append(firsts[1:], len(order))
    for g0, g1, lo, hi in zip(starts, ends_, firsts, lasts):
        todo = [(slow_rows[g0:g1], order[lo:hi])]
        for _ in range(PEELS):
            if not todo:
                break
            members, contacts = todo.pop()
            if len(contacts) == 0:
                continue  # (in free flight: nothing holds it)
            forces = _held(members, a[contacts], b[contacts], normals[contacts],
                           curved[contacts], mass, gravity, tol)
            if forces is not None:
                rows_out.append(members)
                sup_out.append(_supports(members, a[contacts], codes[contacts],
                                         b[contacts], normals[contacts], forces, gravity))
            elif len(members) > 1:
                todo.extend(_peel(members, contacts, a, b, normals, mass, gravity))
    if not rows_out:
        return none
    return np.concatenate(rows_out), np.concatenate(sup_out)


def _peel(members, contacts, a, b, normals, mass, gravity):
    """The parts of a group not held that may hold themselves: without the members
    that no non-negative contact forces can balance (a residual above ``UNHELD`` of
    their weight, in the least-squares balance: a member lifted off its support for
    a moment, or leaning on a fast disk outside the group), split into the parts
    their mutual contacts still join, each with its contacts.  A member that loses
    its support this way is left unbalanced in turn, and peeled at the next try."""
    from scipy import optimize, sparse
    from scipy.sparse import csgraph

    k = len(members)
    ca, cb = a[contacts], b[contacts]
    mutual = cb >= 0
    columns, local = _columns(members, ca, cb)
    matrix = columns(normals[contacts], 1.0 / np.repeat(mass[members], 2))
    rhs = -np.tile(gravity, k)
    fit = optimize.lsq_linear(matrix, rhs, bounds=(0.0, np.inf), method="trf",
                              lsmr_tol="auto")
    res = (matrix @ fit.x - rhs).reshape(k, 2)
    bad = np.hypot(res[:, 0], res[:, 1]) > UNHELD * np.hypot(*gravity)
    if not bad.any() or bad.all():
        return []
    dropped = members[bad]
    kept = members[~bad]
    keep = ~np.isin(ca, dropped) & ~np.isin(cb, dropped)
    joined = keep & mutual
    graph = sparse.coo_matrix((np.ones(int(joined.sum())),
                               (local[ca[joined]], local[cb[joined]])), shape=(k, k))
    _, label = csgraph.connected_components(graph, directed=False)
    parts = []
    for part in np.unique(label[~bad]):
        rows = kept[label[~bad] == part]
        parts.append((rows, contacts[keep & np.isin(ca, rows)]))
    return parts


def _columns(members, a, b):
    """The matrix of a group's contacts ``a``-``b`` (``b`` a member, or -1: a static
    body): column ``c`` holds a vector of contact ``c`` on disk ``a``'s two rows and its
    opposite on disk ``b``'s.  Returns ``columns(vectors, scale)``, that sparse matrix
    for one vector per contact, each row scaled by ``scale``, and ``local``, each
    member's index in the group (its rows are ``2 local`` and ``2 local + 1``)."""
    from scipy import sparse

    k = len(members)
    local = np.full(int(max(members.max(), a.max(), b.max())) + 1, -1, np.int64)
    local[members] = np.arange(k)
    m = len(a)
    cols = np.arange(m)
    rows_a = 2 * local[a]
    mutual = b >= 0
    rows_b = 2 * local[b[mutual]]
    r = np.concatenate([rows_a, rows_a + 1, rows_b, rows_b + 1])
    c = np.concatenate([cols, cols, cols[mutual], cols[mutual]])

    def columns(vectors, scale):
        v = np.concatenate([vectors[:, 0], vectors[:, 1], -vectors[mutual, 0],
                            -vectors[mutual, 1]])
        return sparse.csr_matrix((v * scale[r], (r, c)), shape=(2 * k, m))

    return columns, local


def _held(members, a, b, normals, curved, mass, gravity, tol):
    """The contact forces that hold the group ``members`` up, or ``None``.

    Held means *balanced and stable*.  Balanced: non-negative forces ``f`` along the
    contact normals balance every member's weight, ``A f = -m g``, to within ``tol`` of
    it.  Stable: no motion of the group lowers it.  For a motion ``u``, gravity's work
    is ``m g . u = -f . (A^T u)``: a motion that opens a loaded contact lifts the group.
    A motion that keeps every loaded contact closed to first order (``A^T u = 0``
    there, a floppy mode) moves the group at second order by ``-sum f |du_t|^2 /
    (2 l)`` over the loaded curved contacts (``du_t`` the relative motion across a
    contact, ``l`` its radius of curvature, the distance of the centres for two disks):
    it lowers the group unless it moves no curved contact sideways.  Such a neutral
    mode (a slide along a flat wall, a crystal's translation along a frictionless floor)
    is allowed, as a disk on a flat floor is held; any other floppy mode (two
    frictionless disks side by side leaning on two pegs swing down together) is not.
    """
    from scipy import optimize, sparse

    k = len(members)
    m = len(a)
    columns, _ = _columns(members, a, b)
    # The equations per unit mass: A f / m = -g for every member.
    matrix = columns(normals, 1.0 / np.repeat(mass[members], 2))
    rhs = -np.tile(gravity, k)
    # The balance that loads the most contacts, a linear program: A f = s (-g) with
    # f >= t, 0 <= t <= 1, s >= 1, the sum of the t largest (any balance, scaled by s,
    # loads its contacts with forces >= 1: each contact that some balance loads has
    # t = 1).  Infeasible: no balance.
    eye = sparse.identity(m, format="csr")
    lp = optimize.linprog(
        np.concatenate([np.zeros(m), -np.ones(m), [0.0]]),
        A_ub=sparse.hstack([-eye, eye, sparse.csr_matrix((m, 1))]), b_ub=np.zeros(m),
        A_eq=sparse.hstack([matrix, sparse.csr_matrix((2 * k, m)),
                            sparse.csr_matrix(-rhs[:, None])]),
        b_eq=np.zeros(2 * k),
        bounds=[(0.0, None)] * m + [(0.0, 1.0)] * m + [(1.0, None)], method="highs")
    if lp.status != 0:
        return None
    forces = lp.x[:m] / lp.x[2 * m]
    residual = (matrix @ forces - rhs).reshape(k, 2)
    if np.hypot(residual[:, 0], residual[:, 1]).max() > tol * np.hypot(*gravity):
        return None
    loaded = lp.x[m:2 * m] > 0.5
    ones = np.ones(2 * k)
    tangents = np.column_stack([-normals[:, 1], normals[:, 0]])
    if not _stable(columns(normals, ones), columns(tangents, ones), loaded,
                   loaded & curved):
        return None
    return forces


def _stable(normals, tangents, loaded, sideways):
    """Whether every motion that keeps the ``loaded`` contacts closed (the null space of
    their columns of ``normals``, transposed) moves none of the ``sideways`` contacts
    across (their columns of ``tangents``): whether every floppy mode is neutral."""
    dof = normals.shape[0]
    if dof > 2 * RIGID_LIMIT:
        return False  # (not decided: left in flight, as the group breaks up or grows)
    sub = normals[:, np.flatnonzero(loaded)].toarray().T  # (contacts, motions)
    if sub.shape[0] == 0:
        return False
    _, singular, vt = np.linalg.svd(sub, full_matrices=True)
    rank = int((singular > RIGID_TOL * singular[0]).sum())
    floppy = vt[rank:]  # (modes, motions)
    if len(floppy) == 0:
        return True
    across = tangents[:, np.flatnonzero(sideways)].toarray().T @ floppy.T
    return bool(np.abs(across).max(initial=0.0) <= NEUTRAL_TOL)


def _supports(members, a, codes, b, normals, forces, gravity):
    """Each member's supports: the bodies of its loaded contacts, those that push it
    most against gravity first (the bodies under it), then those at its sides, then
    those above it (``MAX_SUPPORTS`` at most: a disk is re-examined when one of them
    wakes, so the bodies it rests on come first)."""
    up = -np.asarray(gravity, float) / np.hypot(*gravity)
    lift = normals @ up  # (the push on a along "up", per unit force; on b it is -lift)
    entries = []  # (member, how much the contact pushes it up, body)
    for c in np.flatnonzero(forces > 0.0):
        entries.append((int(a[c]), float(forces[c] * lift[c]),
                        int(codes[c] if b[c] < 0 else b[c])))
        if b[c] >= 0:
            entries.append((int(b[c]), float(-forces[c] * lift[c]), int(a[c])))
    entries.sort(key=lambda e: (e[0], -e[1]))
    out = np.full((len(members), MAX_SUPPORTS), -1, np.int32)
    index = {int(d): k for k, d in enumerate(members)}
    kept = np.zeros(len(members), np.int64)
    for disk, _, body in entries:
        k = index[disk]
        if kept[k] < MAX_SUPPORTS:
            out[k, kept[k]] = body
            kept[k] += 1
    return out
