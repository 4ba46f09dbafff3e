"""The container: the rectangular :class:`Box`, wall :class:`Wall` segments, the motions a
segment may follow (:class:`Translation`, :class:`Oscillation`), the names of the box
walls, and the area that closed polygons of segments enclose (:func:`container`)."""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._sums import dot
from ._validate import as_float_array, as_positive_float, refusal

__all__ = ["Box", "Wall", "Translation", "Oscillation", "BOX_WALLS", "BOX_WALL_EQUATIONS",
           "container"]

#: The four walls of a box, in the order edmd2d numbers them everywhere (0 to 3: the
#: walls at ``x = 0``, ``x = width``, ``y = 0``, ``y = height``, that is ``2 * axis``
#: plus 1 at the far wall): in heated walls, wall pressures, contacts and messages.
BOX_WALLS = ("left", "right", "bottom", "top")
#: The same walls named by their equations, accepted wherever a box wall is named.
BOX_WALL_EQUATIONS = ("x=0", "x=width", "y=0", "y=height")

# The largest box side, and the largest product of a length and a speed the engine
# accepts: contact times square such products (b^2, dv^2 (dp^2 - d^2)), which must stay
# well inside float64's range (1.8e308), or the discriminant becomes inf or NaN and a
# contact is missed or repeated forever.
MAX_LENGTH = 1e150


@dataclass(frozen=True, init=False)
class Box:
    """A rectangle ``[0, width] x [0, height]``, periodic or walled on each axis.

    Parameters
    ----------
    width, height : float
        Side lengths, > 0.
    periodic : bool or (bool, bool), default True
        ``True`` makes both axes periodic, ``False`` puts hard walls on all four edges,
        a pair ``(px, py)`` chooses per axis (``(True, False)``: a channel periodic in x
        with walls at y = 0 and y = height).

    Examples
    --------
    >>> Box(40.0, 30.0, periodic=(True, False))
    Box(width=40.0, height=30.0, periodic=(True, False))
    >>> Box(10, 10).area
    100.0
    """

    width: float
    height: float
    periodic: tuple[bool, bool]

    def __init__(self, width: float, height: float,
                 periodic: bool | tuple[bool, bool] = True) -> None:
        width = as_positive_float("Box width", width)
        height = as_positive_float("Box height", height)
        for name, length in (("width", width), ("height", height)):
            if length > MAX_LENGTH:  # (squared distances must stay finite)
                raise ValueError(f"Box {name} must be at most {MAX_LENGTH:g} (lengths are "
                                 f"squared in the contact times; choose a larger unit of "
                                 f"length), got {length:g}")
        if isinstance(periodic, (bool, np.bool_)):
            pair = (bool(periodic), bool(periodic))
        else:
            try:
                items = tuple(periodic)
            except TypeError:
                raise TypeError(
                    f"Box periodic must be a bool or a pair of bools, got {periodic!r}"
                ) from None
            if len(items) != 2 or not all(isinstance(p, (bool, np.bool_)) for p in items):
                raise TypeError(
                    f"Box periodic must be a bool or a pair of bools (x, y), got {periodic!r}"
                )
            pair = (bool(items[0]), bool(items[1]))
        object.__setattr__(self, "width", width)
        object.__setattr__(self, "height", height)
        object.__setattr__(self, "periodic", pair)

    @property
    def size(self) -> np.ndarray:
        """``array([width, height])``."""
        return np.array([self.width, self.height])

    @property
    def area(self) -> float:
        """``width * height``."""
        return self.width * self.height


