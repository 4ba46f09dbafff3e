"""Pictures and animations of a :class:`~edmd2d.Simulation` with matplotlib.

This is the only module of edmd2d that imports matplotlib (``pip install 'edmd2d[viz]'``;
``import edmd2d`` alone never does).  Four functions:

- :func:`draw` -- a still frame of the current state;
- :func:`animate` -- a :class:`matplotlib.animation.FuncAnimation` that advances the
  simulation to exact, equally spaced frame times (``sim.advance(until=t_k)``);
- :func:`animate_frames` -- an animation of frames recorded during a run by
  :class:`edmd2d.operations.RecordFrames` (while the same run measures or writes
  files), which can be shown and saved any number of times;
- :func:`save` -- write an animation to ``.gif`` (Pillow) or ``.mp4`` (ffmpeg, found on the
  PATH or supplied by ``pip install 'edmd2d[video]'``), or a still to ``.png``/``.pdf``/...,
  with a progress bar (tqdm).  The animation's own ``save`` method is the same function.

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
from .operations import RecordFrames, Snapshot
from .simulation import Simulation

__all__ = ["draw", "animate", "animate_frames", "save", "SimulationAnimation",
           "FramesAnimation", "TextProgress"]

_COLOR_MODES = ("speed", "species", "mass")
_VIDEO_SUFFIXES = (".mp4", ".m4v", ".mov", ".mkv")
_GIF_SUFFIXES = (".gif",)
# GIF defaults: three quarters of the figure's resolution, 32 colours per frame (the
# README's 1000-disk animation: 13.7 MB instead of 37 MB at 640 px and 256 colours).
_GIF_DPI_FRACTION = 0.75
_GIF_COLORS = 32
# Above this many disks the default drops the disk outlines: at a few pixels per disk they
# only darken the picture, and they roughly double the drawing time.
_OUTLINE_MAX_N = 3000
# Figures made here: inches on the longer side (at least _FIG_MIN_SIDE on the other), and
# the space between the axes and the figure's edges, as a fraction of the figure.
_FIG_LONG_SIDE = 6.4
_FIG_MIN_SIDE = 1.5
_FIG_EDGE = 0.01
# Points between the top of the box and the bottom of the time label.
_LABEL_GAP_PT = 3.0
# The colour bar of a figure made here: inches between the axes and the bar, and the
# bar's width.  Its ticks and label take what they measure, right of the bar.
_CBAR_GAP = 0.15
_CBAR_WIDTH = 0.18
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
        Write the time and the collision count above the box, as for :func:`draw`.
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
        A :class:`matplotlib.animation.FuncAnimation`; save it with :func:`save` or its
        own ``save`` method (the same writers and checks), show it with ``plt.show()``, or
        embed it in a notebook with ``anim.to_jshtml()`` or ``anim.to_html5_video()``.

    Raises
    ------
    TypeError, ValueError
        For invalid arguments (as for :func:`draw`, plus a non-positive ``duration``,
        ``fps`` or ``time_per_second``, a negative ``trail``, out-of-range
        ``trail_disks`` and unknown keywords).

    Examples
    --------
    Five frames per unit of simulated time for one unit: six frames, the first the
    current state, each at its exact time.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import edmd2d as ed
    >>> from edmd2d import viz
    >>> anim = viz.animate(ed.make_gas(30, 0.3, seed=1), duration=1.0, fps=5,
    ...                    time_per_second=1.0)
    >>> anim.frame_times.tolist()
    [0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
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

def animate_frames(
    frames,
    fps: float = 30,
    *,
    color_by: ColorBy = "speed",
    trail: int = 0,
    trail_disks=None,
    trail_color="k",
    show_time: bool = True,
    ax: Axes | None = None,
    blit: bool = True,
    **style,
) -> FramesAnimation:
    """An animation of frames recorded during a run (:class:`~edmd2d.operations.RecordFrames`).

    The frames were taken at their exact times while the simulation ran (with the
    other operations of the same run: measurements, files), so the animation only
    draws them: it can be shown and saved as often as wanted, and the simulation is
    not touched.  It looks as :func:`animate` would at the same times.

    Parameters
    ----------
    frames : RecordFrames or sequence of Snapshot
        The frames, in order (at least one).
    fps : float, default 30
        Frames per second of animation.
    color_by, trail, trail_disks, trail_color, show_time, ax, blit, **style
        As for :func:`animate`; a callable ``color_by`` is called with each
        :class:`~edmd2d.operations.Snapshot`.

    Returns
    -------
    FramesAnimation
        Save it with :func:`save` or its ``save`` method.

    Raises
    ------
    TypeError, ValueError
        For frames that are not snapshots, no frames, frames of different numbers of
        disks, and the arguments :func:`animate` refuses.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import edmd2d as ed
    >>> from edmd2d import operations as op, viz
    >>> rec = op.RecordFrames(op.Every(dt=0.25))
    >>> _ = ed.make_gas(30, 0.3, seed=1).run(until=1.0, operations=[rec])
    >>> anim = viz.animate_frames(rec, fps=10)
    >>> anim.frame_times.tolist()
    [0.0, 0.25, 0.5, 0.75, 1.0]
    """
    shots = list(frames.frames if isinstance(frames, RecordFrames) else frames)
    if not shots:
        raise ValueError("animate_frames needs at least one frame")
    for k, shot in enumerate(shots):
        if not isinstance(shot, Snapshot):
            raise TypeError(f"frames[{k}] must be an edmd2d.operations.Snapshot, got "
                            f"{type(shot).__name__}")
        if shot.n != shots[0].n:
            raise ValueError(f"frames[{k}] has {shot.n} disks, frames[0] {shots[0].n}")
    fps = as_positive_float("fps", fps)
    trail = as_count("trail", trail)
    scene = _Scene(shots[0], ax, color_by=color_by, trail=trail, trail_disks=trail_disks,
                   trail_color=trail_color, show_time=show_time, **style)
    return FramesAnimation(scene, shots, fps, blit=blit)


class SimulationAnimation(manim.FuncAnimation):
    """The animation made by :func:`animate` (a :class:`~matplotlib.animation.FuncAnimation`).

    Its :meth:`save` is :func:`save`: the same writers (GIF through Pillow, video through
    ffmpeg or imageio-ffmpeg), the same checks before the first frame is drawn.

    Made by :func:`animate`, which checks its arguments; not meant to be built directly.

    Parameters
    ----------
    scene : object
        The artists of one simulation on one Axes (built by :func:`animate`).
    frame_times : numpy.ndarray
        Simulation time of each frame, increasing.
    fps : float
        Frames per second.
    blit : bool
        Whether matplotlib redraws only the artists that change.

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
        self._played = False  # a frame has been drawn: the simulation may have moved on
        self._writer_draws = False  # saving with a writer whose grab_frame draws the figure
        super().__init__(
            scene.ax.figure, self.goto_frame, frames=len(frame_times),
            init_func=scene.update, interval=1000.0 / fps, repeat=False, blit=blit,
            cache_frame_data=False,
        )

    def goto_frame(self, k: int) -> list:
        """Advance the simulation to frame ``k``'s time and update the artists.

        This is what the animation calls for each frame; it does not redraw the canvas.

        Parameters
        ----------
        k : int
            The frame, ``0 <= k < len(frame_times)``.

        Returns
        -------
        list
            The artists that changed.

        Raises
        ------
        RuntimeError
            If the simulation is already past that time (the animation was played or
            saved before, or the simulation was advanced elsewhere).
        """
        self._check_can_start(k)
        self._played = True
        self.sim.advance(until=float(self.frame_times[k]))
        return self._scene.update()

    def save(self, filename, writer=None, fps=None, dpi=None, codec=None, bitrate=None,
             extra_args=None, metadata=None, extra_anim=None, savefig_kwargs=None, *,
             progress_callback=None, colors=None) -> None:
        """Write the animation to a file: :func:`save` with matplotlib's signature.

        ``anim.save("run.mp4")`` is ``viz.save(anim, "run.mp4", progress=False)``: GIFs
        go through Pillow at three quarters of the figure's resolution and 32 colours,
        videos through ffmpeg (the one on the PATH, else imageio-ffmpeg's).  A writer given
        by name or as an instance is used as in matplotlib, except that one that cannot
        write the file is refused before the first frame is drawn, instead of falling
        back to Pillow.  The parameters are those of
        :meth:`matplotlib.animation.Animation.save`, and ``colors`` as for :func:`save`
        (colours per GIF frame).

        Parameters
        ----------
        filename : str or os.PathLike
            The file; its suffix picks the format.
        writer : str or matplotlib.animation.AbstractMovieWriter, optional
            A writer by name (``"pillow"``, ``"ffmpeg"``, ...) or an instance; by
            default the one for the suffix.
        fps : float, optional
            Frames per second of the file; the animation's own by default.
        dpi : float, optional
            Resolution; for GIFs three quarters of the figure's by default.
        codec, bitrate, extra_args, metadata, extra_anim, savefig_kwargs : optional
            As for :meth:`matplotlib.animation.Animation.save`.
        progress_callback : callable, optional
            Called as ``progress_callback(frame_index, total_frames)`` after each
            frame.
        colors : int, optional
            Colours per GIF frame (32 by default, at most 256).

        Raises
        ------
        RuntimeError
            If the animation was already played or saved (the simulation has moved on),
            or no program can write the format (with what to install).
        ValueError, FileNotFoundError
            For a file suffix that no writer here can write, or a missing folder.
        """
        options = {"writer": writer, "codec": codec, "bitrate": bitrate,
                   "extra_args": extra_args, "metadata": metadata,
                   "extra_anim": extra_anim, "savefig_kwargs": savefig_kwargs}
        _save_animation(self, Path(filename), fps=fps, dpi=dpi, colors=colors,
                        progress=progress_callback or False,
                        **{k: v for k, v in options.items() if v is not None})

    def to_html5_video(self, embed_limit=None) -> str:
        """As :meth:`matplotlib.animation.Animation.to_html5_video`, with imageio-ffmpeg's
        ffmpeg when there is none on the PATH.

        Parameters
        ----------
        embed_limit : float, optional
            The largest video in MB (matplotlib's ``animation.embed_limit`` by default).

        Returns
        -------
        str
            An HTML ``<video>`` element with the video embedded (base64).
        """
        exe = None
        if mpl.rcParams["animation.writer"] in ("ffmpeg", "ffmpeg_file"):
            exe = _ffmpeg_executable("an HTML5 video")
        with mpl.rc_context({} if exe is None else {"animation.ffmpeg_path": exe}):
            return super().to_html5_video(embed_limit)

    def _render(self, path: Path, writer, **kwargs) -> None:
        """Matplotlib's frame loop, without its second drawing of each frame."""
        self._writer_draws = type(writer).grab_frame in _SAVEFIG_GRABBERS
        try:
            super().save(str(path), writer=writer, **kwargs)
        finally:
            self._writer_draws = False

    def _post_draw(self, framedata, blit) -> None:
        # While saving, matplotlib draws the canvas after each frame's update and the
        # writer then draws the figure again in savefig: the first drawing is skipped for
        # writers known to call savefig (a third of the time of a 1000-disk frame).
        if self._writer_draws and self._fig.canvas.is_saving():
            return
        super()._post_draw(framedata, blit)

    def _check_can_start(self, k: int = 0) -> None:
        t = float(self.frame_times[k])
        if t >= self.sim.time:
            return
        if self._played:
            raise RuntimeError(
                f"this animation was already played or saved: its simulation has moved on "
                f"to t={self.sim.time:g}, past frame {k} at t={t:g}. Simulations only run "
                "forward, so an animation can be played or saved once; to render it again, "
                "build the simulation anew and make a new animation with viz.animate"
            )
        raise RuntimeError(
            f"the simulation was advanced to t={self.sim.time:g} after viz.animate made "
            f"this animation (frame {k} is at t={t:g}). Simulations only run forward: make "
            "a new animation with viz.animate to show the simulation from its current time"
        )


