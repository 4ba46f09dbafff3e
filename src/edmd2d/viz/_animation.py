"""Animations: :func:`animate` runs a simulation forward to exact, equally spaced frame
times; :func:`animate_frames` draws frames recorded during a run.  Both are
:class:`~matplotlib.animation.FuncAnimation` objects drawn by a scene, and saved
through edmd2d's writers."""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import matplotlib as mpl
import matplotlib.animation as manim
import numpy as np
from matplotlib.axes import Axes
from numpy.typing import ArrayLike

from .._validate import as_count, as_positive_float
from ..operations import RecordFrames, Snapshot
from ..simulation import Simulation
from ._colors import Color, ColorBy
from ._layout import _figure_of
from ._scene import _Scene
from ._writers import _SAVEFIG_GRABBERS, _ffmpeg_executable, _save_animation


def animate(
    sim: Simulation,
    duration: float,
    fps: float = 30,
    *,
    color_by: ColorBy = "speed",
    trail: int = 0,
    trail_disks: ArrayLike | None = None,
    trail_color: Color = "k",
    show_time: bool = True,
    time_per_second: float = 1.0,
    ax: Axes | None = None,
    blit: bool = True,
    **style: Any,
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
        ``figsize``, ``angle_marks``).

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
    frames: RecordFrames | Sequence[Snapshot],
    fps: float = 30,
    *,
    color_by: ColorBy = "speed",
    trail: int = 0,
    trail_disks: ArrayLike | None = None,
    trail_color: Color = "k",
    show_time: bool = True,
    ax: Axes | None = None,
    blit: bool = True,
    **style: Any,
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
            _figure_of(scene.ax), self.goto_frame, frames=len(frame_times),
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
        # (A simulation: FramesAnimation, whose frames are snapshots, has its own.)
        assert isinstance(self.sim, Simulation)
        self.sim.advance(until=float(self.frame_times[k]))
        return self._scene.update()

    def save(self, filename: str | os.PathLike[str],
             writer: manim.AbstractMovieWriter | str | None = None,
             fps: float | None = None, dpi: float | None = None, codec: str | None = None,
             bitrate: int | None = None, extra_args: list[str] | None = None,
             metadata: dict[str, str] | None = None,
             extra_anim: list[manim.Animation] | None = None,
             savefig_kwargs: dict[str, Any] | None = None, *,
             progress_callback: Callable[[int, int], Any] | None = None,
             colors: int | None = None) -> None:
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
        _save_animation(self, Path(filename), ours=True, fps=fps, dpi=dpi, colors=colors,
                        progress=progress_callback or False,
                        **{k: v for k, v in options.items() if v is not None})

    def to_html5_video(self, embed_limit: float | None = None) -> str:
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
        if self._writer_draws and self.ax.figure.canvas.is_saving():
            return
        # (matplotlib's own hook, which its type stubs leave out)
        super()._post_draw(framedata, blit)  # type: ignore[misc]

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
