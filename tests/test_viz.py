"""edmd2d.viz: what is drawn matches the simulation; animations step exactly; files save."""

from __future__ import annotations

import io
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402
from PIL import Image  # noqa: E402

import edmd2d as ed  # noqa: E402
from conftest import seed_of
from edmd2d import viz  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def by_gid(ax, gid):
    found = [c for c in ax.get_children() if c.get_gid() == gid]
    assert len(found) == 1, f"expected one artist {gid!r}, found {len(found)}"
    return found[0]


def small_periodic():
    """Four disks in a periodic 10x10 box: one inside, one at the x edge, one at the
    y edge, one in a corner."""
    pos = [[5.0, 5.0], [0.2, 3.0], [7.0, 9.9], [9.7, 0.1]]
    vel = [[1.0, 0.5], [-0.3, 0.0], [0.0, 2.0], [0.4, -0.4]]
    radii = [0.5, 0.6, 0.4, 0.5]
    return ed.Simulation(pos, vel, radii=radii, masses=[1.0, 2.0, 1.0, 1.0],
                         box=ed.Box(10.0, 10.0, periodic=True))


def trail_steps(trails):
    """The trail's steps as an (m, 2, 2) array of (start, end) pairs, and each step's alpha.

    Each path of the trail collection holds all the steps of one age, as start/end pairs
    separated by NaN rows."""
    steps, alphas = [], []
    for seg, rgba in zip(trails.get_segments(), trails.get_colors()):
        pairs = np.asarray(seg).reshape(-1, 2, 2)  # get_segments() drops the NaN rows
        steps.append(pairs)
        alphas.append(np.full(len(pairs), rgba[3]))
    if not steps:
        return np.zeros((0, 2, 2)), np.zeros(0)
    return np.concatenate(steps), np.concatenate(alphas)


HAVE_IMAGEIO_FFMPEG = __import__("importlib").util.find_spec("imageio_ffmpeg") is not None
needs_imageio_ffmpeg = pytest.mark.skipif(not HAVE_IMAGEIO_FFMPEG,
                                          reason="needs pip install 'edmd2d[video]'")


def no_system_ffmpeg(monkeypatch):
    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", "no-such-ffmpeg-here")


def walled_with_walls():
    pos = [[2.0, 2.0], [6.0, 5.0], [8.0, 8.0]]
    vel = [[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]]
    walls = [ed.Wall((5.0, 0.0), (5.0, 4.0)), *ed.Wall.polygon([(6, 6), (7, 6), (6.5, 7)])]
    return ed.Simulation(pos, vel, radii=0.5, box=ed.Box(10.0, 10.0, periodic=False),
                         walls=walls)


# --------------------------------------------------------------------- still frames
def test_import_edmd2d_does_not_import_matplotlib():
    code = "import sys, edmd2d; sys.exit('matplotlib' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], check=False).returncode == 0


def test_disks_drawn_at_positions_and_true_size_with_periodic_images():
    sim = small_periodic()
    ax = viz.draw(sim)
    disks = by_gid(ax, "edmd2d-disks")
    assert isinstance(disks, EllipseCollection)
    assert len([c for c in ax.collections if isinstance(c, EllipseCollection)]) == 1
    off = disks.get_offsets()
    n = len(sim)
    np.testing.assert_array_equal(off[:n], sim.positions)
    np.testing.assert_allclose(disks.get_widths()[:n], 2 * sim.radii)
    np.testing.assert_allclose(disks.get_heights()[:n], 2 * sim.radii)
    # images: disk 1 across x; disk 2 across y; disk 3 across x, y and the corner
    images = {tuple(np.round(p, 12)) for p in off[n:]}
    assert images == {(10.2, 3.0), (7.0, -0.1), (-0.3, 0.1), (9.7, 10.1), (-0.3, 10.1)}
    assert len(off) == n + 5
    # every image has the size of its disk
    widths = dict(zip(map(tuple, np.round(off, 12)), disks.get_widths()))
    assert widths[(10.2, 3.0)] == pytest.approx(1.2)
    assert widths[(-0.3, 10.1)] == pytest.approx(1.0)
    # data units: the disk's drawn diameter in pixels is 2r times the data scale
    ax.figure.canvas.draw()
    scale = ax.transData.get_matrix()[0, 0]
    path = disks.get_paths()[0].transformed(disks.get_transform())
    ext = path.get_extents()
    assert ext.width * disks.get_widths()[0] / 2 == pytest.approx(2 * 0.5 * scale, rel=1e-9)