class FramesAnimation(SimulationAnimation):
    """The animation made by :func:`animate_frames`: recorded frames, drawn in order.

    It saves like :class:`SimulationAnimation` (the same writers and checks) but runs
    no simulation, so it can be played and saved again.

    Made by :func:`animate_frames`, which checks its arguments; not meant to be built
    directly.

    Parameters
    ----------
    scene : object
        The artists on one Axes, drawn from the first frame (built by
        :func:`animate_frames`).
    frames : list of Snapshot
        The frames, in order.
    fps : float
        Frames per second.
    blit : bool
        Whether matplotlib redraws only the artists that change.

    Attributes
    ----------
    frames : list of Snapshot
        The frames.
    frame_times : numpy.ndarray
        Simulation time of each frame.
    fps : float
        Frames per second.
    ax : matplotlib Axes
        The axes drawn on.
    """

    def __init__(self, scene: _Scene, frames: list, fps: float, *, blit: bool):
        self.frames = frames
        super().__init__(scene, np.array([f.time for f in frames], dtype=float), fps,
                         blit=blit)

    def goto_frame(self, k: int) -> list:
        """Show frame ``k``.

        Parameters
        ----------
        k : int
            The frame, ``0 <= k < len(frames)``.

        Returns
        -------
        list
            The artists that changed.
        """
        if k == 0:
            self._scene.reset()
        self._scene.sim = self.sim = self.frames[k]
        return self._scene.update()

    def _check_can_start(self, k: int = 0) -> None:
        """Recorded frames can always be drawn again."""


