"""The scene: the artists that draw one state of a simulation on one Axes (disks and
their periodic images, box edges, walls, trails, time label, colour bar), updated in
place from frame to frame, and :func:`draw`, which makes a still of it."""

from __future__ import annotations

import math
from collections import deque

import matplotlib as mpl
import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.collections import EllipseCollection, LineCollection
from matplotlib.transforms import Bbox, TransformedBbox

from .._validate import as_count, as_positive_float, indices_where
from ..operations import Snapshot
from ..simulation import Simulation
from ._colors import Color, ColorBy, _ColorScheme
from ._layout import (
    _FIG_EDGE,
    _LABEL_GAP_PT,
    _colorbar_beside,
    _figure_of,
    _figure_size,
    _label_fits,
    _label_height,
)

# Above this many disks the default drops the disk outlines: at a few pixels per disk they
# only darken the picture, and they roughly double the drawing time.
_OUTLINE_MAX_N = 3000


def draw(
    sim: Simulation | Snapshot,
    ax: Axes | None = None,
    *,
    color_by: ColorBy = "speed",
    cmap: str | mcolors.Colormap | None = None,
    vmin: float | None = None,
    vmax: float | None = None,
    color: Color = "C0",
    edgecolor: Color = "0.15",
    linewidth: float | None = None,
    wall_color: Color = "k",
    colorbar: bool = False,
    show_time: bool = False,
    margin: float = 0.02,
    figsize: tuple[float, float] | None = None,
    angle_marks: bool | None = None,
) -> Axes:
    """Draw the current state of ``sim`` (a still frame).

    Parameters
    ----------
    sim : Simulation or edmd2d.operations.Snapshot
        What to draw; it is only read, never advanced.
    ax : matplotlib Axes, optional
        Where to draw; a new figure sized to the box's aspect ratio by default.  The axes
        get an equal aspect, limits at the box plus ``margin``, and no ticks.
    color_by : {"speed", "species", "mass"}, array_like, callable or None
        ``"speed"``: ``|v|`` through ``cmap`` (default ``viridis``) from ``vmin`` (default
        0) to ``vmax`` (default twice the root-mean-square speed).  ``"species"``: one
        colour per distinct (radius, mass) class, ordered by radius then mass, from the
        ``tab10`` cycle.  ``"mass"``: mass through ``cmap``; immovable disks (``inf``)
        grey.  An array of N numbers is mapped through ``cmap``; an array of N colours
        (names, or RGB/RGBA rows of shape (N, 3) or (N, 4)) is used as is.  A callable
        ``f(sim) -> array of N numbers`` is evaluated at every frame.  ``None``: all
        disks in ``color``.
    cmap : str or Colormap, optional
        Colormap for numeric colourings.
    vmin, vmax : float, optional
        Colour scale limits for numeric colourings (kept fixed during an animation).
    color : colour, default "C0"
        Face colour when ``color_by`` is None.
    edgecolor : colour, default "0.15"
        Disk outline colour.
    linewidth : float, optional
        Disk outline width in points; default 0.4 up to 3000 disks, no outline above.
    wall_color : colour, default "k"
        Colour of wall segments and of walled box edges.
    colorbar : bool, default False
        Add a colour bar (numeric colourings only): right of the box, in a strip added
        to the width of the figure made here, so that the box keeps its size; in given
        axes, or with ``figsize``, it takes its share of the axes.
    show_time : bool, default False
        Write the time and the collision count above the box's upper left corner, in a
        strip added to the axes (the figure made here is taller by it).
    margin : float, default 0.02
        Space around the box, as a fraction of its larger side.
    figsize : (float, float), optional
        Figure size in inches when ``ax`` is None.
    angle_marks : bool, optional
        Rough disks (:class:`edmd2d.physics.Rough`): draw a radius of each disk at its
        angle, so that the turning shows (a line from the centre to the rim, in
        ``edgecolor``).  Default: for rough disks, up to 3000 disks.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.  Its collections carry the gids ``"edmd2d-disks"`` (the
        :class:`~matplotlib.collections.EllipseCollection`), ``"edmd2d-walls"`` and
        ``"edmd2d-box"`` (and ``"edmd2d-angles"``, the angle marks).

    Raises
    ------
    TypeError, ValueError
        For a non-Simulation ``sim``, an ``ax`` that is not an Axes, an unknown
        ``color_by`` or one of the wrong length, and the like.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import edmd2d as ed
    >>> from edmd2d import viz
    >>> ax = viz.draw(ed.make_gas(30, 0.3, seed=1), color_by="speed")
    >>> [c.get_gid() for c in ax.collections][:1]
    ['edmd2d-disks']
    """
    scene = _Scene(
        sim, ax, color_by=color_by, cmap=cmap, vmin=vmin, vmax=vmax, color=color,
        edgecolor=edgecolor, linewidth=linewidth, wall_color=wall_color, colorbar=colorbar,
        show_time=show_time, margin=margin, figsize=figsize, angle_marks=angle_marks,
    )
    scene.update()
    return scene.ax


