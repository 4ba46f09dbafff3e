""":func:`save`: any animation to a video or GIF, or a simulation's current state to an
image, with every check made before the first frame is drawn."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import matplotlib.animation as manim
import matplotlib.pyplot as plt

from ..operations import Snapshot
from ..simulation import Simulation
from ._animation import SimulationAnimation
from ._layout import _figure_of
from ._scene import draw
from ._writers import _GIF_SUFFIXES, _VIDEO_SUFFIXES, _check_folder, _save_animation


def save(
    obj: manim.Animation | Simulation | Snapshot,
    path: str | os.PathLike[str],
    *,
    fps: float | None = None,
    dpi: float | None = None,
    colors: int | None = None,
    progress: bool | Callable[[int, int | None], None] = True,
    **kwargs: Any,
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
        fig = _figure_of(ax)  # (draw made it)
        try:
            fig.savefig(path, dpi=dpi)
        finally:
            plt.close(fig)
        return path
    if not isinstance(obj, manim.Animation):
        raise TypeError(
            f"save() takes an animation from viz.animate() or a Simulation, "
            f"got {type(obj).__name__}"
        )
    _save_animation(obj, path, ours=isinstance(obj, SimulationAnimation), fps=fps, dpi=dpi,
                    colors=colors, progress=progress, **kwargs)
    return path