def test_walls_and_box_edges_drawn():
    sim = walled_with_walls()
    ax = viz.draw(sim, color_by=None)
    walls = by_gid(ax, "edmd2d-walls")
    segs = [np.asarray(s) for s in walls.get_segments()]
    assert len(segs) == len(sim.walls) == 4
    for seg, wall in zip(segs, sim.walls):
        np.testing.assert_array_equal(seg, [wall.start, wall.end])
    box = by_gid(ax, "edmd2d-box")
    assert len(box.get_segments()) == 4
    assert all(dashes is None for _, dashes in box.get_linestyles())  # all walled: solid
    assert len(by_gid(ax, "edmd2d-disks").get_offsets()) == len(sim)  # no images
    assert ax.get_xlim()[0] < 0 < 10 < ax.get_xlim()[1]


def test_open_walls_drawn_faint_and_dashed():
    sim = walled_with_walls()
    sim.open_wall(2)
    walls = by_gid(viz.draw(sim, color_by=None), "edmd2d-walls")
    dashed = [dashes is not None for _, dashes in walls.get_linestyles()]
    assert dashed == [False, False, True, False]
    alpha = walls.get_colors()[:, 3]
    assert alpha[2] < 0.5 and (alpha[[0, 1, 3]] == 1.0).all()


def test_periodic_edges_dashed_walled_solid():
    sim = ed.Simulation([[5.0, 5.0]], [[1.0, 0.0]], radii=0.5,
                        box=ed.Box(10.0, 8.0, periodic=(True, False)))
    box = by_gid(viz.draw(sim), "edmd2d-box")
    styles = [dashes is not None for _, dashes in box.get_linestyles()]
    assert styles == [True, True, False, False]  # x=0, x=width, y=0, y=height


def test_colours_follow_speed():
    sim = small_periodic()
    ax = viz.draw(sim, color_by="speed", vmin=0.0, vmax=3.0, cmap="plasma")
    disks = by_gid(ax, "edmd2d-disks")
    n = len(sim)
    speed = np.hypot(*sim.velocities.T)
    np.testing.assert_allclose(disks.get_array()[:n], speed)
    ax.figure.canvas.draw()
    expected = plt.get_cmap("plasma")(speed / 3.0)
    np.testing.assert_allclose(disks.get_facecolors()[:n], expected)
    # the images share their disk's colour
    np.testing.assert_allclose(disks.get_array()[n], speed[1])


def test_default_speed_scale_and_colorbar():
    sim = small_periodic()
    ax = viz.draw(sim, colorbar=True)
    disks = by_gid(ax, "edmd2d-disks")
    rms = np.sqrt(np.mean(np.sum(sim.velocities**2, axis=1)))
    assert disks.norm.vmin == 0.0
    assert disks.norm.vmax == pytest.approx(2 * rms)
    assert len(ax.figure.axes) == 2


@pytest.mark.parametrize("show_time", [False, True])
@pytest.mark.parametrize("aspect", [1.0, 2.0, 0.5])
def test_a_colorbar_widens_the_figure_and_leaves_the_box_as_it_was(aspect, show_time):
    # The bar once took its width from the axes, and the box, kept at equal aspect,
    # shrank and left empty bands above and below it (and on a tall box the tick
    # labels were cut off at the figure's right edge).
    sim = ed.make_gas(60, 0.4, aspect=aspect, seed=seed_of(5))
    plain = viz.draw(sim, show_time=show_time)
    barred = viz.draw(sim, show_time=show_time, colorbar=True)
    for ax in (plain, barred):
        ax.figure.canvas.draw()

    def box_px(ax):
        return ax.transData.transform([(0, 0), tuple(sim.box.size)]).ravel()

    (x0, y0, x1, y1), (px0, py0, px1, py1) = box_px(barred), box_px(plain)
    assert (x1 - x0, y0, y1) == pytest.approx((px1 - px0, py0, py1), abs=0.5)
    fig = barred.figure
    w, h = fig.get_size_inches()
    pw, ph = plain.figure.get_size_inches()
    assert h == pytest.approx(ph) and pw + 0.5 < w < pw + 1.5
    cax = next(a for a in fig.axes if a is not barred)
    bar = cax.get_tightbbox(fig.canvas.get_renderer())  # bar, ticks and label
    assert x1 < bar.x0 and bar.x1 <= fig.bbox.x1
    assert y0 <= cax.bbox.y0 < cax.bbox.y1 <= y1  # beside the box