class _Scene:
    """The artists that show one simulation on one Axes, and their per-frame update."""

    def __init__(
        self,
        sim: Simulation | Snapshot,
        ax: Axes | None = None,
        *,
        color_by: ColorBy = "speed",
        cmap=None,
        vmin: float | None = None,
        vmax: float | None = None,
        color="C0",
        edgecolor="0.15",
        linewidth: float | None = None,
        wall_color="k",
        colorbar: bool = False,
        show_time: bool = False,
        margin: float = 0.02,
        figsize: tuple[float, float] | None = None,
        trail: int = 0,
        trail_disks=None,
        trail_color="k",
        angle_marks: bool | None = None,
    ) -> None:
        if not isinstance(sim, (Simulation, Snapshot)):
            raise TypeError(f"sim must be an edmd2d.Simulation, got {type(sim).__name__}")
        if ax is not None and not isinstance(ax, Axes):
            raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
        margin = as_positive_float("margin", margin, allow_zero=True)
        trail = as_count("trail", trail)
        self.sim = sim
        box = sim.box
        self._size = box.size
        self._periodic = box.periodic
        diameters = 2.0 * sim.radii
        n = len(diameters)
        # Validate all colour options before any figure is made.
        self._color = _ColorScheme(sim, color_by, cmap, vmin, vmax, color)
        if linewidth is None:
            linewidth = 0.4 if n <= _OUTLINE_MAX_N else 0.0
        else:
            linewidth = as_positive_float("linewidth", linewidth, allow_zero=True)
        self._trail_sel = _trail_selection(trail_disks, n) if trail > 0 else None
        if colorbar and not self._color.numeric:
            raise ValueError(
                "colorbar=True needs a numeric colouring (speed, mass, an array of "
                f"numbers or a callable), not color_by={self._color.name}"
            )

        w, h = box.width, box.height
        pad = margin * max(w, h)
        label_font = mpl.font_manager.FontProperties(family="monospace", size="small")
        self._label_sep = "   "  # between time and collisions; a new line if narrow
        sized_here = ax is None and figsize is None  # (room for a colour bar is added)
        label = 0.0
        if ax is None:
            if figsize is None:
                label = _label_height(label_font, 1) if show_time else 0.0
                figsize = _figure_size(w + 2 * pad, h + 2 * pad, label)
                if show_time and not _label_fits(label_font, (1 - 2 * _FIG_EDGE) * figsize[0]):
                    label = _label_height(label_font, 2)
                    figsize = _figure_size(w + 2 * pad, h + 2 * pad, label)
            _fig, ax = plt.subplots(figsize=figsize)
            _fig.subplots_adjust(_FIG_EDGE, _FIG_EDGE, 1 - _FIG_EDGE, 1 - _FIG_EDGE)
        self.ax = ax
        ax.set_xlim(-pad, w + pad)
        ax.set_ylim(-pad, h + pad)
        ax.set_aspect("equal")
        ax.set_axis_off()
        # Everything inside the box is clipped to it (a Bbox clip is cheap in Agg).
        clip = TransformedBbox(Bbox([[0.0, 0.0], [w, h]]), ax.transData)

        self.disks = EllipseCollection(
            diameters, diameters, 0.0, units="xy", offsets=np.zeros((n, 2)),
            offset_transform=ax.transData, edgecolors=edgecolor, linewidths=linewidth,
            zorder=2,
        )
        self._color.style(self.disks)
        self.disks.set_gid("edmd2d-disks")
        ax.add_collection(self.disks, autolim=False)
        self.disks.set_clip_box(clip)

        rough = "rough" in getattr(sim, "families", {})
        if angle_marks is None:
            angle_marks = rough and n <= _OUTLINE_MAX_N
        elif angle_marks and not rough:
            raise ValueError("angle_marks needs rough disks (tangential_restitution): "
                             "smooth disks do not turn")
        self.marks = None
        if angle_marks:
            self.marks = LineCollection([], colors=edgecolor,
                                        linewidths=max(linewidth, 0.6), zorder=2.2)
            self.marks.set_gid("edmd2d-angles")
            ax.add_collection(self.marks, autolim=False)
            self.marks.set_clip_box(clip)

        self.trails = None
        if self._trail_sel is not None:
            self.trails = LineCollection([], linewidths=1.0, zorder=2.5, capstyle="round")
            self.trails.set_gid("edmd2d-trails")
            ax.add_collection(self.trails, autolim=False)
            self.trails.set_clip_box(clip)
            self._trail_rgba = np.array(mcolors.to_rgba(trail_color))
            self._trail_hist: deque = deque(maxlen=trail + 1)
            self._trail_t = -math.inf

        self.box_edges = _box_artist(box, wall_color)
        ax.add_collection(self.box_edges, autolim=False)
        self.walls = LineCollection(
            self._wall_segments(), colors=wall_color, linewidths=1.5,
            capstyle="round", zorder=3, clip_on=False,
        )
        self.walls.set_gid("edmd2d-walls")
        ax.add_collection(self.walls, autolim=False)
        self._wall_rgba = np.array(mcolors.to_rgba(wall_color))
        self._walls_open: np.ndarray | None = None
        self._style_open_walls()

        if colorbar and sized_here:
            _colorbar_beside(ax, self.disks, self._color.label, (w + 2 * pad, h + 2 * pad),
                             label)
        elif colorbar:  # (the caller's axes or figure size: the bar takes its share)
            ax.figure.colorbar(self.disks, ax=ax, shrink=0.8, label=self._color.label)
        self.text = None
        if show_time:
            # The label goes in a strip added above the box, inside the axes: it covers no
            # disk and no edge, and blitting (which redraws the axes' area) updates it.
            fw, fh = _figure_of(ax).get_size_inches()
            pos = ax.get_position(original=True)  # after the colour bar took its share
            bw, bh = w + 2 * pad, h + 2 * pad
            lines = 1 if _label_fits(label_font, pos.width * fw) else 2
            self._label_sep = "   " if lines == 1 else "\n"
            label_inches = _label_height(label_font, lines)
            scale = min(pos.width * fw / bw, (pos.height * fh - label_inches) / bh)
            if scale <= 0:  # axes too short for the strip: keep the width
                scale = pos.width * fw / bw
            ax.set_ylim(-pad, h + pad + label_inches / scale)
            # Anchored at the box's upper left corner and raised a few points (an offset in
            # display units, so that it does not depend on the data scale).
            self.text = ax.annotate(
                "", (0.0, h), xycoords="data", xytext=(0, _LABEL_GAP_PT),
                textcoords="offset points", ha="left", va="bottom", zorder=5,
                fontproperties=label_font, annotation_clip=False,
            )
            self.text.set_gid("edmd2d-text")

    def reset(self) -> None:
        """Forget the trails (an animation of recorded frames starting again)."""
        if self.trails is not None:
            self._trail_hist.clear()
            self._trail_t = -math.inf

    def update(self) -> list:
        """Show the simulation's current state; returns the artists that changed."""
        sim = self.sim
        pos = sim.positions
        rad = sim.radii  # (read afresh: growing disks change size)
        idx, offsets = _with_periodic_images(pos, rad, self._size, self._periodic,
                                             getattr(sim, "shear_offset", 0.0))
        self.disks.set_offsets(offsets)
        diam = 2.0 * rad[idx]
        self.disks.set_widths(diam)
        self.disks.set_heights(diam)
        self._color.apply(self.disks, sim, idx)
        changed: list[Artist] = [self.disks]
        if self.marks is not None:
            # A radius of each drawn disk (and image) at the disk's angle.
            theta = np.asarray(sim.angles)[idx]
            rim = offsets + 0.5 * diam[:, None] * np.column_stack([np.cos(theta),
                                                                   np.sin(theta)])
            self.marks.set_segments(list(np.stack([offsets, rim], axis=1)))
            changed.append(self.marks)
        if self._style_open_walls():
            changed.append(self.walls)
        if "moving_walls" in getattr(sim, "families", {}):
            self.walls.set_segments(self._wall_segments())  # (where they are now)
            changed.append(self.walls)
        if self.trails is not None:
            self._update_trails(pos)
            changed.append(self.trails)
        if self.text is not None:
            self.text.set_text(
                f"t = {sim.time:.2f}{self._label_sep}collisions {sim.counts.collisions:,}")
            changed.append(self.text)
        return changed

    def _wall_segments(self) -> list:
        """The wall segments where they are now (``Simulation.wall_positions``: moving
        segments move), as pairs of points."""
        where = getattr(self.sim, "wall_positions", None)
        if where is None:
            return [[w_.start, w_.end] for w_ in self.sim.walls]
        return list(np.asarray(where))

    def _style_open_walls(self) -> bool:
        """Draw the open wall segments (``Simulation.open_walls``) faint and dashed;
        returns whether their style changed."""
        is_open = getattr(self.sim, "open_walls", None)
        if is_open is None or len(is_open) == 0 or (
                self._walls_open is not None and np.array_equal(is_open, self._walls_open)):
            return False
        self._walls_open = np.array(is_open)
        colors = np.tile(self._wall_rgba, (len(is_open), 1))
        colors[is_open, 3] *= 0.3
        self.walls.set_color(colors)  # type: ignore[arg-type]  # (RGBA rows)
        self.walls.set_linestyle([(0, (3, 3)) if o else "solid" for o in is_open])
        return True

    def _update_trails(self, pos: np.ndarray) -> None:
        assert self.trails is not None  # (called only where there are trails)
        sel = self._trail_sel
        unwrapped = self.sim.unwrapped_positions[sel]
        # Offset from unwrapped to wrapped coordinates: a whole number of box lengths
        # (along x of a sheared box, also the images' offset times the boxes crossed
        # along y: the frame of the box then slides, at -U per box crossed upwards).
        shift = np.round((pos[sel] - unwrapped) / self._size) * self._size
        speed = _shear_speed(self.sim)
        if speed != 0.0:
            shift[:, 0] = pos[sel, 0] - unwrapped[:, 0]
        entry = (unwrapped, shift, -shift[:, 1] / self._size[1] * speed, self.sim.time)
        if self._trail_hist and self.sim.time == self._trail_t:
            self._trail_hist[-1] = entry
        else:
            self._trail_hist.append(entry)
        self._trail_t = self.sim.time
        hist = list(self._trail_hist)
        n_seg = len(hist) - 1
        paths = []
        for j in range(n_seg):
            (a, sa, ua, ta), (b, sb, ub, tb) = hist[j], hist[j + 1]
            # Each step is drawn continuously in the frame of its end point, so a step that
            # crosses a periodic edge runs out of the box (and is clipped there) instead of
            # spanning the whole box; a second copy in the frame of its start point shows
            # the part on the other side.  (A sheared frame slides at u: the start point
            # in the end point's frame lies u dt further along x.)
            dt = tb - ta
            start_parts = [a + sb + np.column_stack([ub * dt, np.zeros(len(ub))])]
            end_parts = [b + sb]
            # (Wrapped: the box crossed along y, or a width along x beyond the
            # frame's slide.)
            wrapped = (sa[:, 1] != sb[:, 1]) | (
                np.abs(sa[:, 0] - sb[:, 0] - ub * dt) > 0.5 * self._size[0])
            if wrapped.any():
                start_parts.append(a[wrapped] + sa[wrapped])
                end_parts.append(b[wrapped] + sa[wrapped]
                                 - np.column_stack([ua[wrapped] * dt, np.zeros(wrapped.sum())]))
            # All steps of one age share a colour, so they make one path: (start, end, NaN)
            # rows, and Agg lifts the pen at each NaN.  One Path per age instead of one
            # per step cuts the trail's cost per frame from 17 ms to 4 ms at 1000 disks.
            starts, ends = np.concatenate(start_parts), np.concatenate(end_parts)
            verts = np.full((len(starts), 3, 2), np.nan)
            verts[:, 0] = starts
            verts[:, 1] = ends
            paths.append(verts.reshape(-1, 2))
        rgba = np.repeat(self._trail_rgba[None, :], n_seg, axis=0)
        rgba[:, 3] *= np.arange(1, n_seg + 1) / max(n_seg, 1)  # older steps fade out
        self.trails.set_segments(paths)
        # (RGBA rows, one per segment, which matplotlib takes though its stubs name
        # only sequences of colours)
        self.trails.set_color(rgba)  # type: ignore[arg-type]