def save(
    obj,
    path,
    *,
    fps: float | None = None,
    dpi: float | None = None,
    colors: int | None = None,
    progress: bool | Callable[[int, int | None], None] = True,
    **kwargs,
) -> Path:
    """Write an animation to a video or GIF, or a simulation's current state to an image.

    Everything that can be checked is checked before the first frame is drawn (the
    format, the writer, the folder), so a refused save leaves the simulation where it
    was.

    Parameters
    ----------
    obj : SimulationAnimation, matplotlib Animation, Simulation or Snapshot
        An animation is rendered frame by frame (running its simulation forward, or
        drawing its recorded frames); a simulation or a snapshot is drawn with
        :func:`draw` and saved as a still.
    path : str or Path
        For an animation ``.gif`` (written with Pillow) or ``.mp4``/``.m4v``/``.mov``/
        ``.mkv`` (H.264 through ffmpeg: the ``ffmpeg`` on the PATH, or else the binary
        of the ``imageio-ffmpeg`` package, ``pip install 'edmd2d[video]'``).  For a
        simulation any format matplotlib's ``savefig`` knows (``.png``, ``.pdf``, ``.svg``).
        Video is the better choice for long or large runs: the README's 1000-disk
        animation is 7.9 MB as MP4 at 640 px and 13.7 MB as GIF at 480 px.
    fps : float, optional
        Frames per second of the file; default the animation's own.
    dpi : float, optional
        Resolution.  Default for ``.gif`` three quarters of the figure's (480 px for the
        default 6.4 inch figure), otherwise the figure's (matplotlib's ``savefig.dpi``).
    colors : int, optional
        For ``.gif`` only: colours per frame, 2 to 256, default 32.  More colours
        render the antialiased disk edges and a continuous colour scale more smoothly, in
        a larger file (the README's animation at 480 px: 13.7 MB with 32, 19.3 MB with
        64, 25.8 MB with 256).
    progress : bool or callable, default True
        For animations: print a progress bar to stderr (``True``), nothing (``False``),
        or call ``progress(frame_index, total_frames)`` after each frame.
    **kwargs
        For a simulation, keywords of :func:`draw`; for an animation, keywords of
        :meth:`matplotlib.animation.Animation.save` (e.g. ``bitrate``, ``codec``,
        ``writer``).  A ``writer`` that is not available, or that cannot write the
        suffix, is an error here (matplotlib would fall back to Pillow).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    TypeError
        For an ``obj`` that is neither an animation nor a simulation.
    ValueError
        For a file suffix that cannot hold the object, an unknown writer, or ``colors``
        out of range or given for a file that is not a GIF.
    FileNotFoundError
        For a folder that does not exist.
    RuntimeError
        For a video when no ffmpeg can be found, or a writer whose program is missing
        (with what to install); for an animation that was already played or saved.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import tempfile, pathlib
    >>> import edmd2d as ed
    >>> from edmd2d import viz
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> anim = viz.animate(ed.make_gas(30, 0.3, seed=1), duration=0.4, fps=5,
    ...                    time_per_second=1.0)
    >>> viz.save(anim, folder / "gas.gif", progress=False).stat().st_size > 0
    True
    >>> viz.save(ed.make_gas(30, 0.3, seed=1), folder / "gas.png").suffix
    '.png'
    """
    path = Path(path)
    if isinstance(obj, (Simulation, Snapshot)):
        if path.suffix.lower() in _VIDEO_SUFFIXES + _GIF_SUFFIXES:
            raise ValueError(
                f"{path.name}: a Simulation is saved as a still image (.png, .pdf, .svg); "
                "for a video pass viz.animate(sim, duration) instead"
            )
        if colors is not None:
            raise ValueError("colors applies to animations saved as .gif, not to stills")
        _check_folder(path)
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
    _save_animation(obj, path, fps=fps, dpi=dpi, colors=colors, progress=progress, **kwargs)
    return path