def test_a_colorbar_on_given_axes_or_size_takes_its_share_of_them():
    sim = small_periodic()
    ax = viz.draw(sim, colorbar=True, figsize=(4.0, 3.0))
    assert tuple(ax.figure.get_size_inches()) == (4.0, 3.0)
    _, (left, right) = plt.subplots(1, 2, figsize=(8, 3))
    viz.draw(sim, ax=left, colorbar=True)
    assert tuple(left.figure.get_size_inches()) == (8.0, 3.0)
    assert len(left.figure.axes) == 3


def test_species_mass_array_and_callable_colours():
    sim = small_periodic()  # classes (r, m): (0.4,1), (0.5,1) twice, (0.6,2)
    n = len(sim)
    fc = by_gid(viz.draw(sim, color_by="species"), "edmd2d-disks").get_facecolors()[:n]
    np.testing.assert_array_equal(fc[0], fc[3])
    assert len({tuple(c) for c in fc}) == 3

    fc = by_gid(viz.draw(sim, color_by=["red", "lime", "blue", "k"]),
                "edmd2d-disks").get_facecolors()
    np.testing.assert_array_equal(fc[:n, :3], [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 0]])

    values = np.array([1.0, 2.0, 3.0, 4.0])
    disks = by_gid(viz.draw(sim, color_by=values), "edmd2d-disks")
    np.testing.assert_array_equal(disks.get_array()[:n], values)

    disks = by_gid(viz.draw(sim, color_by=lambda s: s.positions[:, 0]), "edmd2d-disks")
    np.testing.assert_array_equal(disks.get_array()[:n], sim.positions[:, 0])

    pegged = ed.Simulation([[2.0, 2.0], [6.0, 6.0]], [[1.0, 0.0], [0.0, 0.0]], radii=0.5,
                           masses=[1.0, np.inf], box=ed.Box(10, 10))
    ax = viz.draw(pegged, color_by="mass")
    ax.figure.canvas.draw()
    fc = by_gid(ax, "edmd2d-disks").get_facecolors()
    np.testing.assert_allclose(fc[1], matplotlib.colors.to_rgba("0.45"))


def test_time_text():
    sim = small_periodic()
    sim.advance(until=1.5)
    ax = viz.draw(sim, show_time=True)
    text = by_gid(ax, "edmd2d-text").get_text()
    assert "t = 1.50" in text and f"collisions {sim.counts.collisions}" in text