@dataclass(frozen=True, init=False)
class Wall:
    """A hard wall segment from ``start`` to ``end``.

    A disk can hit either side of the segment or one of its two end points (an end point
    acts as a fixed circle of radius 0).  Segments must lie inside the box.

    Parameters
    ----------
    start, end : array_like, shape (2,)
        The end points ``(x, y)``, distinct.  Both belong to the wall.

    Raises
    ------
    TypeError, ValueError
        For end points that are not two finite numbers each, or that coincide.

    Examples
    --------
    >>> Wall((5, 0), (5, 20)).length
    20.0
    """

    start: tuple[float, float]
    end: tuple[float, float]

    def __init__(self, start: ArrayLike, end: ArrayLike) -> None:
        a = as_float_array("Wall start", start, (2,))
        b = as_float_array("Wall end", end, (2,))
        if np.hypot(*(b - a)) == 0.0:
            raise ValueError(f"Wall is degenerate: start and end are both "
                             f"({float(a[0])!r}, {float(a[1])!r})")
        object.__setattr__(self, "start", (float(a[0]), float(a[1])))
        object.__setattr__(self, "end", (float(b[0]), float(b[1])))

    @property
    def length(self) -> float:
        """Euclidean length of the segment."""
        return float(np.hypot(self.end[0] - self.start[0], self.end[1] - self.start[1]))

    @classmethod
    def polygon(cls, vertices: ArrayLike, closed: bool = True) -> list[Wall]:
        """Walls along a polyline through ``vertices`` (closed by default).

        A closed polygon needs at least 3 vertices, an open polyline at least 2.

        Parameters
        ----------
        vertices : array_like, shape (K, 2)
            The corners in order.  Counterclockwise vertices put the inside of the
            polygon on the left side of every segment.
        closed : bool, default True
            Whether a last segment joins the last vertex back to the first.

        Returns
        -------
        list of Wall
            ``K`` segments for a closed polygon, ``K - 1`` for an open polyline.

        Raises
        ------
        TypeError, ValueError
            For vertices that are not an array of finite ``(x, y)`` pairs, too few
            vertices, or two consecutive vertices that coincide.

        Examples
        --------
        >>> len(Wall.polygon([(1, 1), (9, 1), (5, 8)]))
        3
        """
        pts = as_float_array("polygon vertices", vertices, (None, 2))
        need = 3 if closed else 2
        if len(pts) < need:
            raise ValueError(
                f"a {'closed polygon' if closed else 'polyline'} needs at least {need} "
                f"vertices, got {len(pts)}"
                + (" (for a single segment use Wall(start, end), or closed=False)"
                   if closed and len(pts) == 2 else "")
            )
        pairs = list(zip(pts[:-1], pts[1:]))
        if closed:
            pairs.append((pts[-1], pts[0]))
        return [cls(a, b) for a, b in pairs]


@dataclass(frozen=True, init=False)
class Translation:
    """A wall segment's motion at a constant velocity over a given distance (a piston).

    The segment keeps its shape and orientation.  It rests where it was given until
    the time ``begin``, then moves at ``velocity`` until it has travelled
    ``distance``, and rests there from then on: at time ``t`` it is shifted by
    ``velocity * clamp(t - begin, 0, distance / |velocity|)``.

    Parameters
    ----------
    velocity : array_like, shape (2,)
        The velocity ``(ux, uy)``, not zero.
    distance : float
        How far it moves, > 0.
    begin : float, optional
        The time it starts to move; default: the time the simulation starts (or the
        time the motion is set).

    Examples
    --------
    >>> m = Translation((0.0, -0.5), distance=4.0, begin=1.0)
    >>> m.end
    9.0
    >>> m.shift(3.0).tolist(), m.velocity_at(3.0).tolist()
    ([0.0, -1.0], [0.0, -0.5])
    >>> m.shift(20.0).tolist(), m.velocity_at(20.0).tolist()
    ([0.0, -4.0], [0.0, 0.0])
    """

    velocity: tuple[float, float]
    distance: float
    begin: float | None

    def __init__(self, velocity: ArrayLike, distance: float,
                 begin: float | None = None) -> None:
        u = as_float_array("Translation velocity", velocity, (2,))
        if not np.any(u != 0.0):
            raise refusal(ValueError, "velocity", "Translation velocity must not be zero")
        object.__setattr__(self, "velocity", (float(u[0]), float(u[1])))
        object.__setattr__(self, "distance", as_positive_float("Translation distance",
                                                               distance))
        if begin is not None:
            begin = float(as_float_array("Translation begin", begin, ()))
        object.__setattr__(self, "begin", begin)

    @property
    def speed(self) -> float:
        """``|velocity|``."""
        return float(np.hypot(*self.velocity))

    @property
    def end(self) -> float:
        """The time it stops (``begin + distance / speed``; needs ``begin``)."""
        if self.begin is None:
            raise ValueError("this Translation has no begin time yet")
        return self.begin + self.distance / self.speed

    def starting(self, time: float) -> Translation:
        """The same motion, with ``begin`` set to ``time`` where it was not given.

        Parameters
        ----------
        time : float

        Returns
        -------
        Translation
        """
        return self if self.begin is not None else Translation(self.velocity, self.distance,
                                                               time)

    def extremes(self) -> np.ndarray:
        """The two extreme shifts of the path: none and the last.

        Returns
        -------
        numpy.ndarray, shape (2, 2)
        """
        u = np.array(self.velocity)
        return np.array([[0.0, 0.0], u * (self.distance / self.speed)])

    def shift(self, t: float) -> np.ndarray:
        """The segment's displacement at time ``t`` from where it was given.

        Parameters
        ----------
        t : float

        Returns
        -------
        numpy.ndarray, shape (2,)
        """
        assert self.begin is not None
        moved = min(max(t - self.begin, 0.0), self.distance / self.speed)
        return np.array(self.velocity) * moved

    def velocity_at(self, t: float) -> np.ndarray:
        """The segment's velocity at time ``t`` (moving on ``[begin, end)``).

        Parameters
        ----------
        t : float

        Returns
        -------
        numpy.ndarray, shape (2,)
        """
        assert self.begin is not None
        on = self.begin <= t < self.end
        return np.array(self.velocity) if on else np.zeros(2)