# Keywords of Animation.save that belong to a writer's constructor.
_WRITER_OPTIONS = ("codec", "bitrate", "extra_args", "metadata")
# What to install for a writer of matplotlib's that is not available.
_WRITER_HINTS = {
    "imagemagick": "install ImageMagick (its 'magick' or 'convert' program on the PATH)",
    "imagemagick_file": "install ImageMagick (its 'magick' or 'convert' program on the PATH)",
}


def _save_animation(anim, path: Path, *, fps, dpi, colors, progress, **kwargs) -> None:
    """Resolve and check the writer, then render: nothing is drawn before every check."""
    suffix = path.suffix.lower()
    ours = isinstance(anim, SimulationAnimation)
    if ours:
        anim._draw_was_started = True  # as matplotlib's save: no "never rendered" warning
        anim._check_can_start()
    if progress is True:
        callback = TextProgress()
    elif progress is False or progress is None:
        callback = None
    elif callable(progress):
        callback = progress
    else:
        raise TypeError(f"progress must be True, False or a callable, got {progress!r}")
    writer = kwargs.pop("writer", None)
    options = {k: kwargs.pop(k) for k in _WRITER_OPTIONS if kwargs.get(k) is not None}
    if writer is not None and not isinstance(writer, str):
        if fps is not None or options:
            raise ValueError(
                f"fps and {', '.join(_WRITER_OPTIONS)} go to the writer's constructor when "
                f"writer is a {type(writer).__name__} instance, not to save()"
            )
    elif fps is None:
        # ours carry fps; any other matplotlib animation has its frame interval in ms
        fps = getattr(anim, "fps", None) or 1000.0 / getattr(anim, "_interval", 200)
    else:
        fps = as_positive_float("fps", fps)
    gif = suffix in _GIF_SUFFIXES
    if colors is not None:
        if not gif or writer is not None:
            raise ValueError(
                f"colors applies to .gif files written by edmd2d's GIF writer, not to "
                f"{path.name}" + ("" if writer is None else f" with writer={writer!r}")
            )
        colors = as_count("colors", colors)
        if not 2 <= colors <= 256:
            raise ValueError(f"colors must be between 2 and 256 (a GIF palette), got {colors}")

    rc = {}
    if writer is None:
        if gif:
            if options:
                raise ValueError(f"{path.name}: {', '.join(options)} apply to video files")
            writer = _GifWriter(fps=fps, colors=_GIF_COLORS if colors is None else colors)
        elif suffix in _VIDEO_SUFFIXES:
            writer = "ffmpeg"
        else:
            raise ValueError(
                f"{path.name}: cannot tell how to write an animation to {suffix!r}; "
                f"use one of {', '.join(_GIF_SUFFIXES + _VIDEO_SUFFIXES)}"
            )
    uses_ffmpeg = (writer in ("ffmpeg", "ffmpeg_file") if isinstance(writer, str)
                   else isinstance(writer, manim.FFMpegBase))
    if uses_ffmpeg:
        exe = _ffmpeg_executable(path.name)
        if exe is not None:
            rc["animation.ffmpeg_path"] = exe
    with mpl.rc_context(rc):
        if isinstance(writer, str):
            writer = _writer_by_name(writer, path.name, fps, options)
        if isinstance(writer, manim.PillowWriter):
            _check_pillow_can_write(path)
        _check_folder(path)
        if dpi is None and gif:
            dpi = _GIF_DPI_FRACTION * _savefig_dpi(anim._fig)
        render = anim._render if ours else anim.save
        render(path, writer=writer, dpi=dpi, progress_callback=callback, **kwargs)


