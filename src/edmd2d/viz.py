"""Pictures and animations of a :class:`~edmd2d.Simulation` with matplotlib.

This is the only module of edmd2d that imports matplotlib (``pip install 'edmd2d[viz]'``;
``import edmd2d`` alone never does).  Three functions:

- :func:`draw` -- a still frame of the current state;
- :func:`animate` -- a :class:`matplotlib.animation.FuncAnimation` that advances the
  simulation to exact, equally spaced frame times (``sim.advance(until=t_k)``);
- :func:`save` -- write an animation to ``.gif`` (Pillow) or ``.mp4`` (ffmpeg, found on the
  PATH or supplied by ``pip install 'edmd2d[video]'``), or a still to ``.png``/``.pdf``/...,
  with a text progress bar.

Disks are drawn at their true size in data units by a single
:class:`~matplotlib.collections.EllipseCollection` whose offsets, sizes and colours are
updated in place every frame, so thousands of disks stay cheap.  Its first ``N`` entries
are the disks in order; after them come the periodic images of disks that straddle a
periodic edge, so that such a disk is seen on both sides.  Box edges are drawn solid where
walled and dashed where periodic; wall segments are drawn solid on top of the disks.

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import edmd2d as ed
>>> from edmd2d import viz
>>> sim = ed.make_gas(50, 0.3, seed=1)
>>> ax = viz.draw(sim, color_by="speed")
>>> anim = viz.animate(sim, duration=0.5, fps=10)
>>> len(anim.frame_times)
6
>>> viz.save(anim, "gas.gif", progress=False)  # doctest: +SKIP
"""

from __future__ import annotations

import io
import math
import shutil
import sys
import time as _time
from collections import deque
from collections.abc import Callable, Sequence
from pathlib import Path

try:
    import matplotlib as mpl
except ModuleNotFoundError as exc:  # (an optional dependency: say which extra brings it)
    raise ModuleNotFoundError(
        "edmd2d.viz needs matplotlib, which is not installed: pip install 'edmd2d[viz]' "
        "(or 'edmd2d[video]' for .mp4 output), or pip install matplotlib pillow",
        name=exc.name,
    ) from exc
import matplotlib.animation as manim
import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import EllipseCollection, LineCollection
from matplotlib.transforms import Bbox, TransformedBbox

from ._validate import as_count, as_positive_float, indices_where
from .simulation import Simulation

__all__ = ["draw", "animate", "save", "SimulationAnimation", "TextProgress"]

_COLOR_MODES = ("speed", "species", "mass")
_VIDEO_SUFFIXES = (".mp4", ".m4v", ".mov", ".mkv")
_GIF_SUFFIXES = (".gif",)
# Above this many disks the default drops the disk outlines: at a few pixels per disk they
# only darken the picture, and they roughly double the drawing time.
_OUTLINE_MAX_N = 3000
# Colour of disks whose value is NaN (e.g. immovable disks when colouring by mass).
_BAD_COLOR = "0.45"

ColorBy = str | Sequence | np.ndarray | Callable | None


# ---------------------------------------------------------------------- public API
def draw(
    sim: Simulation,
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
) -> Axes:
    """Draw the current state of ``sim`` (a still frame).

    Parameters
    ----------
    sim : Simulation
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
        Add a colour bar (numeric colourings only).
    show_time : bool, default False
        Write the time and the collision count in the upper left corner.
    margin : float, default 0.02
        Space around the box, as a fraction of its larger side.
    figsize : (float, float), optional
        Figure size in inches when ``ax`` is None.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.  Its collections carry the gids ``"edmd2d-disks"`` (the
        :class:`~matplotlib.collections.EllipseCollection`), ``"edmd2d-walls"`` and
        ``"edmd2d-box"``.

    Raises
    ------
    TypeError, ValueError
        For a non-Simulation ``sim``, an ``ax`` that is not an Axes, an unknown
        ``color_by`` or one of the wrong length, and the like.
    """
    scene = _Scene(
        sim, ax, color_by=color_by, cmap=cmap, vmin=vmin, vmax=vmax, color=color,
        edgecolor=edgecolor, linewidth=linewidth, wall_color=wall_color, colorbar=colorbar,
        show_time=show_time, margin=margin, figsize=figsize,
    )
    scene.update()
    return scene.ax