@dataclass(frozen=True, init=False)
class Oscillation:
    """A wall segment's sinusoidal motion along a direction (a shaken floor): at time
    ``t`` it is shifted from where it was given by ``amplitude * sin(omega * t +
    phase)`` along the unit vector of ``direction``.  The given position is the centre
    of the motion; ``t`` is the simulation's clock.

    Parameters
    ----------
    amplitude : float
        > 0.
    omega : float
        The angular frequency, > 0.
    direction : array_like, shape (2,), default (0, 1)
        The direction of motion, not zero (normalised).
    phase : float, default 0

    Examples
    --------
    >>> m = Oscillation(0.5, omega=2.0)
    >>> m.period
    3.141592653589793
    >>> m.shift(0.0).tolist(), m.velocity_at(0.0).tolist()
    ([0.0, 0.0], [0.0, 1.0])
    """

    amplitude: float
    omega: float
    direction: tuple[float, float]
    phase: float

    def __init__(self, amplitude: float, omega: float, direction: ArrayLike = (0.0, 1.0),
                 phase: float = 0.0) -> None:
        object.__setattr__(self, "amplitude", as_positive_float("Oscillation amplitude",
                                                                amplitude))
        object.__setattr__(self, "omega", as_positive_float("Oscillation omega", omega))
        d = as_float_array("Oscillation direction", direction, (2,))
        norm = float(np.hypot(d[0], d[1]))
        if norm == 0.0:
            raise refusal(ValueError, "direction", "Oscillation direction must not be zero")
        object.__setattr__(self, "direction", (float(d[0] / norm), float(d[1] / norm)))
        object.__setattr__(self, "phase", float(as_float_array("Oscillation phase", phase,
                                                               ())))

    @property
    def period(self) -> float:
        """``2 pi / omega``."""
        return 2.0 * math.pi / self.omega

    def starting(self, time: float) -> Oscillation:
        """The same motion (its clock is the simulation's: nothing to set).

        Parameters
        ----------
        time : float

        Returns
        -------
        Oscillation
        """
        return self

    def extremes(self) -> np.ndarray:
        """The two extreme shifts of the path: ``-A`` and ``+A`` along the direction.

        Returns
        -------
        numpy.ndarray, shape (2, 2)
        """
        d = np.array(self.direction) * self.amplitude
        return np.array([-d, d])

    def shift(self, t: float) -> np.ndarray:
        """The segment's displacement at time ``t`` from where it was given.

        Parameters
        ----------
        t : float

        Returns
        -------
        numpy.ndarray, shape (2,)
        """
        return np.array(self.direction) * (self.amplitude * math.sin(self.omega * t +
                                                                     self.phase))

    def velocity_at(self, t: float) -> np.ndarray:
        """The segment's velocity at time ``t``.

        Parameters
        ----------
        t : float

        Returns
        -------
        numpy.ndarray, shape (2,)
        """
        return np.array(self.direction) * (self.amplitude * self.omega *
                                           math.cos(self.omega * t + self.phase))


#: The motions a wall segment may follow.
Motion = Translation | Oscillation


def as_walls(walls: Wall | Iterable[Wall] | None) -> list[Wall]:
    """A ``walls`` argument as a list: ``None`` (none), one :class:`Wall` or a sequence
    of them; ``TypeError`` about ``walls`` naming what else was given."""
    if walls is None:
        return []
    if isinstance(walls, Wall):
        return [walls]
    if isinstance(walls, (str, bytes, np.ndarray)) or not hasattr(walls, "__iter__"):
        raise refusal(TypeError, "walls",
                      f"walls must be an edmd2d.Wall or a sequence of them, got "
                      f"{type(walls).__name__}; for a polygon pass "
                      "walls=edmd2d.Wall.polygon(vertices)")
    items = list(walls)
    for k, w in enumerate(items):
        if not isinstance(w, Wall):
            raise refusal(TypeError, "walls",
                          f"walls[{k}] must be an edmd2d.Wall, got {type(w).__name__} "
                          f"({w!r}); for a polygon pass walls=edmd2d.Wall.polygon(vertices)")
    return items


