"""The geometry of a figure made here, in inches: its size for a box, the strip for the
time label above the box, and a colour bar added beside the box without shrinking it."""

from __future__ import annotations

from matplotlib.axes import Axes
from matplotlib.figure import Figure

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


def _figure_of(ax: Axes) -> Figure:
    """The figure of ``ax``: a :class:`~matplotlib.figure.Figure`, whose size the
    drawings set and which the animations save (a subfigure has neither)."""
    fig = ax.figure
    assert isinstance(fig, Figure), "edmd2d draws in the axes of a figure, not a subfigure"
    return fig


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
    fig = _figure_of(ax)
    fw, fh = fig.get_size_inches()
    pos = ax.get_position(original=True)
    x0, y0, aw, ah = pos.x0 * fw, pos.y0 * fh, pos.width * fw, pos.height * fh
    bw, bh = region
    scale = min(aw / bw, (ah - top) / bh)  # inches per data unit, as set_aspect gives
    drawn = scale * bh + top  # (the region and the label strip, centred in the axes)
    middle = y0 + 0.5 * (ah - drawn) + 0.5 * scale * bh
    bar_h = 0.8 * (ah - top)
    bar = [x0 + aw + _CBAR_GAP, middle - 0.5 * bar_h, _CBAR_WIDTH, bar_h]
    cax = fig.add_axes((bar[0] / fw, bar[1] / fh, bar[2] / fw, bar[3] / fh))
    fig.colorbar(mappable, cax=cax, label=label)
    # What the ticks, their labels and the axis label take right of the bar, in inches,
    # and then the figure's usual edge.
    ticks = cax.get_tightbbox()
    assert ticks is not None  # (None only for axes that are not drawn)
    right = ticks.x1 / fig.dpi - (bar[0] + bar[2])
    width = fw + _CBAR_GAP + _CBAR_WIDTH + max(right, 0.0) + _FIG_EDGE * fw
    fig.set_size_inches(width, fh)
    ax.set_position((x0 / width, pos.y0, aw / width, pos.height))
    cax.set_position((bar[0] / width, bar[1] / fh, bar[2] / width, bar[3] / fh))


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