@pytest.mark.parametrize("make", ["draw", "animate", "draw_given_axes", "colorbar", "tall"])
def test_time_label_sits_above_the_box_inside_the_axes(make):
    sim = ed.make_gas(200, 0.5, seed=seed_of(3))  # disks right up to the top edge
    if make == "tall":  # too narrow for one line: two
        sim = ed.Simulation([[1.0, 11.5], [1.0, 5.0]], [[1.0, 0.0], [0.0, 0.0]], radii=0.5,
                            box=ed.Box(2.0, 12.0, periodic=False))
        ax = viz.draw(sim, show_time=True)
        assert "\n" in by_gid(ax, "edmd2d-text").get_text()
    elif make == "draw":
        ax = viz.draw(sim, show_time=True)
    elif make == "animate":
        anim = viz.animate(sim, duration=0.2, fps=10)
        anim._draw_was_started = True
        ax = anim.ax
    elif make == "draw_given_axes":
        _, (ax, _other) = plt.subplots(1, 2, figsize=(8, 3))
        viz.draw(sim, ax=ax, show_time=True)
    else:
        ax = viz.draw(sim, show_time=True, colorbar=True)
    fig = ax.figure
    fig.canvas.draw()
    label = by_gid(ax, "edmd2d-text").get_window_extent(fig.canvas.get_renderer())
    # the top of the box (and of every disk drawn inside it) in pixels
    box_top = ax.transData.transform([(0.0, sim.box.height)])[0, 1]
    box_left, _ = ax.transData.transform([(0.0, 0.0)])[0]
    disks_top = ax.transData.transform(
        [(0.0, (sim.positions[:, 1] + sim.radii).max())])[0, 1]
    assert label.y0 > box_top >= disks_top - 1e-9
    # inside the axes, so that blitting (which redraws the axes' area) updates it,
    # and inside the figure
    bb = ax.bbox
    assert bb.x0 - 1 <= label.x0 and label.x1 <= bb.x1 + 1
    assert bb.y0 - 1 <= label.y0 and label.y1 <= bb.y1 + 1
    assert label.x0 == pytest.approx(box_left, abs=1.0)  # left-aligned with the box
    assert label.x1 <= fig.bbox.x1 and label.y1 <= fig.bbox.y1


def test_time_label_leaves_the_box_as_large_as_without_it():
    sim = small_periodic()
    plain = viz.draw(sim)
    labelled = viz.draw(sim, show_time=True)
    for ax in (plain, labelled):
        ax.figure.canvas.draw()
    def box_px(ax):
        (x0, y0), (x1, y1) = ax.transData.transform([(0, 0), (10, 10)])
        return x1 - x0, y1 - y0
    assert box_px(labelled) == pytest.approx(box_px(plain), rel=1e-6)
    w, h = labelled.figure.get_size_inches()
    assert w == pytest.approx(6.4) and 6.4 < h < 6.8  # a strip added above


# --------------------------------------------------------------------- animations
def test_animation_steps_to_exact_frame_times_and_gif_has_every_frame(tmp_path):
    sim = small_periodic()
    anim = viz.animate(sim, duration=1.0, fps=8)  # dt = 1/8, exact in binary
    n_frames = len(anim.frame_times)
    assert n_frames == 9
    np.testing.assert_array_equal(anim.frame_times, np.arange(9) / 8)
    path = viz.save(anim, tmp_path / "run.gif", progress=False)
    assert sim.time == (n_frames - 1) / 8
    with Image.open(path) as im:
        assert im.n_frames == n_frames
        assert im.info["duration"] == pytest.approx(1000 / 8, abs=10)
    # the collection shows the final state
    disks = by_gid(anim.ax, "edmd2d-disks")
    np.testing.assert_array_equal(disks.get_offsets()[: len(sim)], sim.positions)
    np.testing.assert_allclose(disks.get_array()[: len(sim)], np.hypot(*sim.velocities.T))
    # the simulation only runs forward: a second rendering is refused clearly
    with pytest.raises(RuntimeError, match="only run forward"):
        viz.save(anim, tmp_path / "again.gif", progress=False)


def test_animation_time_per_second_and_start_time():
    sim = small_periodic().advance(until=0.5)
    anim = viz.animate(sim, duration=3.0, fps=4, time_per_second=2.0)
    np.testing.assert_array_equal(anim.frame_times, 0.5 + 0.5 * np.arange(7))
    for k in range(len(anim.frame_times)):
        anim.goto_frame(k)
        assert sim.time == anim.frame_times[k]
    assert sim.time == 3.5
    anim._draw_was_started = True  # driven by hand: no "never rendered" warning