def animate(
    sim: Simulation,
    duration: float,
    fps: float = 30,
    *,
    color_by: ColorBy = "speed",
    trail: int = 0,
    trail_disks=None,
    trail_color="k",
    show_time: bool = True,
    time_per_second: float = 1.0,
    ax: Axes | None = None,
    blit: bool = True,
    **style,
) -> SimulationAnimation:
    """An animation that runs ``sim`` forward for ``duration`` and shows every frame.

    Frame ``k`` shows the state at the exact time ``t_k = t_0 + k * dt`` with
    ``dt = time_per_second / fps`` and ``t_0`` the simulation time when ``animate`` is
    called; ``k = 0 .. n`` with ``n = round(duration / dt)``, so there are ``n + 1``
    frames and, once they have all been drawn (shown or saved), ``sim.time == t_0 + n*dt``.
    Between frames the simulation is advanced with ``sim.advance(until=t_k)``: every
    collision in between is processed, none is skipped by the frame rate.

    The simulation only runs forward, so an animation can be played or saved once; to
    render it again, build the simulation and the animation anew.

    Parameters
    ----------
    sim : Simulation
        Advanced in place, frame by frame, as the animation is drawn.
    duration : float
        Simulation time to show, > 0 (rounded to a whole number of frames, at least one).
    fps : float, default 30
        Frames per second of animation (and the playback rate).
    color_by : {"speed", "species", "mass"}, array_like, callable or None
        As for :func:`draw`; ``"speed"`` follows the disks' speeds frame by frame.
    trail : int, default 0
        Draw a trail through each disk's positions in the last ``trail`` frames, fading
        with age.  Trails are broken where a disk wraps across a periodic edge.
    trail_disks : int, array_like of int or bool mask, optional
        Which disks get a trail (all by default when ``trail > 0``).
    trail_color : colour, default "k"
        Colour of the trails.
    show_time : bool, default True
        Write the time and the collision count in the upper left corner.
    time_per_second : float, default 1.0
        Simulation time shown per second of animation.
    ax : matplotlib Axes, optional
        Where to draw; a new figure by default.
    blit : bool, default True
        Let interactive backends redraw only the moving artists.
    **style
        Further keywords of :func:`draw` (``cmap``, ``vmin``, ``vmax``, ``color``,
        ``edgecolor``, ``linewidth``, ``wall_color``, ``colorbar``, ``margin``,
        ``figsize``).

    Returns
    -------
    SimulationAnimation
        A :class:`matplotlib.animation.FuncAnimation`; save it with :func:`save` (or
        its own ``save`` method for ``.gif``, or ``.mp4`` with a system ffmpeg), show it
        with ``plt.show()``, or embed it in a notebook with ``anim.to_jshtml()``.

    Raises
    ------
    TypeError, ValueError
        For invalid arguments (as for :func:`draw`, plus a non-positive ``duration``,
        ``fps`` or ``time_per_second``, a negative ``trail``, out-of-range
        ``trail_disks`` and unknown keywords).
    """
    if not isinstance(sim, Simulation):
        raise TypeError(f"sim must be an edmd2d.Simulation, got {type(sim).__name__}")
    duration = as_positive_float("duration", duration)
    fps = as_positive_float("fps", fps)
    time_per_second = as_positive_float("time_per_second", time_per_second)
    trail = as_count("trail", trail)
    dt = time_per_second / fps
    n_steps = max(1, round(duration / dt))
    # Frame times from the index, not by accumulation, so that rounding never piles up.
    frame_times = sim.time + dt * np.arange(n_steps + 1)
    scene = _Scene(sim, ax, color_by=color_by, trail=trail, trail_disks=trail_disks,
                   trail_color=trail_color, show_time=show_time, **style)
    return SimulationAnimation(scene, frame_times, fps, blit=blit)