def _writer_by_name(name: str, filename: str, fps: float, options: dict):
    """An instance of matplotlib's writer ``name``; an error if it cannot run here."""
    registry = manim.writers
    if name not in getattr(registry, "_registered", {name: None}):
        raise ValueError(
            f"unknown writer {name!r} for {filename}; leave writer out to use edmd2d's "
            f"(.gif with Pillow, video with ffmpeg), or name one of matplotlib's: "
            f"{', '.join(sorted(getattr(registry, '_registered', {})))}"
        )
    if not registry.is_available(name):
        hint = _WRITER_HINTS.get(name, "its program is not installed")
        raise RuntimeError(
            f"matplotlib's writer {name!r} cannot run here: {hint}; or leave writer out "
            f"to write {filename} with edmd2d's writers"
        )
    return registry[name](fps=fps, **options)


def _check_pillow_can_write(path: Path) -> None:
    from PIL import Image

    fmt = Image.registered_extensions().get(path.suffix.lower())
    if fmt not in Image.SAVE_ALL:
        raise ValueError(
            f"{path.name}: Pillow cannot write {path.suffix} animations (it writes .gif, "
            ".png, .webp); for video leave writer out, which uses ffmpeg "
            "(pip install 'edmd2d[video]' if there is none)"
        )


def _check_folder(path: Path) -> None:
    folder = path.parent
    if not folder.is_dir():
        raise FileNotFoundError(f"cannot save {path}: the folder {folder} does not exist")


