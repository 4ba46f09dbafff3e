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

# matplotlib is the one dependency of this package that not every install has: it is
# imported first, so that its absence names the extra that brings it.
try:
    import matplotlib  # noqa: F401
except ModuleNotFoundError as exc:
    raise ModuleNotFoundError(
        "edmd2d.viz needs matplotlib, which is not installed: pip install 'edmd2d[viz]' "
        "(or 'edmd2d[video]' for .mp4 output), or pip install matplotlib pillow",
        name=exc.name,
    ) from exc

from ._animation import FramesAnimation, SimulationAnimation, animate, animate_frames
from ._colors import ColorBy as ColorBy  # (the type of the color_by arguments)
from ._save import save
from ._scene import draw
from ._writers import TextProgress

__all__ = ["draw", "animate", "animate_frames", "save", "SimulationAnimation",
           "FramesAnimation", "TextProgress"]