def test_trails_follow_the_disk_and_break_at_periodic_wraps():
    # one fast disk crossing the periodic x edge; another without a trail
    sim = ed.Simulation([[7.1, 5.0], [3.0, 2.0]], [[2.0, 0.0], [0.0, 1.0]], radii=0.5,
                        box=ed.Box(10.0, 10.0))
    anim = viz.animate(sim, duration=2.0, fps=4, trail=3, trail_disks=[0])
    trails = by_gid(anim.ax, "edmd2d-trails")
    for k in range(len(anim.frame_times)):
        anim.goto_frame(k)
        steps, _ = trail_steps(trails)
        for step in steps:
            # a step is half a unit long: never a line across the box
            assert np.hypot(*(step[1] - step[0])) == pytest.approx(0.5)
    anim._draw_was_started = True
    segs, alphas = trail_steps(trails)
    # at t = 2 the disk is at x = 1.1 (wrapped); it crossed x = 10 at t = 1.45, so of
    # the last three steps the first is drawn twice: ending at 0.1 and at 10.1
    assert len(segs) == 4
    ends = {tuple(np.round(s[1], 12)) for s in segs}
    assert ends == {(1.1, 5.0), (0.6, 5.0), (0.1, 5.0), (10.1, 5.0)}
    assert alphas.max() == pytest.approx(1.0) and alphas.min() == pytest.approx(1 / 3)
    # the newest step is the most opaque, both copies of the wrapped one the faintest
    newest = np.flatnonzero(np.isclose(segs[:, 1, 0], 1.1))
    wrapped = np.flatnonzero(np.isclose(segs[:, 1, 0], 0.1) | np.isclose(segs[:, 1, 0], 10.1))
    assert alphas[newest] == pytest.approx([1.0])
    assert alphas[wrapped] == pytest.approx([1 / 3, 1 / 3])


def test_a_sheared_box_shows_its_images_shifted_and_trails_in_the_box_frame():
    """Across the sliding boundary a disk near the bottom shows above, shifted by the
    offset (and wrapped along x); near the top, below, shifted back.  A disk moving
    up at (0.5, 4) through the top with rate 0.2 in a 10 x 10 box re-enters at the
    bottom with x less the offset and its x velocity less U = 2: every trail step is
    its velocity in the box's frame times the frame interval, never a jump."""
    sim = ed.Simulation([[1.0, 0.2], [5.0, 9.9], [8.0, 5.0]], np.zeros((3, 2)), 0.5,
                        box=ed.Box(10.0, 10.0), shear_rate=0.2, shear_offset=9.5)
    ax = viz.draw(sim)
    off = by_gid(ax, "edmd2d-disks").get_offsets()
    images = {tuple(np.round(p, 12)) for p in off[3:]}
    # disk 0 above at x 1 + 9.5 = 10.5 -> 0.5; disk 1 below at 5 - 9.5 = -4.5 -> 5.5
    assert images == {(0.5, 10.2), (5.5, -0.1)}
    plt.close(ax.figure)
    sim = ed.Simulation([[3.0, 7.9], [8.0, 3.0]], [[0.5, 4.0], [0.0, 0.0]], 0.3,
                        box=ed.Box(10.0, 10.0), shear_rate=0.2)
    anim = viz.animate(sim, duration=1.0, fps=4, trail=4, trail_disks=[0])
    trails = by_gid(anim.ax, "edmd2d-trails")
    for k in range(len(anim.frame_times)):
        anim.goto_frame(k)
    steps, _ = trail_steps(trails)
    # Before the exit the step is (0.5, 4) / 4; after it (0.5 - 2, 4) / 4 (both the
    # copy in the frame before the exit and the one after).
    lengths = sorted({tuple(np.round((b - a) * 4, 9)) for a, b in steps})
    assert set(lengths) <= {(0.5, 4.0), (-1.5, 4.0)} and (-1.5, 4.0) in lengths
    plt.close(anim.ax.figure)


def test_trails_drawn_as_one_path_per_age_and_rendered_with_breaks():
    sim = ed.make_gas(30, 0.3, seed=seed_of(2))
    anim = viz.animate(sim, duration=1.0, fps=10, trail=4, blit=False, color_by=None,
                       show_time=False)
    for k in range(6):
        anim.goto_frame(k)
    anim._draw_was_started = True
    trails = by_gid(anim.ax, "edmd2d-trails")
    assert len(trails.get_paths()) == 4  # one path per age, not one per step
    steps, _ = trail_steps(trails)
    assert len(steps) >= 4 * len(sim)
    # Agg breaks each path at its NaN rows: no line joins one disk's step to the next
    # disk's (those joins would cross the box; the steps are a few pixels long)
    fig = anim.ax.figure
    for coll in anim.ax.collections:
        coll.set_visible(coll is trails)
    trails.set_color("k")
    fig.canvas.draw()
    inked = (np.asarray(fig.canvas.buffer_rgba())[..., :3] < 128).any(axis=-1).mean()
    assert 0 < inked < 0.015  # 0.3 % measured; joined steps would ink 3.9 %