def _with_periodic_images(pos, rad, size, periodic, offset=0.0):
    """Disk indices and centres to draw: every disk, then images across periodic edges.

    A disk closer than its radius to a periodic edge also shows on the opposite side, and
    one near a corner of a fully periodic box in all four corners.  One image per axis is
    enough because a periodic length is at least one diameter.  In a sheared box
    (``offset``: the images above shifted along x, see ``Simulation.shear_offset``) a
    disk near the bottom shows above shifted by ``offset``, one near the top below
    shifted by ``-offset``, and those images near a side also on the other side.
    """
    if offset != 0.0:
        return _with_sheared_images(pos, rad, size, offset)
    n = len(pos)
    shift = np.zeros((n, 2))
    for axis in (0, 1):
        if periodic[axis]:
            c = pos[:, axis]
            shift[c < rad, axis] = size[axis]
            shift[c > size[axis] - rad, axis] = -size[axis]
    has_x, has_y = shift[:, 0] != 0, shift[:, 1] != 0
    if not (has_x.any() or has_y.any()):
        return np.arange(n), pos
    ix, iy, ixy = np.flatnonzero(has_x), np.flatnonzero(has_y), np.flatnonzero(has_x & has_y)
    idx = np.concatenate([np.arange(n), ix, iy, ixy])
    offsets = np.concatenate([
        pos,
        pos[ix] + shift[ix] * [1.0, 0.0],
        pos[iy] + shift[iy] * [0.0, 1.0],
        pos[ixy] + shift[ixy],
    ])
    return idx, offsets