class SimulationAnimation(manim.FuncAnimation):
    """The animation made by :func:`animate` (a :class:`~matplotlib.animation.FuncAnimation`).

    Attributes
    ----------
    sim : Simulation
        The simulation being shown (advanced as frames are drawn).
    frame_times : numpy.ndarray
        Simulation time of each frame.
    fps : float
        Frames per second.
    ax : matplotlib Axes
        The axes drawn on.
    """

    def __init__(self, scene: _Scene, frame_times: np.ndarray, fps: float, *, blit: bool):
        self._scene = scene
        self.sim = scene.sim
        self.ax = scene.ax
        self.frame_times = frame_times
        self.fps = fps
        super().__init__(
            scene.ax.figure, self.goto_frame, frames=len(frame_times),
            init_func=scene.update, interval=1000.0 / fps, repeat=False, blit=blit,
            cache_frame_data=False,
        )

    def goto_frame(self, k: int) -> list:
        """Advance the simulation to frame ``k``'s time and update the artists.

        This is what the animation calls for each frame; it does not redraw the canvas.
        Returns the artists that changed.

        Raises
        ------
        RuntimeError
            If the simulation is already past that time (the animation was played or
            saved before, or the simulation was advanced elsewhere).
        """
        self._check_can_start(k)
        self.sim.advance(until=float(self.frame_times[k]))
        return self._scene.update()

    def _check_can_start(self, k: int = 0) -> None:
        t = float(self.frame_times[k])
        if t < self.sim.time:
            raise RuntimeError(
                f"frame {k} is at t={t} but the simulation is already at t={self.sim.time}: "
                "simulations only run forward, so an animation can be played or saved once. "
                "Build the simulation and the animation again to render it anew."
            )