# --------------------------------------------------------------------------- containers
# End points of two wall segments closer than this fraction of the box's larger side
# count as one vertex of a closed polygon (Wall.polygon repeats the vertex exactly;
# hand-built walls may differ by rounding).
_COINCIDE = 1e-9


def container(box: Box, walls: Sequence[Wall], centres: np.ndarray) -> tuple[float, str]:
    """The area of the container that holds the points ``centres`` in ``box``, among
    the wall segments ``walls``, and where it comes from.

    Closed polygons are found among ``walls``: loops of segments
    in which each end point coincides with that of exactly one other segment (to
    within ``1e-9`` of the box's larger side, as ``Wall.polygon`` builds them), that
    cross neither themselves nor each other.  They cut the box into regions: the inside
    of a polygon less the polygons directly inside it, and the box less the outermost
    polygons.  The result is the total area (shoelace formula) of the regions that
    hold a point of ``centres``: the box's area when no polygon is closed, the
    octagon's for a gas in an octagonal container, the octagon's less the triangle's
    when a triangular obstacle stands inside it, the box's less the triangle's for a
    gas around a closed obstacle.

    Open polylines and segments that branch (an end point shared by three or more
    segments) are left out: with the box walls or with each other they may close a
    region that this function does not see (then pass ``area=`` to
    :func:`edmd2d.measurements.measure`).  If two closed polygons cross or touch, no
    area can be told from them: the box's area is used, with a warning.

    Parameters
    ----------
    box : Box
    walls : sequence of Wall
    centres : ndarray, shape (P, 2)
        The points whose regions count (the centres of the movable disks).

    Returns
    -------
    area : float
    source : {"box", "walls"}
        ``"box"`` when no closed polygon bounds the regions of the points.
    """
    loops = _closed_loops(tuple(walls), _COINCIDE * max(box.width, box.height))
    if not loops:
        return box.area, "box"
    areas = np.array([abs(_shoelace(v)) for v in loops])
    # (Loops do not cross: one vertex tells whether a loop lies inside another.)
    first = np.array([v[0] for v in loops])
    inside = np.array([_inside_polygon(first, v) for v in loops])  # [a, b]: b inside a
    np.fill_diagonal(inside, False)
    # The region of a loop is its inside less that of its children: the loops inside
    # it and inside no smaller loop that is inside it.
    parent = np.full(len(loops), -1)
    for b in range(len(loops)):
        holders = np.flatnonzero(inside[:, b])
        if len(holders):
            parent[b] = holders[np.argmin(areas[holders])]
    region = areas.copy()
    outer = box.area
    for b in range(len(loops)):
        if parent[b] >= 0:
            region[parent[b]] -= areas[b]
        else:
            outer -= areas[b]
    # Each disk is in the region of the smallest loop that holds it (or outside all).
    if len(centres) == 0:  # (no gas to hold: the box's area, as without containers)
        return box.area, "box"
    holds = np.array([_inside_polygon(centres, v) for v in loops])  # (loops, disks)
    innermost = np.where(holds, areas[:, None], np.inf).argmin(axis=0)
    innermost[~holds.any(axis=0)] = -1
    occupied = np.unique(innermost)
    total = sum(outer if k < 0 else float(region[k]) for k in occupied)
    return float(total), "walls"