@pytest.mark.skipif(
    not (shutil.which(matplotlib.rcParams["animation.ffmpeg_path"])
         or __import__("importlib").util.find_spec("imageio_ffmpeg")),
    reason="no ffmpeg: pip install 'edmd2d[video]'",
)
def test_save_mp4(tmp_path):
    sim = small_periodic()
    anim = viz.animate(sim, duration=0.5, fps=10, figsize=(3.01, 2.33))  # odd pixel sizes
    path = viz.save(anim, tmp_path / "run.mp4", progress=False)
    assert path.stat().st_size > 0
    assert sim.time == anim.frame_times[-1]
    try:
        import imageio_ffmpeg
    except ImportError:
        return
    frames, _ = imageio_ffmpeg.count_frames_and_secs(str(path))
    assert frames == len(anim.frame_times)


def test_save_mp4_without_ffmpeg_says_how_to_get_it(tmp_path, monkeypatch):
    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", "no-such-ffmpeg-here")
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)
    anim = viz.animate(small_periodic(), duration=0.2, fps=10)
    with pytest.raises(RuntimeError, match=r"edmd2d\[video\]"):
        viz.save(anim, tmp_path / "run.mp4", progress=False)
    anim._draw_was_started = True


@needs_imageio_ffmpeg
def test_animation_save_method_writes_mp4_without_a_system_ffmpeg(tmp_path, monkeypatch):
    no_system_ffmpeg(monkeypatch)
    sim = small_periodic()
    anim = viz.animate(sim, duration=0.5, fps=10)
    anim.save(tmp_path / "run.mp4")  # matplotlib's own way
    import imageio_ffmpeg

    frames, _ = imageio_ffmpeg.count_frames_and_secs(str(tmp_path / "run.mp4"))
    assert frames == len(anim.frame_times)
    assert sim.time == anim.frame_times[-1]


@needs_imageio_ffmpeg
def test_to_html5_video_without_a_system_ffmpeg(monkeypatch):
    no_system_ffmpeg(monkeypatch)
    anim = viz.animate(small_periodic(), duration=0.3, fps=10)
    assert "<video" in anim.to_html5_video()


def test_animation_save_method_gif_uses_the_viz_writer(tmp_path):
    sim = small_periodic()
    anim = viz.animate(sim, duration=0.5, fps=10)
    anim.save(str(tmp_path / "run.gif"), dpi=50)
    with Image.open(tmp_path / "run.gif") as im:
        assert im.n_frames == len(anim.frame_times)
        assert im.size == tuple(int(x * 50) for x in anim.ax.figure.get_size_inches())
        assert len(im.getcolors()) <= 32
    assert sim.time == anim.frame_times[-1]


def test_gif_defaults_three_quarter_resolution_and_32_colours(tmp_path):
    anim = viz.animate(small_periodic(), duration=0.2, fps=10)
    path = viz.save(anim, tmp_path / "run.gif", progress=False)
    with Image.open(path) as im:
        # the 640 px wide figure (taller by the time label's strip) at three quarters
        width, height = anim.ax.figure.get_size_inches() * 75
        assert im.size == (480, int(height)) and height < width * 1.05
        for k in range(im.n_frames):
            im.seek(k)
            assert len(im.convert("RGB").getcolors()) <= 32
    anim = viz.animate(small_periodic(), duration=0.2, fps=10)
    path = viz.save(anim, tmp_path / "rich.gif", dpi=100, colors=256, progress=False)
    with Image.open(path) as im:
        assert im.size[0] == 640
        assert len(im.convert("RGB").getcolors()) > 32
    anim = viz.animate(small_periodic(), duration=0.2, fps=10)
    with pytest.raises(ValueError, match="colors"):
        viz.save(anim, tmp_path / "run.gif", colors=1, progress=False)
    with pytest.raises(ValueError, match="colors.*gif"):
        viz.save(anim, tmp_path / "run.mp4", colors=64, progress=False)
    anim._draw_was_started = True


