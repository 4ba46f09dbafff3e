"""Writing animations to files: the writer for a file's suffix, the checks made before
the first frame is drawn, edmd2d's GIF writer, the ffmpeg to use, and the progress bar."""

from __future__ import annotations

import io
import shutil
import sys
from pathlib import Path
from typing import Any, TextIO

import matplotlib as mpl
import matplotlib.animation as manim

from .._validate import as_count, as_positive_float

_VIDEO_SUFFIXES = (".mp4", ".m4v", ".mov", ".mkv")
_GIF_SUFFIXES = (".gif",)
# GIF defaults: three quarters of the figure's resolution, 32 colours per frame (the
# README's 1000-disk animation: 13.7 MB instead of 37 MB at 640 px and 256 colours).
_GIF_DPI_FRACTION = 0.75
_GIF_COLORS = 32

# Keywords of Animation.save that belong to a writer's constructor.
_WRITER_OPTIONS = ("codec", "bitrate", "extra_args", "metadata")
# What to install for a writer of matplotlib's that is not available.
_WRITER_HINTS = {
    "imagemagick": "install ImageMagick (its 'magick' or 'convert' program on the PATH)",
    "imagemagick_file": "install ImageMagick (its 'magick' or 'convert' program on the PATH)",
}


def _save_animation(anim, path: Path, *, ours: bool, fps, dpi, colors, progress,
                    **kwargs) -> None:
    """Resolve and check the writer, then render: nothing is drawn before every check.

    ``ours`` says whether ``anim`` is a :class:`~edmd2d.viz.SimulationAnimation`: one
    that checks first that it can still be drawn, and renders with its own frame loop.
    (The caller knows; this module sits below the animations, which use it.)
    """
    suffix = path.suffix.lower()
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

    rc: dict[Any, Any] = {}  # (matplotlib's settings for the writing, by name)
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
    # (matplotlib's writers take any frame rate, though its stubs name an int)
    return registry[name](fps=fps, **options)  # type: ignore[arg-type]


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
        # (Pillow reads the buffer in place, which its stubs do not list)
        rgba = Image.frombuffer("RGBA", self.frame_size, buf.getbuffer(),  # type: ignore[arg-type]
                                "raw", "RGBA", 0, 1)
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

    def __init__(self, stream: TextIO | None = None, width: int = 60) -> None:
        self.stream = sys.stderr if stream is None else stream
        self.width = as_count("width", width)
        self._bar: Any = None  # (a tqdm bar from the first frame on)

    def __call__(self, i: int, n: int | None) -> None:
        from tqdm.auto import tqdm

        if self._bar is None:
            self._bar = tqdm(total=n, unit="frame", desc="save", file=self.stream,
                             ncols=self.width, leave=True)
        self._bar.update(i + 1 - self._bar.n)
        if n is not None and i + 1 >= n:
            self._bar.close()


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