def save(
    obj,
    path,
    *,
    fps: float | None = None,
    dpi: float | None = None,
    progress: bool | Callable[[int, int | None], None] = True,
    **kwargs,
) -> Path:
    """Write an animation to a video or GIF, or a simulation's current state to an image.

    Parameters
    ----------
    obj : SimulationAnimation, matplotlib Animation or Simulation
        An animation is rendered frame by frame (running its simulation forward); a
        simulation is drawn with :func:`draw` and saved as a still.
    path : str or Path
        For an animation ``.gif`` (written with Pillow) or ``.mp4``/``.m4v``/``.mov``/
        ``.mkv`` (H.264 through ffmpeg: the ``ffmpeg`` on the PATH, or else the binary
        of the ``imageio-ffmpeg`` package, ``pip install 'edmd2d[video]'``).  For a
        simulation any format matplotlib's ``savefig`` knows (``.png``, ``.pdf``, ``.svg``).
    fps : float, optional
        Frames per second of the file; default the animation's own.
    dpi : float, optional
        Resolution; default the figure's.
    progress : bool or callable, default True
        For animations: print a progress bar to stderr (``True``), nothing (``False``),
        or call ``progress(frame_index, total_frames)`` after each frame.
    **kwargs
        For a simulation, keywords of :func:`draw`; for an animation, keywords of
        :meth:`matplotlib.animation.Animation.save` (e.g. ``bitrate``, ``codec``,
        ``writer``).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    TypeError
        For an ``obj`` that is neither an animation nor a simulation.
    ValueError
        For a file suffix that cannot hold the object.
    RuntimeError
        For a video when no ffmpeg can be found (with the command that installs one).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if isinstance(obj, Simulation):
        if suffix in _VIDEO_SUFFIXES + _GIF_SUFFIXES:
            raise ValueError(
                f"{path.name}: a Simulation is saved as a still image (.png, .pdf, .svg); "
                "for a video pass viz.animate(sim, duration) instead"
            )
        ax = draw(obj, **kwargs)
        try:
            ax.figure.savefig(path, dpi=dpi)
        finally:
            plt.close(ax.figure)
        return path
    if not isinstance(obj, manim.Animation):
        raise TypeError(
            f"save() takes an animation from viz.animate() or a Simulation, "
            f"got {type(obj).__name__}"
        )
    if isinstance(obj, SimulationAnimation):
        obj._check_can_start()
    if fps is None:
        # ours carry fps; any other matplotlib animation has its frame interval in ms
        fps = getattr(obj, "fps", None) or 1000.0 / getattr(obj, "_interval", 200)
    else:
        fps = as_positive_float("fps", fps)
    if progress is True:
        callback = TextProgress()
    elif progress is False or progress is None:
        callback = None
    elif callable(progress):
        callback = progress
    else:
        raise TypeError(f"progress must be True, False or a callable, got {progress!r}")

    writer = kwargs.pop("writer", None)
    rc = {}
    if writer is None:
        if suffix in _GIF_SUFFIXES:
            writer = _GifWriter(fps=fps)
            fps = None  # given to the writer; matplotlib refuses it twice
        elif suffix in _VIDEO_SUFFIXES:
            exe = _ffmpeg_executable(path.name)
            if exe is not None:
                rc["animation.ffmpeg_path"] = exe
            writer = "ffmpeg"
        else:
            raise ValueError(
                f"{path.name}: cannot tell how to write an animation to {suffix!r}; "
                f"use one of {', '.join(_GIF_SUFFIXES + _VIDEO_SUFFIXES)}"
            )
    with mpl.rc_context(rc):
        obj.save(path, writer=writer, fps=fps, dpi=dpi, progress_callback=callback, **kwargs)
    return path


class _GifWriter(manim.AbstractMovieWriter):
    """GIF through Pillow, keeping each frame as 8-bit palette image as it is grabbed.

    Unlike matplotlib's ``PillowWriter`` (which keeps full RGBA frames until the end and
    quantizes them then), this holds one byte per pixel, so long renders of large systems
    need a quarter of the memory, and the fast octree quantizer keeps the cost per frame
    at a few milliseconds.  Frames are opaque (the figure background is used).
    """

    @classmethod
    def isAvailable(cls) -> bool:
        return True

    def setup(self, fig, outfile, dpi=None) -> None:
        super().setup(fig, outfile, dpi=dpi)
        self._frames: list = []

    def grab_frame(self, **savefig_kwargs) -> None:
        from PIL import Image

        buf = io.BytesIO()
        self.fig.savefig(buf, **{**savefig_kwargs, "format": "rgba", "dpi": self.dpi})
        rgba = Image.frombuffer("RGBA", self.frame_size, buf.getbuffer(), "raw", "RGBA", 0, 1)
        self._frames.append(rgba.convert("RGB").quantize(256, Image.Quantize.FASTOCTREE))

    def finish(self) -> None:
        if not self._frames:  # nothing was drawn (an error while rendering): no file
            return
        # GIF stores delays in hundredths of a second.
        self._frames[0].save(self.outfile, save_all=True, append_images=self._frames[1:],
                             duration=round(1000.0 / self.fps), loop=0)
        self._frames = []


class TextProgress:
    """A text progress bar for :func:`save`: ``progress(frame_index, total_frames)``.

    On a terminal the bar is redrawn in place (at most ten times a second); elsewhere
    (a log file, CI) a line is printed at every tenth of the way.

    Parameters
    ----------
    stream : file-like, optional
        Where to write; ``sys.stderr`` by default.
    width : int, default 30
        Characters in the bar.
    """

    def __init__(self, stream=None, width: int = 30) -> None:
        self.stream = sys.stderr if stream is None else stream
        self.width = as_count("width", width)
        self._start: float | None = None
        self._last_print = -math.inf
        self._last_tenth = -1

    def __call__(self, i: int, n: int | None) -> None:
        now = _time.perf_counter()
        if self._start is None:
            self._start = now
        done = i + 1
        elapsed = now - self._start
        is_tty = getattr(self.stream, "isatty", lambda: False)()
        last = n is not None and done >= n
        if n is None:
            line = f"frame {done}  {elapsed:.1f} s"
            tenth = done // 10
        else:
            frac = min(done / n, 1.0)
            filled = int(round(frac * self.width))
            eta = elapsed / done * (n - done) if done else 0.0
            bar = "#" * filled + "-" * (self.width - filled)
            line = f"[{bar}] {done}/{n} frames  {elapsed:.1f} s, ~{eta:.0f} s left"
            tenth = int(frac * 10)
        if is_tty:
            if last or now - self._last_print >= 0.1:
                self.stream.write("\r" + line + ("\n" if last else ""))
                self.stream.flush()
                self._last_print = now
        elif tenth > self._last_tenth or last:
            self._last_tenth = tenth
            self.stream.write(line + "\n")
            self.stream.flush()


# ---------------------------------------------------------------------- the scene
class _Scene:
    """The artists that show one simulation on one Axes, and their per-frame update."""

    def __init__(
        self,
        sim: Simulation,
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
    ) -> None:
        if not isinstance(sim, Simulation):
            raise TypeError(f"sim must be an edmd2d.Simulation, got {type(sim).__name__}")
        if ax is not None and not isinstance(ax, Axes):
            raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
        margin = as_positive_float("margin", margin, allow_zero=True)
        trail = as_count("trail", trail)
        self.sim = sim
        box = sim.box
        self._size = box.size
        self._periodic = box.periodic
        self._diam = 2.0 * sim.radii
        self._rad = sim.radii
        n = len(self._diam)
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

        if ax is None:
            _fig, ax = plt.subplots(figsize=figsize or _figure_size(box.width, box.height))
            _fig.subplots_adjust(0.01, 0.01, 0.99, 0.99)
        self.ax = ax
        w, h = box.width, box.height
        pad = margin * max(w, h)
        ax.set_xlim(-pad, w + pad)
        ax.set_ylim(-pad, h + pad)
        ax.set_aspect("equal")
        ax.set_axis_off()
        # Everything inside the box is clipped to it (a Bbox clip is cheap in Agg).
        clip = TransformedBbox(Bbox([[0.0, 0.0], [w, h]]), ax.transData)

        self.disks = EllipseCollection(
            self._diam, self._diam, 0.0, units="xy", offsets=np.zeros((n, 2)),
            offset_transform=ax.transData, edgecolors=edgecolor, linewidths=linewidth,
            zorder=2,
        )
        self._color.style(self.disks)
        self.disks.set_gid("edmd2d-disks")
        ax.add_collection(self.disks, autolim=False)
        self.disks.set_clip_box(clip)

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
            [[w_.start, w_.end] for w_ in sim.walls], colors=wall_color, linewidths=1.5,
            capstyle="round", zorder=3, clip_on=False,
        )
        self.walls.set_gid("edmd2d-walls")
        ax.add_collection(self.walls, autolim=False)

        self.text = None
        if show_time:
            self.text = ax.text(
                0.02, 0.98, "", transform=ax.transAxes, ha="left", va="top", zorder=5,
                fontsize="small", family="monospace",
                bbox={"boxstyle": "round,pad=0.3", "fc": "white", "ec": "none", "alpha": 0.75},
            )
            self.text.set_gid("edmd2d-text")
        if colorbar:
            ax.figure.colorbar(self.disks, ax=ax, shrink=0.8, label=self._color.label)

    def update(self) -> list:
        """Show the simulation's current state; returns the artists that changed."""
        sim = self.sim
        pos = sim.positions
        idx, offsets = _with_periodic_images(pos, self._rad, self._size, self._periodic)
        self.disks.set_offsets(offsets)
        diam = self._diam[idx]
        self.disks.set_widths(diam)
        self.disks.set_heights(diam)
        self._color.apply(self.disks, sim, idx)
        changed = [self.disks]
        if self.trails is not None:
            self._update_trails(pos)
            changed.append(self.trails)
        if self.text is not None:
            self.text.set_text(f"t = {sim.time:.2f}\ncollisions {sim.counts.collisions:,}")
            changed.append(self.text)
        return changed

    def _update_trails(self, pos: np.ndarray) -> None:
        sel = self._trail_sel
        unwrapped = self.sim.unwrapped_positions[sel]
        # Offset from unwrapped to wrapped coordinates: a whole number of box lengths.
        shift = np.round((pos[sel] - unwrapped) / self._size) * self._size
        entry = (unwrapped, shift)
        if self._trail_hist and self.sim.time == self._trail_t:
            self._trail_hist[-1] = entry
        else:
            self._trail_hist.append(entry)
        self._trail_t = self.sim.time
        hist = list(self._trail_hist)
        if len(hist) < 2:
            self.trails.set_segments(np.zeros((0, 2, 2)))
            return
        segs, ages = [], []
        n_seg = len(hist) - 1
        for j in range(n_seg):
            (a, sa), (b, sb) = hist[j], hist[j + 1]
            # Each step is drawn continuously in the frame of its end point, so a step that
            # crosses a periodic edge runs out of the box (and is clipped there) instead of
            # spanning the whole box; a second copy in the frame of its start point shows
            # the part on the other side.
            segs.append(np.stack([a + sb, b + sb], axis=1))
            ages.append(np.full(len(a), j))
            wrapped = (sa != sb).any(axis=1)
            if wrapped.any():
                segs.append(np.stack([a[wrapped] + sa[wrapped], b[wrapped] + sa[wrapped]], axis=1))
                ages.append(np.full(int(wrapped.sum()), j))
        segments = np.concatenate(segs)
        age = np.concatenate(ages)
        rgba = np.repeat(self._trail_rgba[None, :], len(segments), axis=0)
        rgba[:, 3] *= (age + 1) / n_seg  # older steps fade out
        self.trails.set_segments(segments)
        self.trails.set_color(rgba)