@pytest.mark.parametrize("how", ["method", "viz.save"])
def test_unwritable_target_fails_before_rendering_anything(tmp_path, monkeypatch, how):
    no_system_ffmpeg(monkeypatch)
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)
    monkeypatch.setitem(matplotlib.rcParams, "animation.convert_path", "no-such-convert")
    sim = small_periodic()
    anim = viz.animate(sim, duration=0.5, fps=10)

    def save(name, **kwargs):
        if how == "method":
            anim.save(str(tmp_path / name), **kwargs)
        else:
            viz.save(anim, tmp_path / name, progress=False, **kwargs)

    cases = [
        (("run.mp4",), {}, RuntimeError, r"pip install 'edmd2d\[video\]'"),
        (("run.mov",), {"writer": "ffmpeg"}, RuntimeError, r"edmd2d\[video\]"),
        (("run.mp4",), {"writer": "pillow"}, ValueError, r"Pillow cannot write \.mp4"),
        (("run.gif",), {"writer": "imagemagick"}, RuntimeError, "ImageMagick"),
        (("run.gif",), {"writer": "no-such-writer"}, ValueError, "unknown writer"),
        (("run.avi",), {}, ValueError, "cannot tell"),
        (("missing/run.gif",), {}, FileNotFoundError, "folder"),
    ]
    for args, kwargs, error, match in cases:
        with pytest.raises(error, match=match):
            save(*args, **kwargs)
        assert sim.time == 0.0, f"{args} {kwargs}: the simulation was advanced"
    assert list(tmp_path.iterdir()) == []
    # and the animation is still good for a format that can be written
    save("run.gif")
    with Image.open(tmp_path / "run.gif") as im:
        assert im.n_frames == len(anim.frame_times)


@pytest.mark.parametrize("how", ["method", "viz.save"])
def test_second_save_says_the_animation_was_already_played(tmp_path, how):
    sim = small_periodic()
    anim = viz.animate(sim, duration=0.3, fps=10)
    if how == "method":
        anim.save(str(tmp_path / "first.gif"))
    else:
        viz.save(anim, tmp_path / "first.gif", progress=False)
    for name in ("again.gif", "again.mp4"):
        with pytest.raises(RuntimeError, match="already played") as info:
            if how == "method":
                anim.save(str(tmp_path / name))
            else:
                viz.save(anim, tmp_path / name, progress=False)
        assert "viz.animate" in str(info.value) and "only run forward" in str(info.value)
    assert not (tmp_path / "again.gif").exists() and not (tmp_path / "again.mp4").exists()


def test_advanced_elsewhere_is_not_called_played(tmp_path):
    sim = small_periodic()
    anim = viz.animate(sim, duration=0.3, fps=10)
    sim.advance(until=1.0)
    with pytest.raises(RuntimeError, match="advanced to t=1 after") as info:
        viz.save(anim, tmp_path / "late.gif", progress=False)
    assert "already played" not in str(info.value)


def test_each_frame_is_drawn_once_when_saving(tmp_path, monkeypatch):
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    anim = viz.animate(small_periodic(), duration=1.0, fps=10)
    draws = []
    original = FigureCanvasAgg.draw
    monkeypatch.setattr(FigureCanvasAgg, "draw",
                        lambda self, *a, **k: (draws.append(1), original(self, *a, **k))[1])
    viz.save(anim, tmp_path / "run.gif", progress=False)
    assert len(draws) == len(anim.frame_times)


def test_other_writers_still_redraw_each_frame(tmp_path):
    # a writer that reads the canvas instead of calling savefig gets drawn frames
    class CanvasWriter(matplotlib.animation.AbstractMovieWriter):
        def setup(self, fig, outfile, dpi=None):
            super().setup(fig, outfile, dpi)
            self.frames = []

        def grab_frame(self, **kwargs):
            self.frames.append(np.asarray(self.fig.canvas.buffer_rgba()).copy())

        def finish(self):
            pass

    sim = small_periodic()
    anim = viz.animate(sim, duration=0.3, fps=10, color_by=None, show_time=False)
    writer = CanvasWriter(fps=10)
    anim.save(str(tmp_path / "x.raw"), writer=writer)
    assert len(writer.frames) == 4
    assert not np.array_equal(writer.frames[0], writer.frames[-1])


