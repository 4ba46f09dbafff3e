"""The gaps between disks, and between disks and walls, near contact: the search that
the contact analysis (:mod:`edmd2d.contacts`) and the search for groups of disks at
rest (``_balance.py``) share.  Distances respect the box as everywhere in edmd2d:
minimum image on periodic axes, box walls on the others, wall segments seen through
the periodic images as the engine sees them."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._sums import dot
from .geometry import Box


def _boxsize(box: Box, reach: float):
    """``boxsize`` for scipy's cKDTree: the box on periodic axes; on a walled axis a
    period longer than the box by more than ``reach``, so that no pair closer than
    ``reach`` is ever found through it (positions there lie in [0, L])."""
    if not any(box.periodic):
        return None
    return np.array([length if p else length + reach + 1.0
                     for length, p in zip((box.width, box.height), box.periodic)])


def _min_image(d: np.ndarray, box: Box) -> np.ndarray:
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            d[..., axis] -= length * np.round(d[..., axis] / length)
    return d


@dataclass(frozen=True)
class _Candidates:
    """Every disk-disk, box-wall and segment gap up to a relative reach, with the
    contact scale of each (sum of radii, or diameter for walls)."""

    pairs: np.ndarray      # (P, 2) int64, i < j
    gaps: np.ndarray       # (P,)
    pair_vec: np.ndarray   # (P, 2) from the centre of i to (the image of) j
    pair_scale: np.ndarray  # (P,) sum of radii
    box: np.ndarray        # (B, 2) int64: disk, side
    box_gaps: np.ndarray
    box_scale: np.ndarray  # (B,) diameter
    segs: np.ndarray       # (S, 2) int64: disk, segment
    seg_gaps: np.ndarray
    seg_vec: np.ndarray    # (S, 2) from the segment's nearest point to the disk
    seg_scale: np.ndarray  # (S,) diameter


def _candidates(pos, rad, box: Box, ends, reach: float) -> _Candidates:
    """All gaps at most ``reach`` times their contact scale (with a small margin, so
    that the exact comparison is made on the gaps themselves)."""
    rmax = float(rad.max())
    # The margin covers the rounding of the tree's distances.
    cut = 2.0 * rmax * (1.0 + reach) * (1.0 + 1e-12) + 1e-300
    from scipy import spatial

    tree = spatial.cKDTree(pos, boxsize=_boxsize(box, cut))
    sides = [length for length, p in zip((box.width, box.height), box.periodic) if p]
    if all(side > 2.0 * cut for side in sides):
        # At most one image of a disk lies within the cut of another: the minimum image.
        pairs = tree.query_pairs(cut, output_type="ndarray").astype(np.int64).reshape(-1, 2)
        vec = _min_image(pos[pairs[:, 1]] - pos[pairs[:, 0]], box)
    else:
        pairs, vec = _image_pairs(pos, box, cut)
    dist = np.hypot(vec[:, 0], vec[:, 1])
    scale = rad[pairs[:, 0]] + rad[pairs[:, 1]]
    gaps = dist - scale
    # (Compared as relative gaps, computed as _relative does, so that the candidates
    # at reach = tol are exactly the contacts.)
    keep = gaps / scale <= reach
    pairs, gaps, vec = pairs[keep], gaps[keep], vec[keep]
    order = np.lexsort((pairs[:, 1], pairs[:, 0]))
    pairs, gaps, vec = pairs[order], gaps[order], vec[order]

    bdisk, bside, bgap = [], [], []
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            continue
        low, high = pos[:, axis] - rad, length - pos[:, axis] - rad
        for side, g in ((2 * axis, low), (2 * axis + 1, high)):
            hit = np.flatnonzero(g / (2.0 * rad) <= reach)
            bdisk.append(hit)
            bside.append(np.full(len(hit), side, dtype=np.int64))
            bgap.append(g[hit])
    bcont = _stack(bdisk, bside)
    bgaps = np.concatenate(bgap) if bgap else np.zeros(0)
    order = np.lexsort((bcont[:, 1], bcont[:, 0]))

    sdisk, sidx, sgap, svec = [], [], [], []
    for k, (a, b) in enumerate(ends):
        if not (np.isfinite(a).all() and np.isfinite(b).all()):
            continue  # (an open segment, left out by the caller: no contact)
        half = 0.5 * float(np.hypot(*(b - a)))
        near = np.asarray(tree.query_ball_point(0.5 * (a + b), half + rmax * (1.0 + 2.0 * reach)
                                                * (1.0 + 1e-12)), dtype=np.int64)
        if len(near) == 0:
            continue
        off = _segment_offset(pos[near], a, b, box)
        g = np.hypot(off[:, 0], off[:, 1]) - rad[near]
        hit = g / (2.0 * rad[near]) <= reach
        sdisk.append(near[hit])
        sidx.append(np.full(int(hit.sum()), k, dtype=np.int64))
        sgap.append(g[hit])
        svec.append(off[hit])
    scont = _stack(sdisk, sidx)
    sgaps = np.concatenate(sgap) if sgap else np.zeros(0)
    svecs = np.concatenate(svec) if svec else np.zeros((0, 2))
    sorder = np.lexsort((scont[:, 1], scont[:, 0]))
    bcont, bgaps, scont, sgaps = bcont[order], bgaps[order], scont[sorder], sgaps[sorder]
    return _Candidates(pairs, gaps, vec, rad[pairs[:, 0]] + rad[pairs[:, 1]],
                       bcont, bgaps, 2.0 * rad[bcont[:, 0]],
                       scont, sgaps, svecs[sorder], 2.0 * rad[scont[:, 0]])


def _stack(first, second) -> np.ndarray:
    if not first:
        return np.zeros((0, 2), dtype=np.int64)
    return np.column_stack([np.concatenate(first), np.concatenate(second)]).astype(np.int64)


def _image_pairs(pos, box: Box, cut: float):
    """Pairs ``i < j`` closer than ``cut`` through any periodic image, once per image
    (for boxes less than two cut-offs wide, where the minimum image is not enough), with
    the vector from ``i`` to that image of ``j``."""
    from scipy import spatial

    reps = [int(math.ceil(cut / length)) if p else 0
            for length, p in zip((box.width, box.height), box.periodic)]
    tree = spatial.cKDTree(pos)
    found_pairs, found_vec = [], []
    for a in range(-reps[0], reps[0] + 1):
        for b in range(-reps[1], reps[1] + 1):
            shift = np.array([a * box.width, b * box.height])
            rec = tree.sparse_distance_matrix(spatial.cKDTree(pos + shift), cut,
                                              output_type="ndarray")
            # (j, i, -shift) is the same contact as (i, j, shift): keep i < j only.
            rec = rec[rec["i"] < rec["j"]]
            found = np.column_stack([rec["i"], rec["j"]]).astype(np.int64)
            found_pairs.append(found)
            found_vec.append(pos[found[:, 1]] + shift - pos[found[:, 0]])
    return (np.concatenate(found_pairs).reshape(-1, 2),
            np.concatenate(found_vec).reshape(-1, 2))


def _segment_distance(p, a, b, box: Box) -> np.ndarray:
    """Distance from each point of ``p`` (K, 2) to the segment a-b, the nearest of the
    points' periodic images (those within one period of the segment's midpoint)."""
    off = _segment_offset(p, a, b, box)
    return np.hypot(off[:, 0], off[:, 1])


def _segment_offset(p, a, b, box: Box) -> np.ndarray:
    """The vector (K, 2) from the segment a-b's nearest point to each point of ``p``,
    for the nearest of the points' periodic images (as :func:`_segment_distance`)."""
    mid = 0.5 * (a + b)
    q = mid + _min_image(p - mid, box)
    u = b - a
    best = np.full(len(p), np.inf)
    out = np.zeros((len(p), 2))
    shifts = [(sx * box.width, sy * box.height)
              for sx in ((-1, 0, 1) if box.periodic[0] else (0,))
              for sy in ((-1, 0, 1) if box.periodic[1] else (0,))]
    for shift in shifts:
        r = q + np.array(shift) - a
        s = np.clip(dot(r, u) / dot(u, u), 0.0, 1.0)
        d = r - s[:, None] * u
        dist = np.hypot(d[:, 0], d[:, 1])
        nearer = dist < best
        best[nearer] = dist[nearer]
        out[nearer] = d[nearer]
    return out
