"""edmd2d.viz: what is drawn matches the simulation; animations step exactly; files save."""

from __future__ import annotations

import io
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


def walled_with_walls():
    pos = [[2.0, 2.0], [6.0, 5.0], [8.0, 8.0]]
    vel = [[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]]
    walls = [ed.Wall((5.0, 0.0), (5.0, 4.0)), *ed.Wall.polygon([(6, 6), (7, 6), (6.5, 7)])]
    return ed.Simulation(pos, vel, radii=0.5, box=ed.Box(10.0, 10.0, periodic=False),
                         walls=walls)


# --------------------------------------------------------------------- still frames
def test_import_edmd2d_does_not_import_matplotlib():
    code = "import sys, edmd2d; sys.exit('matplotlib' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0


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
        for seg in trails.get_segments():
            step = np.asarray(seg)
            # a step is half a unit long: never a line across the box
            assert np.hypot(*(step[1] - step[0])) == pytest.approx(0.5)
    anim._draw_was_started = True
    segs = np.array(trails.get_segments())
    # at t = 2 the disk is at x = 1.1 (wrapped); it crossed x = 10 at t = 1.45, so of
    # the last three steps the first is drawn twice: ending at 0.1 and at 10.1
    assert len(segs) == 4
    ends = {tuple(np.round(s[1], 12)) for s in segs}
    assert ends == {(1.1, 5.0), (0.6, 5.0), (0.1, 5.0), (10.1, 5.0)}
    alphas = trails.get_colors()[:, 3]
    assert alphas.max() == pytest.approx(1.0) and alphas.min() == pytest.approx(1 / 3)


@pytest.mark.skipif(
    not (viz.shutil.which(matplotlib.rcParams["animation.ffmpeg_path"])
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


def test_save_still_and_progress(tmp_path):
    path = viz.save(small_periodic(), tmp_path / "still.png", color_by="species")
    with Image.open(path) as im:
        assert im.size[0] > 100
    out = io.StringIO()
    bar = viz.TextProgress(stream=out, width=10)
    for i in range(20):
        bar(i, 20)
    lines = out.getvalue().splitlines()
    assert lines[-1].startswith("[##########] 20/20 frames")
    assert len(lines) <= 11


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
