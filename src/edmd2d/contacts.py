"""Contacts of a packing: the contact network, rattlers and the isostatic count.

:func:`contact_network` finds every pair of disks (and every disk and wall) closer than
a small tolerance, removes the rattlers and compares the contacts of the remaining
backbone with the isostatic count; :func:`contact_tolerance` chooses the tolerance
from the gaps themselves.  Distances respect the box as everywhere in edmd2d: minimum
image on periodic axes, box walls on the others, and wall segments seen through the
periodic images as the engine sees them.

Which gaps are contacts
-----------------------
Hard disks never touch exactly in a packing made by a simulation: compressed to a
reduced pressure ``Z = P A / (N k T)``, each disk rattles in a cage.  The free-volume
(cell) argument gives ``Z ~ 1 / (1 - (phi / phi_J)^(1/d))``, asymptotically the exact
``d / (1 - phi / phi_J)`` of Salsburg and Wood (J. Chem. Phys. 37, 798 (1962)), with
neighbours a gap ``h ~ sigma (1 - (phi / phi_J)^(1/d)) ~ sigma / Z`` apart (``sigma``
the sum of the two radii); the virial of an isostatic packing (``z = 2d`` contacts per
disk, each pushing with the entropic force ``k T / h``) gives the same ``h ~ sigma / Z``.
The gaps of contacts are therefore of order ``1 / Z`` relative to ``sigma`` (spread
over decades below that in a snapshot), while the near contacts that are not contacts
spread continuously above it: their number per disk grows about as ``h^0.6``
(``g(r) ~ (r - sigma)^-0.4`` near contact; Donev, Torquato and Stillinger, Phys. Rev.
E 71, 011105 (2005); Charbonneau, Corwin, Parisi and Zamponi, Phys. Rev. Lett. 109,
205501 (2012)).  A tolerance must lie well above ``1 / Z`` (all contacts found) and as
far below the near contacts as possible (none taken for a contact); there is a clean
separation only in a packing compressed to a high ``Z``.

The default tolerance, ``1e-7``, is ``100 / Z`` for the ``Z = 1e9`` at which
:func:`edmd2d.compress` stops by default (:data:`edmd2d.compress.DEFAULT_MAX_PRESSURE`).
Measured on the 50:50 mixture of diameter ratio 1.4 (256 disks, rate 1e-2, three
seeds, ``Z`` = 1.01e9-1.05e9), the backbone's contacts have gaps up to 60-80 times
``1 / Z`` (most below ``10 / Z``), and only a few gaps follow below ``1e3 / Z``:
tolerances from ``100 / Z`` to ``3e3 / Z`` give the same backbone to within 6 of its
441-465 contacts, while ``1 / Z`` (1e-9) leaves every disk a rattler.  A packing
compressed further keeps its contacts below the default; one compressed less has
contacts near or above it.  That is detected: when more gaps than 5 % of the contacts
found lie within a factor ``sqrt(10)`` of ``tol`` on either side, the contacts depend
on ``tol`` and :func:`contact_network` warns, naming it (for the packings above at the
default, 3-7 gaps, 0.7-1.5 %; at 1e-9, some 250 gaps against a handful of contacts).
It warns too when every disk is a rattler (no backbone, a mean contact number of NaN).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._gaps import _Candidates, _candidates
from ._validate import as_float_array, as_positive_float, indices_where, per_disk
from .analysis import _wrap
from .compress import DEFAULT_MAX_PRESSURE
from .geometry import BOX_WALLS, Box, Wall, as_walls
from .simulation import Simulation

__all__ = ["ContactNetwork", "contact_network", "contact_tolerance", "BOX_SIDES",
           "DEFAULT_TOL"]

#: Names of the box walls in ``ContactNetwork.box_contacts`` (side codes 0 to 3:
#: ``x = 0``, ``x = width``, ``y = 0``, ``y = height``): :data:`edmd2d.geometry.BOX_WALLS`.
BOX_SIDES = BOX_WALLS

_DIM = 2
# Relative gaps are floored here by contact_tolerance before their logarithms are
# compared: a lattice built at exact contact has gaps of 0 or +-1 ulp, all one class.
_GAP_FLOOR = 2.0**-52
#: The default relative tolerance of :func:`contact_network`: ``100 / Z`` for the
#: reduced pressure ``Z = 1e9`` at which :func:`edmd2d.compress` stops by default (see
#: the module notes).
DEFAULT_TOL = 100.0 / DEFAULT_MAX_PRESSURE
# contact_network warns when more gaps than this fraction of the contacts found lie
# within a factor _BAND of tol (above or below): the tolerance then cuts through the
# gaps instead of falling between contacts and near contacts.
_AMBIGUOUS = 0.05
_BAND = math.sqrt(10.0)
# contact_tolerance looks at the gaps up to this fraction of the sum of radii: the
# first shell of neighbours of a dense packing, some 3N gaps and more.
_AUTO_REACH = 0.25


# --------------------------------------------------------------------------- result
@dataclass(frozen=True, eq=False, repr=False)
class ContactNetwork:
    """The contacts of a packing and their count against isostaticity.

    Made by :func:`contact_network`; every array is read-only.

    Attributes
    ----------
    pairs : ndarray of int, shape (C, 2)
        Disk-disk contacts ``(i, j)``, ``i < j``, sorted.  A pair touching through two
        periodic images (in a box less than two of its diameters wide) is listed once
        per image; a disk touching its own image is not a contact (the distance to it
        is fixed by the box and constrains nothing).
    gaps : ndarray, shape (C,)
        Centre distance minus the sum of radii of each pair (negative: an overlap).
    box_contacts : ndarray of int, shape (B, 2)
        Contacts ``(disk, side)`` with the box walls of walled axes, ``side`` an index
        into :data:`BOX_SIDES` (0 ``x = 0``, 1 ``x = width``, 2 ``y = 0``, 3
        ``y = height``).
    box_gaps : ndarray, shape (B,)
        Distance from the centre to the wall minus the radius.
    wall_contacts : ndarray of int, shape (S, 2)
        Contacts ``(disk, k)`` with the wall segment ``walls[k]`` (its side or an end
        point), one per disk and segment.
    wall_gaps : ndarray, shape (S,)
        Distance from the centre to the segment minus the radius.
    contact_numbers : ndarray of int, shape (N,)
        Contacts of each disk before rattlers are removed: disks, box walls and
        segments.
    rattlers : ndarray of bool, shape (N,)
        Disks removed as rattlers (see :func:`contact_network`).
    mean_contact_number : float
        ``z = (2 n_contacts + n_wall_contacts) / N'`` over the ``N'`` non-rattlers,
        counting only their contacts with each other and with walls (in a periodic box
        ``2 n_contacts / N'``); NaN when every disk is a rattler.
    isostatic_contact_number : float
        ``2 d = 4``, the isostatic mean contact number of a large packing.
    excess_contact_number : float
        ``mean_contact_number - 4`` (``Delta z``, which vanishes at jamming as the
        square root of the excess packing fraction for soft disks).
    n_contacts : int
        Disk-disk contacts between non-rattlers.
    n_wall_contacts : int
        Box-wall and segment contacts of non-rattlers.
    n_isostatic : int
        The fewest contacts (``n_contacts + n_wall_contacts``) of a jammed backbone of
        ``N'`` disks: ``d N' - p + 1``, ``p`` the number of periodic axes (0 when
        ``N' = 0``); see :func:`contact_network`.
    excess_contacts : int
        ``n_contacts + n_wall_contacts - n_isostatic``: 0 for an isostatic packing,
        positive for a hyperstatic one, negative for a backbone that cannot be jammed
        (too few contacts, or the tolerance too tight).
    max_overlap : float
        The largest overlap found, ``max(0, -gap)`` over all contacts (disk-disk, box
        walls and segments), in units of length.
    max_relative_overlap : float
        The same relative to the sum of radii (for walls: to the diameter); a packing
        from an exact simulation has overlaps of rounding only (1e-14 or less).
    tol : float
        The tolerance used (given, or chosen by ``tol="auto"``).
    """

    pairs: np.ndarray
    gaps: np.ndarray
    box_contacts: np.ndarray
    box_gaps: np.ndarray
    wall_contacts: np.ndarray
    wall_gaps: np.ndarray
    contact_numbers: np.ndarray
    rattlers: np.ndarray
    mean_contact_number: float
    isostatic_contact_number: float
    excess_contact_number: float
    n_contacts: int
    n_wall_contacts: int
    n_isostatic: int
    excess_contacts: int
    max_overlap: float
    max_relative_overlap: float
    tol: float

    @property
    def n_disks(self) -> int:
        """Number of disks ``N``."""
        return len(self.rattlers)

    @property
    def n_rattlers(self) -> int:
        """Number of rattlers ``N_r``; ``N' = N - N_r``."""
        return int(self.rattlers.sum())

    @property
    def is_isostatic(self) -> bool:
        """Whether the non-rattlers hold exactly ``n_isostatic`` contacts (and are
        not all rattlers)."""
        return self.n_disks > self.n_rattlers and self.excess_contacts == 0

    def __repr__(self) -> str:
        return (f"ContactNetwork(disks={self.n_disks}, rattlers={self.n_rattlers}, "
                f"contacts={self.n_contacts}, wall_contacts={self.n_wall_contacts}, "
                f"z={self.mean_contact_number:.6g}, n_isostatic={self.n_isostatic}, "
                f"excess_contacts={self.excess_contacts}, "
                f"max_overlap={self.max_overlap:.3g}, tol={self.tol:.3g})")


# --------------------------------------------------------------------------- public
def contact_network(source: Simulation | ArrayLike, box: Box | None = None, *,
                    radii: ArrayLike | None = None, walls: Wall | Iterable[Wall] | None = None,
                    tol: float | str = DEFAULT_TOL) -> ContactNetwork:
    """The contact network of a packing, its rattlers and its isostatic count.

    Two disks are in contact when their gap (centre distance, minimum image on
    periodic axes, minus the sum of radii) is at most ``tol`` times the sum of radii;
    a disk touches a box wall (walled axes) or a wall segment when its gap to it is at
    most ``tol`` times its diameter (a wall is judged like a disk of the same size, so
    that equal disks have one threshold for all their contacts).

    Rattlers are disks with fewer than ``d + 1 = 3`` contacts, the fewest that can hold
    a disk in place, found iteratively: a rattler's contacts are taken away from its
    neighbours, which may then become rattlers too, until every remaining disk (the
    backbone, ``N' = N - N_r`` disks) has at least 3 contacts with the backbone and the
    walls.  (A disk with 3 or more contacts all on one side of it is not caught: the
    count is the usual criterion.)

    The isostatic count is that of Goodrich, Liu and Nagel, Phys. Rev. Lett. 109,
    095704 (2012): a jammed packing of ``N'`` disks in a periodic box needs at least
    ``N_c = d (N' - 1) + 1`` contacts, ``d N'`` coordinates less the ``d`` global
    translations, plus one contact for the rigidity against compression (the scale of
    the disks, or the volume of the box, is a degree of freedom of a jammed packing
    too), so a mean contact number ``z = 2d - 2d/N' + 2/N'``, which tends to
    ``2d = 4``.  With walls,
    a walled axis has no translation to subtract and a wall contact counts as one
    constraint: ``n_isostatic = d N' - p + 1`` contacts with disks and walls, ``p`` the
    number of periodic axes (2 for a periodic box, 0 for a closed one).

    Parameters
    ----------
    source : Simulation or array_like, shape (N, 2)
        A simulation (its positions, radii, box and wall segments) or positions.
    box : Box
        Required with positions; not allowed with a Simulation.
    radii : float or array_like, shape (N,)
        Required with positions (> 0); not allowed with a Simulation.
    walls : Wall or sequence of Wall, optional
        Wall segments, with positions only (a Simulation's own are used).
    tol : float or "auto", default 1e-7
        The largest relative gap of a contact, in [0, 1).  Contacts of a packing
        compressed to a reduced pressure ``Z`` have relative gaps of order ``1 / Z``
        (see the module notes): take ``tol`` about ``100 / Z``.  The default,
        :data:`DEFAULT_TOL` ``= 100 / 1e9``, suits the packings :func:`edmd2d.compress`
        makes with its default ``max_pressure = 1e9`` and any compressed further; for
        a packing compressed less, pass ``tol=100 / result.reduced_pressure`` (for a
        tolerance of ``h``, some ``h^0.6`` near contacts per disk are then counted as
        contacts), or ``"auto"`` (:func:`contact_tolerance`, which refuses a packing
        without a clear separation).  Hand-built packings at exact contact have gaps
        of rounding only, found by any tolerance.

    Returns
    -------
    ContactNetwork
        The contacts, rattlers, counts and the largest overlap.

    Warns
    -----
    UserWarning
        When ``tol`` does not separate contacts from gaps: more than 5 % as many
        gaps as contacts lie within a factor ``sqrt(10)`` of ``tol`` (the count
        depends on ``tol``; e.g. a packing compressed less than ``tol`` suits, or a
        tolerance wide enough to reach the neighbours of a gas), or no disk is left
        after the rattlers are removed (``mean_contact_number`` is NaN).  The
        message names ``tol`` and how many gaps lie near it.

    Raises
    ------
    TypeError, ValueError
        For a bad source, box, radii or walls, positions outside a walled axis, or a
        ``tol`` outside [0, 1); from ``tol="auto"`` as :func:`contact_tolerance`.

    Examples
    --------
    A square lattice of unit disks at contact: each disk touches 4, and the periodic
    packing of 64 disks is hyperstatic by ``64 * 2 - 64 * 2 + 2 - 1 = 1`` contact:

    >>> import numpy as np, edmd2d as ed
    >>> i, j = np.meshgrid(np.arange(8), np.arange(8))
    >>> pts = np.column_stack([i.ravel() + 0.5, j.ravel() + 0.5])
    >>> net = ed.contact_network(pts, ed.Box(8.0, 8.0), radii=0.5)
    >>> int(net.contact_numbers.min()), int(net.contact_numbers.max()), net.n_rattlers
    (4, 4, 0)
    >>> net.n_contacts, net.n_isostatic, net.excess_contacts, net.max_overlap
    (128, 127, 1, 0.0)
    """
    pos, rad, box, segs = _inputs(source, box, radii, walls)
    if isinstance(tol, str):
        if tol != "auto":
            raise ValueError(f'tol must be a number in [0, 1) or "auto", got {tol!r}')
        cand = _candidates(pos, rad, box, segs, _AUTO_REACH)
        tol = _auto_tolerance(cand, len(pos), min_separation=100.0)
    else:
        tol = _as_tol(tol)
        # Up to a factor _BAND above tol, for the check of the gaps near it.
        cand = _candidates(pos, rad, box, segs, min(tol * _BAND, 1.0))
    net = _network(cand, rad, box, tol)
    _check_separation(cand, net, tol)
    return net


def contact_tolerance(source: Simulation | ArrayLike, box: Box | None = None, *,
                      radii: ArrayLike | None = None, walls: Wall | Iterable[Wall] | None = None,
                      min_separation: float = 100.0) -> float:
    """A contact tolerance read off the gaps of a packing, where they separate.

    The relative gaps of all near neighbours (gap over the sum of radii, up to 0.25;
    walls relative to the diameter) are sorted, and the widest step between two
    consecutive gaps on a logarithmic scale is taken for the line between contacts
    and near contacts: the tolerance is the geometric mean of the two gaps at that
    step.  Only steps with between ``N / 2`` and ``3 N`` plus the number of wall
    gaps below them are considered, the contact counts a packing can have (a jammed
    packing has about ``2 N'`` contacts; a planar contact graph of disks at most
    about ``3 N``): the smallest gaps of contacts themselves spread over decades, and
    a step among them must not be taken.  This is robust for a packing compressed
    until its contacts lie decades below its near contacts, with no stray gap
    between them, and on hand-built packings at contact; it is refused otherwise.
    A few gaps between the two (a rattler's, in its cage) are enough to split the
    step: for the 50:50 mixture jammed by :func:`edmd2d.compress` with its default
    ``Z = 1e9`` (256 disks, rate 1e-2), the widest step was a factor 4 to 70 over
    three seeds, and it is refused there, where the default ``tol`` of
    :func:`contact_network` suits.

    Parameters
    ----------
    source, box, radii, walls
        As for :func:`contact_network`.
    min_separation : float, default 100.0
        The least ratio of the gaps across the step, > 1: below it no clear separation
        exists and a ``ValueError`` is raised.

    Returns
    -------
    float
        A relative tolerance for :func:`contact_network`.

    Raises
    ------
    ValueError
        When no step of at least ``min_separation`` exists (the packing is not
        compressed enough, or too small; pass ``tol`` explicitly), and for bad input
        as :func:`contact_network`.

    Examples
    --------
    A triangular lattice at contact with gaps of 1e-12 between neighbours; the next
    neighbours lie ``sqrt(3) - 1`` diameters further:

    >>> import numpy as np, edmd2d as ed
    >>> i, j = np.meshgrid(np.arange(10), np.arange(10))
    >>> s = 1.0 + 1e-12
    >>> pts = np.column_stack([((i + 0.5 * (j % 2)) * s).ravel(), (j * s * np.sqrt(3) / 2).ravel()])
    >>> box = ed.Box(10 * s, 10 * s * np.sqrt(3) / 2)
    >>> tol = ed.contact_tolerance(pts, box, radii=0.5)
    >>> bool(1e-10 < tol < 1e-3), ed.contact_network(pts, box, radii=0.5, tol=tol).n_contacts
    (True, 300)
    """
    pos, rad, box, segs = _inputs(source, box, radii, walls)
    sep = as_positive_float("min_separation", min_separation)
    if not sep > 1.0:
        raise ValueError(f"min_separation must be > 1, got {sep}")
    cand = _candidates(pos, rad, box, segs, _AUTO_REACH)
    return _auto_tolerance(cand, len(pos), min_separation=sep)


# --------------------------------------------------------------------------- inputs
def _inputs(source, box, radii, walls):
    """``(positions wrapped into the box, radii, box, segment end points (S, 2, 2))``."""
    if isinstance(source, Simulation):
        for name, value in (("box", box), ("radii", radii), ("walls", walls)):
            if value is not None:
                raise TypeError(f"{name} must not be given with a Simulation (it has its own)")
        pos, rad, box = source.positions, source.radii, source.box
        # (The segments where they are now: some may move.)
        segs = tuple(Wall(a, b) for a, b in source.wall_positions)
    else:
        if box is None:
            raise TypeError("box is required with an array of positions: pass "
                            "box=edmd2d.Box(...)")
        if not isinstance(box, Box):
            raise TypeError(f"box must be an edmd2d.Box, got {type(box).__name__}")
        pos = as_float_array("positions", source, (None, 2))
        if len(pos) == 0:
            raise ValueError("positions must hold at least one disk, got shape (0, 2)")
        if radii is None:
            raise TypeError("radii is required with an array of positions: pass radii=r "
                            "(one number, or one per disk)")
        rad = per_disk("radii", radii, len(pos))
        if (rad <= 0).any():
            raise ValueError(f"radii must be > 0; disks {indices_where(rad <= 0)} are not")
        segs = tuple(as_walls(walls))
    pos = _wrap(np.ascontiguousarray(pos, dtype=np.float64), box)
    ends = np.array([[w.start, w.end] for w in segs], dtype=np.float64).reshape(-1, 2, 2)
    if isinstance(source, Simulation):
        ends[source.open_walls] = np.nan  # (an open segment touches nothing)
    return pos, np.asarray(rad, dtype=np.float64), box, ends


def _as_tol(tol) -> float:
    tol = as_positive_float("tol", tol, allow_zero=True)
    if tol >= 1.0:
        raise ValueError(f"tol must be < 1 (a fraction of the sum of radii; contacts of a "
                         f"compressed packing lie far below, e.g. 1e-9), got {tol}")
    return tol


# --------------------------------------------------------------------------- gaps
# --------------------------------------------------------------------------- analysis
def _auto_tolerance(cand: _Candidates, n: int, *, min_separation: float) -> float:
    """The geometric mean of the two relative gaps across the widest logarithmic step
    whose lower side holds between N/2 and 3N + (wall gaps) gaps."""
    # Every gap not among the candidates is at least the reach: it closes the list.
    rel = np.sort(np.concatenate([*_relative(cand), [_AUTO_REACH]]))
    logs = np.log(np.maximum(rel, _GAP_FLOOR))
    steps = np.diff(logs)  # steps[k - 1]: between the k-th and (k+1)-th smallest
    below = np.arange(1, len(rel))  # gaps below each step
    upper = 3 * n + len(cand.box) + len(cand.segs)
    window = (below >= max(1, math.ceil(n / 2))) & (below <= upper)
    if not window.any():
        raise ValueError(f"contact_tolerance: only {len(rel)} near gaps among {n} disks, "
                         f"fewer than the {math.ceil(n / 2)} contacts of even a loose "
                         "packing; pass tol explicitly")
    k = int(np.argmax(np.where(window, steps, -np.inf)))
    ratio = math.exp(steps[k])
    if ratio < min_separation:
        raise ValueError(
            f"contact_tolerance: the gaps show no clear separation between contacts and "
            f"near contacts (the widest step, after the {k + 1} smallest relative gaps, "
            f"is a factor {ratio:.3g} < min_separation={min_separation:g}); compress "
            "the packing further or pass tol explicitly (about 100 / Z)")
    lo, hi = math.exp(logs[k]), math.exp(logs[k + 1])
    return min(math.sqrt(lo * hi), math.nextafter(1.0, 0.0))


def _check_separation(cand: _Candidates, net: ContactNetwork, tol: float) -> None:
    """Warn when ``tol`` does not separate contacts from gaps (see the module notes)."""
    rel = np.concatenate(_relative(cand))
    found = int(np.count_nonzero(rel <= tol))
    near = int(np.count_nonzero((rel > tol / _BAND) & (rel <= tol * _BAND)))
    if near > _AMBIGUOUS * found:
        warnings.warn(
            f"contact_network: tol={tol:.3g} does not separate contacts from gaps: "
            f"{near} relative gaps lie within a factor {_BAND:.3g} of it, against "
            f"{found} contacts at or below it, so the contacts found depend on tol. "
            "A packing compressed to a reduced pressure Z has its contacts about 1 / Z "
            "apart: pass tol of about 100 / Z (the default 1e-7 suits Z = 1e9, the "
            'default of compress), or tol="auto"', UserWarning, stacklevel=3)
    elif net.n_rattlers == net.n_disks:
        warnings.warn(
            f"contact_network: every disk is a rattler at tol={tol:.3g} ({found} "
            "contacts, none left once the disks with fewer than 3 are removed): no "
            "backbone, mean_contact_number is NaN.  For a compressed packing, pass tol "
            "of about 100 / Z (Z its reduced pressure)", UserWarning, stacklevel=3)


def _relative(cand: _Candidates):
    """Relative gaps of the candidates (pairs, box walls, segments)."""
    return (cand.gaps / cand.pair_scale, cand.box_gaps / cand.box_scale,
            cand.seg_gaps / cand.seg_scale)


def _network(cand: _Candidates, rad, box: Box, tol: float) -> ContactNetwork:
    n = len(rad)
    rel_pairs, rel_box, rel_segs = _relative(cand)
    kp, kb, ks = rel_pairs <= tol, rel_box <= tol, rel_segs <= tol
    pairs, gaps = cand.pairs[kp], cand.gaps[kp]
    bcont, bgaps = cand.box[kb], cand.box_gaps[kb]
    scont, sgaps = cand.segs[ks], cand.seg_gaps[ks]

    walls_per_disk = (np.bincount(bcont[:, 0], minlength=n)
                      + np.bincount(scont[:, 0], minlength=n))
    z = (np.bincount(pairs[:, 0], minlength=n) + np.bincount(pairs[:, 1], minlength=n)
         + walls_per_disk)
    alive = _peel(pairs, z.copy(), n, _DIM + 1)

    n_alive = int(alive.sum())
    backbone = alive[pairs[:, 0]] & alive[pairs[:, 1]]
    n_contacts = int(backbone.sum())
    n_walls = int(walls_per_disk[alive].sum())
    periodic_axes = sum(box.periodic)
    n_iso = _DIM * n_alive - periodic_axes + 1 if n_alive else 0
    zbar = (2 * n_contacts + n_walls) / n_alive if n_alive else math.nan
    rel_all = np.concatenate([rel_pairs[kp], rel_box[kb], rel_segs[ks], [0.0]])
    abs_all = np.concatenate([gaps, bgaps, sgaps, [0.0]])
    return ContactNetwork(
        pairs=_frozen(pairs), gaps=_frozen(gaps), box_contacts=_frozen(bcont),
        box_gaps=_frozen(bgaps), wall_contacts=_frozen(scont), wall_gaps=_frozen(sgaps),
        contact_numbers=_frozen(z.astype(np.int64)), rattlers=_frozen(~alive),
        mean_contact_number=float(zbar), isostatic_contact_number=float(2 * _DIM),
        excess_contact_number=float(zbar - 2 * _DIM), n_contacts=n_contacts,
        n_wall_contacts=n_walls, n_isostatic=int(n_iso),
        excess_contacts=int(n_contacts + n_walls - n_iso),
        max_overlap=float(max(0.0, -abs_all.min())),
        max_relative_overlap=float(max(0.0, -rel_all.min())), tol=float(tol),
    )


def _peel(pairs: np.ndarray, z: np.ndarray, n: int, need: int) -> np.ndarray:
    """Non-rattlers: remove every disk with fewer than ``need`` contacts, take its
    contacts from its neighbours, and repeat until none is left to remove.  The result
    does not depend on the order of removal (removal only lowers counts), so each
    round removes all current candidates at once."""
    both = np.concatenate([pairs, pairs[:, ::-1]])
    both = both[np.argsort(both[:, 0], kind="stable")]
    indptr = np.searchsorted(both[:, 0], np.arange(n + 1))
    nbr = both[:, 1]
    alive = np.ones(n, dtype=bool)
    doomed = np.flatnonzero(z < need)
    while len(doomed):
        alive[doomed] = False
        starts, counts = indptr[doomed], indptr[doomed + 1] - indptr[doomed]
        total = int(counts.sum())
        if total == 0:
            break
        # The CSR slices of all doomed disks, concatenated.
        idx = np.repeat(starts - np.cumsum(counts) + counts, counts) + np.arange(total)
        hit = nbr[idx]
        hit = hit[alive[hit]]
        np.subtract.at(z, hit, 1)
        cand = np.unique(hit)
        doomed = cand[z[cand] < need]
    return alive


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.ascontiguousarray(a)
    a.setflags(write=False)
    return a

