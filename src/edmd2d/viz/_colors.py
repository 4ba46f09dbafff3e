"""What ``color_by`` means: per-disk values through a colour map, or fixed colours.

:class:`_ColorScheme` checks a ``color_by`` argument of :func:`~edmd2d.viz.draw` or
:func:`~edmd2d.viz.animate` once, before any figure is made, and then colours the disks
of every frame.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import matplotlib as mpl
import matplotlib.colors as mcolors
import numpy as np

from ..operations import Snapshot
from ..simulation import Simulation

_COLOR_MODES = ("speed", "species", "mass")
# Colour of disks whose value is NaN (e.g. immovable disks when colouring by mass).
_BAD_COLOR = "0.45"

ColorBy = str | Sequence | np.ndarray | Callable | None
# A matplotlib colour: a name or hex string ("C0", "0.15", "#1f77b4"), or RGB(A) floats.
Color = str | tuple[float, float, float] | tuple[float, float, float, float]


class _ColorScheme:
    """What ``color_by`` means: per-disk values through a colormap, or fixed colours."""

    def __init__(self, sim: Simulation | Snapshot, color_by, cmap, vmin, vmax,
                 color) -> None:
        n = len(sim)
        self.values_at: Callable[[Simulation | Snapshot], np.ndarray] | None = None
        self.values: np.ndarray | None = None
        self.rgba: np.ndarray | None = None
        self.label = ""
        self.name = repr(color_by) if isinstance(color_by, str) or color_by is None else (
            type(color_by).__name__)
        if isinstance(color_by, str):
            if color_by not in _COLOR_MODES:
                raise ValueError(
                    f"color_by must be one of {', '.join(map(repr, _COLOR_MODES))}, None, an "
                    f"array of N={n} numbers or colours, or a callable; got {color_by!r}"
                )
            if color_by == "speed":
                self.values_at = _speeds
                self.label = "speed"
                v = _speeds(sim)
                rms = float(np.sqrt(np.mean(v * v)))
                default_lo, default_hi = 0.0, (2.0 * rms if rms > 0 else 1.0)
            elif color_by == "mass":
                m = sim.masses
                self.values = np.where(np.isinf(m), np.nan, m)
                self.label = "mass"
                default_lo, default_hi = _finite_range(self.values)
            else:
                self.rgba = _species_colors(sim.radii, sim.masses)
        elif color_by is None:
            self.rgba = np.repeat(_as_rgba("color", color)[None, :], n, axis=0)
        elif callable(color_by):
            self.values_at = _checked_callable(color_by, n)
            v = self.values_at(sim)
            default_lo, default_hi = _finite_range(v)
        else:
            values, rgba = _array_colors(color_by, n)
            if rgba is not None:
                self.rgba = rgba
            else:
                self.values = values
                default_lo, default_hi = _finite_range(values)
        self.numeric = self.rgba is None
        if self.numeric:
            lo = default_lo if vmin is None else _as_real("vmin", vmin)
            hi = default_hi if vmax is None else _as_real("vmax", vmax)
            if not hi > lo:
                raise ValueError(f"vmax must be greater than vmin, got vmin={lo}, vmax={hi}")
            self.norm = mcolors.Normalize(lo, hi)
            self.cmap = mpl.colormaps.get_cmap(cmap).with_extremes(bad=_BAD_COLOR)

    def style(self, coll) -> None:
        if self.numeric:
            coll.set_cmap(self.cmap)
            coll.set_norm(self.norm)

    def apply(self, coll, sim: Simulation | Snapshot, idx: np.ndarray) -> None:
        if self.rgba is not None:  # (not numeric)
            coll.set_facecolor(self.rgba[idx])
            return
        values = self.values if self.values_at is None else self.values_at(sim)
        assert values is not None  # (numeric: values or values_at, from __init__)
        coll.set_array(values[idx])


def _speeds(sim: Simulation | Snapshot) -> np.ndarray:
    v = sim.velocities
    return np.hypot(v[:, 0], v[:, 1])


def _finite_range(values: np.ndarray) -> tuple[float, float]:
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return 0.0, 1.0
    lo, hi = float(finite.min()), float(finite.max())
    if hi == lo:  # a constant: centre it in the colour scale
        return lo - 0.5 * (abs(lo) or 1.0), hi + 0.5 * (abs(hi) or 1.0)
    return lo, hi


def _species_colors(radii: np.ndarray, masses: np.ndarray) -> np.ndarray:
    """One colour per distinct (radius, mass), classes ordered by radius then mass."""
    pairs = np.stack([radii, masses], axis=1)
    _, cls = np.unique(pairs, axis=0, return_inverse=True)
    cls = cls.ravel()
    k = int(cls.max()) + 1
    if k <= 20:
        listed = mpl.colormaps["tab10" if k <= 10 else "tab20"]
        assert isinstance(listed, mcolors.ListedColormap)  # (a list of colours)
        palette = np.asarray(listed.colors)[:k]
    else:
        palette = mpl.colormaps["viridis"](np.linspace(0, 1, k))
    return mcolors.to_rgba_array(palette)[cls]


def _array_colors(color_by, n: int):
    """A user array: ``(values, None)`` for N numbers, ``(None, rgba)`` for N colours."""
    arr = np.asarray(color_by)
    if arr.dtype.kind in "USO" and arr.ndim == 1:
        if len(arr) != n:
            raise ValueError(f"color_by has {len(arr)} colours but the simulation has {n} disks")
        try:
            return None, mcolors.to_rgba_array(list(arr))
        except ValueError as exc:
            raise ValueError(f"color_by: not a list of colours ({exc})") from None
    if arr.dtype.kind not in "biuf":
        raise TypeError(
            f"color_by must be 'speed', 'species', 'mass', None, a callable, or an array of "
            f"numbers or colours; got {type(color_by).__name__} of dtype {arr.dtype}"
        )
    if arr.ndim == 1:
        if len(arr) != n:
            raise ValueError(
                f"color_by must have one value per disk, shape ({n},); got shape {arr.shape}"
            )
        return arr.astype(np.float64), None
    if arr.ndim == 2 and arr.shape[0] == n and arr.shape[1] in (3, 4):
        try:
            return None, mcolors.to_rgba_array(arr.astype(np.float64))
        except ValueError as exc:
            raise ValueError(f"color_by: RGB(A) rows must lie in [0, 1] ({exc})") from None
    raise ValueError(
        f"color_by must have shape ({n},) for values or ({n}, 3)/({n}, 4) for colours; "
        f"got shape {arr.shape}"
    )


def _checked_callable(func, n: int):
    def values_at(sim):
        out = np.asarray(func(sim), dtype=np.float64)
        if out.shape != (n,):
            raise ValueError(
                f"color_by callable must return one number per disk, shape ({n},); "
                f"got shape {out.shape}"
            )
        return out

    return values_at


def _as_rgba(name: str, value) -> np.ndarray:
    try:
        return np.array(mcolors.to_rgba(value))
    except ValueError:
        raise ValueError(f"{name} must be a matplotlib colour, got {value!r}") from None


def _as_real(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__} {value!r}")
    value = float(value)
    if not np.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value}")
    return value