def _savefig_dpi(fig) -> float:
    dpi = mpl.rcParams["savefig.dpi"]
    return float(fig.dpi if dpi == "figure" else dpi)


class _GifWriter(manim.AbstractMovieWriter):
    """GIF through Pillow, keeping each frame as 8-bit palette image as it is grabbed.

    Unlike matplotlib's ``PillowWriter`` (which keeps full RGBA frames until the end and
    quantizes them then), this holds one byte per pixel, so long renders of large systems
    need a quarter of the memory, and the fast octree quantizer keeps the cost per frame
    at a few milliseconds.  Frames are opaque (the figure background is used).

    Each frame gets its own palette of ``colors`` colours.  The size of a GIF of a gas is
    set by the antialiased disk edges, which change every frame; fewer colours for those
    blends is what shrinks it (the README's 1000-disk animation, 301 frames at 480 px:
    25.8 MB with 256 colours, 19.3 MB with 64, 13.7 MB with 32).  Reusing one palette
    for all frames, or letting unchanged pixels be transparent, changed the size by less
    than 5 %; drawing without antialiasing would give 9.6 MB, with jagged disks.
    """

    def __init__(self, fps=5, colors: int = 256, **kwargs) -> None:
        super().__init__(fps=fps, **kwargs)
        self.colors = colors

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
        self._frames.append(rgba.convert("RGB").quantize(self.colors,
                                                         Image.Quantize.FASTOCTREE))

    def finish(self) -> None:
        if not self._frames:  # nothing was drawn (an error while rendering): no file
            return
        # GIF stores delays in hundredths of a second.
        self._frames[0].save(self.outfile, save_all=True, append_images=self._frames[1:],
                             duration=round(1000.0 / self.fps), loop=0)
        self._frames = []