def test_save_still_and_progress(tmp_path):
    path = viz.save(small_periodic(), tmp_path / "still.png", color_by="species")
    with Image.open(path) as im:
        assert im.size[0] > 100
    out = io.StringIO()
    bar = viz.TextProgress(stream=out, width=60)
    for i in range(20):
        bar(i, 20)
    assert "20/20" in out.getvalue().replace("\r", "\n").splitlines()[-1]


# --------------------------------------------------------------------- bad arguments
@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"color_by": "colour"}, ValueError, "color_by must be one of"),
        ({"color_by": [1.0, 2.0]}, ValueError, r"shape \(4,\)"),
        ({"color_by": np.zeros((4, 5))}, ValueError, "shape"),
        ({"color_by": ["red", "blue", "green", "notacolour"]}, ValueError, "colours"),
        ({"color_by": "species", "colorbar": True}, ValueError, "numeric colouring"),
        ({"vmin": 2.0, "vmax": 1.0}, ValueError, "vmax must be greater"),
        ({"ax": "axes"}, TypeError, "Axes"),
        ({"color_by": None, "color": "notacolour"}, ValueError, "colour"),
        ({"margin": -1}, ValueError, "margin"),
    ],
)
def test_draw_rejects_bad_arguments(kwargs, error, match):
    with pytest.raises(error, match=match):
        viz.draw(small_periodic(), **kwargs)


def test_callable_colour_of_wrong_length():
    with pytest.raises(ValueError, match="one number per disk"):
        viz.draw(small_periodic(), color_by=lambda s: [1.0])


@pytest.mark.parametrize(
    ("args", "kwargs", "error", "match"),
    [
        ((0.0,), {}, ValueError, "duration"),
        ((1.0,), {"fps": 0}, ValueError, "fps"),
        ((1.0,), {"fps": "fast"}, TypeError, "fps"),
        ((1.0,), {"trail": -1}, ValueError, "trail"),
        ((1.0,), {"trail": 2, "trail_disks": [7]}, ValueError, "out of range"),
        ((1.0,), {"time_per_second": -2.0}, ValueError, "time_per_second"),
        ((1.0,), {"colour_by": "speed"}, TypeError, "colour_by"),
    ],
)
def test_animate_rejects_bad_arguments(args, kwargs, error, match):
    with pytest.raises(error, match=match):
        viz.animate(small_periodic(), *args, **kwargs)
    assert plt.get_fignums() == []  # nothing half-built left behind


def test_bad_simulation_and_save_targets(tmp_path):
    with pytest.raises(TypeError, match="Simulation"):
        viz.draw(np.zeros((3, 2)))
    with pytest.raises(TypeError, match="Simulation"):
        viz.animate(None, 1.0)
    with pytest.raises(TypeError, match="animation"):
        viz.save(42, tmp_path / "x.gif")
    with pytest.raises(ValueError, match="still image"):
        viz.save(small_periodic(), tmp_path / "x.mp4")
    anim = viz.animate(small_periodic(), 0.2, fps=10)
    with pytest.raises(ValueError, match="cannot tell"):
        viz.save(anim, tmp_path / "x.txt")
    with pytest.raises(TypeError, match="progress"):
        viz.save(anim, tmp_path / "x.gif", progress="yes")
    anim._draw_was_started = True


def test_a_growing_simulation_is_drawn_at_its_present_size():
    """The picture follows the radii of growing disks from frame to frame."""
    from edmd2d.viz._scene import _Scene

    sim = ed.random_gas(50, 0.3, seed=seed_of(1))
    sim.set_growth(0.1)
    scene = _Scene(sim)
    scene.update()
    before = np.array(scene.disks.get_widths())
    sim.advance(until=2.0)
    scene.update()
    after = np.array(scene.disks.get_widths())
    assert after.max() == pytest.approx(before.max() * 1.2, rel=1e-9)
    plt.close(scene.ax.figure)