def _shear_speed(sim) -> float:
    """``U = rate * height`` of a sheared simulation: how fast the images above slide
    (0.0 without shear, or for what has no physics families)."""
    shear = getattr(sim, "families", {}).get("shear")
    return 0.0 if shear is None else shear.rate * sim.box.height


def _with_sheared_images(pos, rad, size, offset):
    """:func:`_with_periodic_images` for a box sheared at ``offset`` (periodic on both
    axes)."""
    width, height = size
    n = len(pos)
    low = np.flatnonzero(pos[:, 1] < rad)
    high = np.flatnonzero(pos[:, 1] > height - rad)
    idx = np.concatenate([np.arange(n), low, high])
    centres = np.concatenate([
        pos,
        np.column_stack([(pos[low, 0] + offset) % width, pos[low, 1] + height]),
        np.column_stack([(pos[high, 0] - offset) % width, pos[high, 1] - height]),
    ])
    r = rad[idx]
    left = np.flatnonzero(centres[:, 0] < r)
    right = np.flatnonzero(centres[:, 0] > width - r)
    idx = np.concatenate([idx, idx[left], idx[right]])
    centres = np.concatenate([centres, centres[left] + [width, 0.0],
                              centres[right] - [width, 0.0]])
    return idx, centres


def _box_artist(box, wall_color) -> LineCollection:
    """The four box edges: solid where walled, dashed where periodic."""
    w, h = box.width, box.height
    edges = [  # (segment, periodic?) for x=0, x=width, y=0, y=height
        ([(0, 0), (0, h)], box.periodic[0]),
        ([(w, 0), (w, h)], box.periodic[0]),
        ([(0, 0), (w, 0)], box.periodic[1]),
        ([(0, h), (w, h)], box.periodic[1]),
    ]
    wall_rgba = mcolors.to_rgba(wall_color)
    coll = LineCollection(
        [seg for seg, _ in edges],
        colors=[mcolors.to_rgba("0.6") if p else wall_rgba for _, p in edges],
        linestyles=["--" if p else "-" for _, p in edges],
        linewidths=[0.8 if p else 1.5 for _, p in edges],
        capstyle="projecting", zorder=3, clip_on=False,
    )
    coll.set_gid("edmd2d-box")
    return coll


def _trail_selection(trail_disks, n: int) -> np.ndarray:
    if trail_disks is None:
        return np.arange(n)
    arr = np.asarray(trail_disks)
    if arr.dtype == bool:
        if arr.shape != (n,):
            raise ValueError(f"trail_disks as a mask must have shape ({n},), got {arr.shape}")
        return np.flatnonzero(arr)
    if arr.dtype.kind not in "iu" or arr.ndim > 1:
        raise TypeError(
            "trail_disks must be a disk index, a list of indices or a boolean mask; "
            f"got {trail_disks!r}"
        )
    arr = np.atleast_1d(arr).astype(np.int64)
    bad = (arr < 0) | (arr >= n)
    if bad.any():
        raise ValueError(
            f"trail_disks: indices {arr[bad][:10].tolist()} are out of range for {n} disks "
            f"(entries {indices_where(bad)})"
        )
    return np.unique(arr)