# Writers whose grab_frame draws the figure itself (with savefig).
_SAVEFIG_GRABBERS = {
    cls.grab_frame for cls in (_GifWriter, manim.MovieWriter, manim.FileMovieWriter,
                               manim.PillowWriter, manim.HTMLWriter)
}


class TextProgress:
    """The progress bar of :func:`save` (a ``tqdm`` bar, see :mod:`edmd2d.progress`):
    ``progress(frame_index, total_frames)`` after each frame.

    Parameters
    ----------
    stream : file-like, optional
        Where to write; ``sys.stderr`` by default.  On a terminal tqdm redraws the bar
        in place; elsewhere (a log file, CI) it prints a line at most every tenth of a
        second.
    width : int, default 60
        Characters of the whole line.
    """

    def __init__(self, stream=None, width: int = 60) -> None:
        self.stream = sys.stderr if stream is None else stream
        self.width = as_count("width", width)
        self._bar = None

    def __call__(self, i: int, n: int | None) -> None:
        from tqdm.auto import tqdm

        if self._bar is None:
            self._bar = tqdm(total=n, unit="frame", desc="save", file=self.stream,
                             ncols=self.width, leave=True)
        self._bar.update(i + 1 - self._bar.n)
        if n is not None and i + 1 >= n:
            self._bar.close()


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

        if colorbar and sized_here:
            _colorbar_beside(ax, self.disks, self._color.label, (w + 2 * pad, h + 2 * pad),
                             label)
        elif colorbar:  # (the caller's axes or figure size: the bar takes its share)
            ax.figure.colorbar(self.disks, ax=ax, shrink=0.8, label=self._color.label)
        self.text = None
        if show_time:
            # The label goes in a strip added above the box, inside the axes: it covers no
            # disk and no edge, and blitting (which redraws the axes' area) updates it.
            fw, fh = ax.figure.get_size_inches()
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
        idx, offsets = _with_periodic_images(pos, rad, self._size, self._periodic)
        self.disks.set_offsets(offsets)
        diam = 2.0 * rad[idx]
        self.disks.set_widths(diam)
        self.disks.set_heights(diam)
        self._color.apply(self.disks, sim, idx)
        changed = [self.disks]
        if self.trails is not None:
            self._update_trails(pos)
            changed.append(self.trails)
        if self.text is not None:
            self.text.set_text(
                f"t = {sim.time:.2f}{self._label_sep}collisions {sim.counts.collisions:,}")
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
        n_seg = len(hist) - 1
        paths = []
        for j in range(n_seg):
            (a, sa), (b, sb) = hist[j], hist[j + 1]
            # Each step is drawn continuously in the frame of its end point, so a step that
            # crosses a periodic edge runs out of the box (and is clipped there) instead of
            # spanning the whole box; a second copy in the frame of its start point shows
            # the part on the other side.
            starts, ends = [a + sb], [b + sb]
            wrapped = (sa != sb).any(axis=1)
            if wrapped.any():
                starts.append(a[wrapped] + sa[wrapped])
                ends.append(b[wrapped] + sa[wrapped])
            # All steps of one age share a colour, so they make one path: (start, end, NaN)
            # rows, and Agg lifts the pen at each NaN.  One Path per age instead of one
            # per step cuts the trail's cost per frame from 17 ms to 4 ms at 1000 disks.
            starts, ends = np.concatenate(starts), np.concatenate(ends)
            verts = np.full((len(starts), 3, 2), np.nan)
            verts[:, 0] = starts
            verts[:, 1] = ends
            paths.append(verts.reshape(-1, 2))
        rgba = np.repeat(self._trail_rgba[None, :], n_seg, axis=0)
        rgba[:, 3] *= np.arange(1, n_seg + 1) / max(n_seg, 1)  # older steps fade out
        self.trails.set_segments(paths)
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