class _ColorScheme:
    """What ``color_by`` means: per-disk values through a colormap, or fixed colours."""

    def __init__(self, sim: Simulation, color_by, cmap, vmin, vmax, color) -> None:
        n = len(sim)
        self.values_at: Callable[[Simulation], np.ndarray] | None = None
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

    def apply(self, coll, sim: Simulation, idx: np.ndarray) -> None:
        if not self.numeric:
            coll.set_facecolor(self.rgba[idx])
            return
        values = self.values if self.values_at is None else self.values_at(sim)
        coll.set_array(values[idx])


# ---------------------------------------------------------------------- helpers
def _with_periodic_images(pos, rad, size, periodic):
    """Disk indices and centres to draw: every disk, then images across periodic edges.

    A disk closer than its radius to a periodic edge also shows on the opposite side, and
    one near a corner of a fully periodic box in all four corners.  One image per axis is
    enough because a periodic length is at least one diameter.
    """
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


def _figure_size(width: float, height: float) -> tuple[float, float]:
    """About 6.4 inches on the longer side, keeping the box's aspect ratio."""
    aspect = width / height
    if aspect >= 1:
        return 6.4, max(6.4 / aspect, 1.5)
    return max(6.4 * aspect, 1.5), 6.4


def _speeds(sim: Simulation) -> np.ndarray:
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
    if k <= 10:
        palette = mpl.colormaps["tab10"].colors[:k]
    elif k <= 20:
        palette = mpl.colormaps["tab20"].colors[:k]
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


def _ffmpeg_executable(name: str) -> str | None:
    """The ffmpeg to use: None if matplotlib's configured one exists, else imageio-ffmpeg's."""
    configured = mpl.rcParams["animation.ffmpeg_path"]
    if shutil.which(configured):
        return None
    try:
        import imageio_ffmpeg
    except ImportError:
        raise RuntimeError(
            f"saving {name} needs ffmpeg, but {configured!r} is not on the PATH and the "
            "imageio-ffmpeg package is not installed: pip install 'edmd2d[video]' "
            "(or install ffmpeg, or save a .gif instead)"
        ) from None
    return imageio_ffmpeg.get_ffmpeg_exe()