@functools.lru_cache(maxsize=16)
def _closed_loops(walls: tuple, tol: float) -> tuple[np.ndarray, ...]:
    """The closed polygons among ``walls`` (see :func:`container_area`), each as its
    vertices in order, shape (V, 2); none if two of them (or one with itself) cross
    or touch.  (Cached: a simulation's walls never change, and :func:`measure` may
    be called many times; the arrays returned are read-only.)"""
    # Vertex ids: end points within tol of each other share one (grid of side tol,
    # looked up in the 3 x 3 neighbouring cells).
    cells: dict[tuple[int, int], list[int]] = {}
    vertices: list[tuple[float, float]] = []
    ends = []
    for w in walls:
        for x, y in (w.start, w.end):
            key = (math.floor(x / tol), math.floor(y / tol))
            found = next((v for dx in (-1, 0, 1) for dy in (-1, 0, 1)
                          for v in cells.get((key[0] + dx, key[1] + dy), ())
                          if abs(vertices[v][0] - x) <= tol
                          and abs(vertices[v][1] - y) <= tol), -1)
            if found < 0:
                found = len(vertices)
                vertices.append((x, y))
                cells.setdefault(key, []).append(found)
            ends.append(found)
    edges = [(ends[2 * k], ends[2 * k + 1]) for k in range(len(walls))
             if ends[2 * k] != ends[2 * k + 1]]
    at: dict[int, list[int]] = {}
    for e, (u, v) in enumerate(edges):
        at.setdefault(u, []).append(e)
        at.setdefault(v, []).append(e)
    # Walk from each unvisited edge; a walk through vertices of two edges each that
    # comes back to its start is a loop.
    loops: list[np.ndarray] = []
    loop_edges: list[tuple[int, int]] = []
    seen = [False] * len(edges)
    for e0 in range(len(edges)):
        if seen[e0]:
            continue
        order, path = [edges[e0][0]], [e0]
        seen[e0] = True
        e, v, closed = e0, edges[e0][1], False
        while len(at[v]) == 2:
            if v == order[0]:
                closed = True
                break
            order.append(v)
            e = at[v][0] if at[v][1] == e else at[v][1]
            if seen[e]:
                break
            seen[e] = True
            path.append(e)
            v = edges[e][1] if edges[e][0] == v else edges[e][0]
        # (A walk that stops at an end point or a branch marks its edges seen: a loop
        # through a branch point is not simple and is left out.)
        if closed and len(order) >= 3 and len(at[order[0]]) == 2:
            loop = np.array([vertices[u] for u in order])
            loop.flags.writeable = False
            loops.append(loop)
            loop_edges.extend(edges[k] for k in path)
    if not loops:
        return ()
    if _any_crossing(np.array(vertices), loop_edges):
        warnings.warn(
            "closed loops of wall segments cross or touch: the container's area cannot be "
            "told from them, and the box's area is used; pass measure(area=...)",
            stacklevel=5,
        )
        return ()
    return tuple(loops)


def _any_crossing(vertices: np.ndarray, edges) -> bool:
    """Whether two of the segments ``edges`` (pairs of vertex ids) that share no vertex
    cross or touch."""
    u = np.array([e[0] for e in edges])
    v = np.array([e[1] for e in edges])
    a, b = vertices[u], vertices[v]

    def orient(p, q, r):  # (p, q: (m, 1, 2); r: (1, n, 2))
        return ((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1])
                - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))

    lo, hi = np.minimum(a, b), np.maximum(a, b)
    step = max(1, 2_000_000 // max(1, len(edges)))  # (rows per chunk: bounded memory)
    for s in range(0, len(edges), step):
        pa, pb = a[s:s + step, None], b[s:s + step, None]
        qa, qb = a[None], b[None]
        cross = ((orient(pa, pb, qa) * orient(pa, pb, qb) <= 0.0)
                 & (orient(qa, qb, pa) * orient(qa, qb, pb) <= 0.0)
                 # (collinear segments: the orientations vanish; overlap decides)
                 & (lo[s:s + step, None] <= hi[None]).all(axis=-1)
                 & (lo[None] <= hi[s:s + step, None]).all(axis=-1))
        share = ((u[s:s + step, None] == u[None]) | (u[s:s + step, None] == v[None])
                 | (v[s:s + step, None] == u[None]) | (v[s:s + step, None] == v[None]))
        if (cross & ~share).any():
            return True
    return False


def _shoelace(vertices: np.ndarray) -> float:
    """Signed area of a polygon (positive when counterclockwise)."""
    x, y = vertices[:, 0], vertices[:, 1]
    return 0.5 * float(dot(x, np.roll(y, -1)) - dot(np.roll(x, -1), y))


def _inside_polygon(points: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Whether each point (shape (P, 2)) lies inside the polygon (even-odd rule: a
    ray towards +x crosses its sides an odd number of times)."""
    x0, y0 = vertices[:, 0], vertices[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    out = np.zeros(len(points), bool)
    step = max(1, 2_000_000 // len(vertices))  # (points per chunk: bounded memory)
    for s in range(0, len(points), step):
        px = points[s:s + step, 0:1]
        py = points[s:s + step, 1:2]
        spans = (y0 > py) != (y1 > py)
        with np.errstate(divide="ignore", invalid="ignore"):
            x_cross = x0 + (py - y0) * (x1 - x0) / (y1 - y0)
        out[s:s + step] = (spans & (px < x_cross)).sum(axis=1) % 2 == 1
    return out