def _figure_size(width: float, height: float, label: float = 0.0) -> tuple[float, float]:
    """About 6.4 inches on the longer side, keeping the aspect ratio of the drawn region
    ``width`` x ``height`` (data units), plus a strip of ``label`` inches above it."""
    frac = 1 - 2 * _FIG_EDGE  # of the figure taken by the axes
    if width >= height:
        fig_w = _FIG_LONG_SIDE
        scale = frac * fig_w / width
        fig_h = (scale * height + label) / frac
    else:
        fig_h = _FIG_LONG_SIDE
        scale = (frac * fig_h - label) / height
        fig_w = scale * width / frac
    return max(fig_w, _FIG_MIN_SIDE), max(fig_h, _FIG_MIN_SIDE + label)


def _colorbar_beside(ax: Axes, mappable, label: str, region: tuple[float, float],
                     top: float) -> None:
    """A colour bar right of ``ax`` in a strip added to the figure's width.

    ``figure.colorbar(ax=...)`` would take its width from the axes, which were sized to
    the box: the box, kept at equal aspect, would shrink and leave empty bands above and
    below it.  Here the axes keep their size in inches and the figure grows instead, by
    the gap, the bar and what its ticks and label measure.  The bar spans 0.8 of the
    axes' height below the time label strip (``top`` inches), centred on the drawn
    ``region`` (box plus margin, data units).
    """
    fig = ax.figure
    fw, fh = fig.get_size_inches()
    pos = ax.get_position(original=True)
    x0, y0, aw, ah = pos.x0 * fw, pos.y0 * fh, pos.width * fw, pos.height * fh
    bw, bh = region
    scale = min(aw / bw, (ah - top) / bh)  # inches per data unit, as set_aspect gives
    drawn = scale * bh + top  # (the region and the label strip, centred in the axes)
    middle = y0 + 0.5 * (ah - drawn) + 0.5 * scale * bh
    bar_h = 0.8 * (ah - top)
    bar = [x0 + aw + _CBAR_GAP, middle - 0.5 * bar_h, _CBAR_WIDTH, bar_h]
    cax = fig.add_axes([bar[0] / fw, bar[1] / fh, bar[2] / fw, bar[3] / fh])
    fig.colorbar(mappable, cax=cax, label=label)
    # What the ticks, their labels and the axis label take right of the bar, in inches,
    # and then the figure's usual edge.
    right = cax.get_tightbbox().x1 / fig.dpi - (bar[0] + bar[2])
    width = fw + _CBAR_GAP + _CBAR_WIDTH + max(right, 0.0) + _FIG_EDGE * fw
    fig.set_size_inches(width, fh)
    ax.set_position([x0 / width, pos.y0, aw / width, pos.height])
    cax.set_position([bar[0] / width, bar[1] / fh, bar[2] / width, bar[3] / fh])


def _label_height(font, lines: int) -> float:
    """Inches above the box for the time label: the gap, the lines, a little air."""
    return (_LABEL_GAP_PT + 1.3 * lines * font.get_size_in_points()) / 72.0 + 0.02


def _label_fits(font, inches: float) -> bool:
    """Whether the time label fits on one line in ``inches`` (for t < 100 000 and fewer
    than ten million collisions)."""
    from matplotlib.textpath import TextPath

    width_pt = TextPath((0, 0), "t = 99999.99   collisions 9,999,999", prop=font
                        ).get_extents().width
    return width_pt / 72.0 <= inches


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
