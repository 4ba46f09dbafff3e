"""Value objects for the container: the rectangular :class:`Box` and wall :class:`Wall` segments."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._validate import as_float_array, as_positive_float

__all__ = ["Box", "Wall", "BOX_WALLS", "BOX_WALL_EQUATIONS"]

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

    def __init__(self, width: float, height: float, periodic=True) -> None:
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

    def __init__(self, start, end) -> None:
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
    def polygon(cls, vertices, closed: bool = True) -> list[Wall]:
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
