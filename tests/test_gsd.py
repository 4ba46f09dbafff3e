"""GSD trajectories: the HOOMD schema in 2D, everything edmd2d knows logged, and
frames read back (edmd2d's own, or another program's) into a valid Simulation."""

from __future__ import annotations

import numpy as np
import pytest

import edmd2d as ed

hoomd = pytest.importorskip("gsd.hoomd")
from conftest import seed_of  # noqa: E402
from edmd2d.io import gsd  # noqa: E402


def mixed_channel():
    radii = np.where(np.arange(200) % 2, 0.5, 0.35)
    gas = ed.make_gas(200, 0.3, radii=radii, periodic=(True, False), seed=seed_of(2))
    species = (radii > 0.4).astype(int)
    mass = gas.masses.copy()
    mass[0] = np.inf
    vel = gas.velocities.copy()
    vel[0] = 0.0
    return ed.Simulation(gas.positions, vel, gas.radii, mass, box=gas.box,
                         species=species, gravity=(0.0, -0.05))


def test_frames_follow_the_hoomd_schema_in_2d(tmp_path):
    sim = mixed_channel()
    path = tmp_path / "run.gsd"
    gsd.record(sim, path, [1.0, 5.0, 20.0])
    with hoomd.open(str(path), "r") as traj:
        assert len(traj) == 3
        f = traj[-1]
    assert f.configuration.dimensions == 2
    w, h = sim.box.width, sim.box.height
    np.testing.assert_allclose(f.configuration.box, [w, h, 0, 0, 0, 0], rtol=1e-7)
    assert f.particles.position.dtype == np.float32  # (GSD's precision: see the module)
    pos = np.asarray(f.particles.position, np.float64)
    assert (pos[:, 2] == 0).all()
    # Centred box, and position + image L is the unwrapped position.
    assert (np.abs(pos[:, 0]) <= w / 2 * (1 + 1e-7)).all()
    unwrapped = pos[:, :2] + f.particles.image[:, :2] * np.array([w, h])
    np.testing.assert_allclose(unwrapped, sim.unwrapped_positions - [w / 2, h / 2],
                               atol=1e-4)
    assert (f.particles.image[:, 1] == 0).all() and np.abs(f.particles.image[:, 0]).max() > 0
    np.testing.assert_allclose(f.particles.diameter, 2 * sim.radii, rtol=1e-7)
    assert f.particles.types == ["A", "B"]
    assert f.particles.typeid.tolist() == sim.species.tolist()
    np.testing.assert_allclose(f.particles.velocity[:, :2], sim.velocities, rtol=1e-6,
                               atol=1e-6)
    assert f.particles.mass[0] == 0.0  # (the peg: HOOMD's "no mass")
    log = f.log
    assert log["edmd2d/time"][0] == 20.0
    assert log["edmd2d/periodic"].tolist() == [1, 0]
    assert log["edmd2d/gravity"].tolist() == [0.0, -0.05]
    assert log["edmd2d/immovable"][0] == 1 and log["edmd2d/immovable"][1:].sum() == 0
    assert log["edmd2d/collisions"][0] == sim.counts.collisions
    assert log["edmd2d/total_energy"][0] == pytest.approx(sim.total_energy())


def test_logged_pressure_is_the_virial_pressure_over_the_window(tmp_path):
    """For an elastic periodic gas kT is constant, so the logged pressure over the
    writer's window is measure()'s virial pressure over the same window."""
    a = ed.make_gas(300, 0.4, seed=seed_of(5)).advance(until=5.0)
    b = ed.make_gas(300, 0.4, seed=seed_of(5)).advance(until=5.0)
    gsd.record(a, tmp_path / "p.gsd", [5.0, 15.0])
    m = b.measure(duration=10.0)
    with hoomd.open(str(tmp_path / "p.gsd"), "r") as traj:
        assert np.isnan(traj[0].log["edmd2d/pressure"][0])  # (no window yet)
        assert traj[1].log["edmd2d/pressure"][0] == pytest.approx(m.pressure, rel=1e-12)


def test_a_frame_reads_back_into_the_same_state(tmp_path):
    sim = mixed_channel().advance(until=3.0)
    sim_walls = ed.Simulation([[2.0, 2.0], [6.0, 6.0]], [[1.0, 0.5], [-0.3, 0.2]], 0.5,
                              box=ed.Box(10.0, 8.0, periodic=False),
                              walls=[ed.Wall((4.0, 1.0), (4.0, 5.0))])
    for original in (sim, sim_walls):
        path = tmp_path / "one.gsd"
        with gsd.Writer(path) as out:
            out.write(original)
        back = gsd.read(path)
        assert back.time == original.time
        assert back.box == original.box
        assert back.walls == original.walls
        np.testing.assert_array_equal(back.gravity, original.gravity)
        np.testing.assert_array_equal(back.species, original.species)
        np.testing.assert_array_equal(back.masses, np.where(
            np.isfinite(original.masses), original.masses.astype(np.float32),
            np.inf))
        np.testing.assert_allclose(back.positions, original.positions, atol=1e-5)
        np.testing.assert_allclose(back.velocities, original.velocities, atol=1e-5)


def test_a_frame_from_another_program_reads_with_defaults(tmp_path):
    f = hoomd.Frame()
    f.configuration.box = [10.0, 10.0, 0.0, 0.0, 0.0, 0.0]
    f.configuration.dimensions = 2
    f.particles.N = 2
    f.particles.position = [[-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
    f.particles.diameter = [1.0, 1.0]
    with hoomd.open(str(tmp_path / "other.gsd"), "w") as traj:
        traj.append(f)
    sim = gsd.read(tmp_path / "other.gsd")
    assert sim.box.periodic == (True, True) and sim.time == 0.0
    np.testing.assert_allclose(sim.positions, [[3.0, 5.0], [7.0, 5.0]])
    assert sim.velocities.tolist() == [[0.0, 0.0], [0.0, 0.0]]


def test_invalid_frames_are_refused(tmp_path):
    def write(name, dims=2, box=(10.0, 10.0, 0.0, 0.0, 0.0, 0.0), x=(-2.0, 2.0)):
        f = hoomd.Frame()
        f.configuration.box = list(box)
        f.configuration.dimensions = dims
        f.particles.N = 2
        f.particles.position = [[x[0], 0.0, 0.0], [x[1], 0.0, 0.0]]
        f.particles.diameter = [1.0, 1.0]
        with hoomd.open(str(tmp_path / name), "w") as traj:
            traj.append(f)
        return tmp_path / name

    with pytest.raises(ValueError, match="3-dimensional"):
        gsd.read(write("3d", dims=3, box=(10.0, 10.0, 10.0, 0, 0, 0)))
    with pytest.raises(ValueError, match="tilted box"):
        gsd.read(write("tilt", box=(10.0, 10.0, 0.0, 0.5, 0, 0)))
    with pytest.raises(ValueError, match="overlaps"):
        gsd.read(write("overlap", x=(0.0, 0.5)))
    with pytest.raises(ValueError, match="frame 5 does not exist"):
        gsd.read(write("ok"), frame=5)
    with pytest.raises(ValueError, match="radius_scale"):
        gsd.read(write("ok2"), radius_scale=0.0)


def test_touching_disks_overlap_in_float32_and_read_with_a_radius_scale(tmp_path):
    """A row of touching disks (centres 1 apart, at an offset that float32 cannot
    hold): rounded to float32 some pairs overlap by ~1e-6 of a diameter, which the
    Simulation refuses; shrunk by 1e-5 the frame reads."""
    n = 20
    x = 0.1234567891 + np.arange(n) * 1.0
    sim = ed.Simulation(np.c_[x, np.full(n, 2.5)], np.zeros((n, 2)), 0.5,
                        box=ed.Box(float(n), 5.0, periodic=(True, False)))
    gsd.record(sim, tmp_path / "row.gsd", [0.0])
    # The message shows the two distances apart (17 digits) and names the remedy.
    with pytest.raises(ValueError, match=r"overlaps disk \d+ \(centre distance "
                       r"0\.99999\d+ < sum of radii 1, by .*radius_scale="):
        gsd.read(tmp_path / "row.gsd")
    back = gsd.read(tmp_path / "row.gsd", radius_scale=1.0 - 1e-5)
    np.testing.assert_allclose(back.positions, sim.positions, atol=1e-5)


def test_record_refuses_times_that_go_back():
    sim = ed.make_gas(50, 0.3, seed=seed_of(1)).advance(until=2.0)
    with pytest.raises(ValueError, match="must increase"):
        gsd.record(sim, "never.gsd", [1.0, 3.0])
    with pytest.raises(ValueError, match="must increase"):
        gsd.record(sim, "never.gsd", [3.0, 2.5])
    with pytest.raises(ValueError, match="mode"):
        gsd.Writer("never.gsd", mode="x")


def test_gsd_frames_give_the_same_g_of_r_in_freud_and_edmd2d(tmp_path):
    """A dense fluid's frames written to GSD, read back with the gsd package: freud's
    g(r) of them (finite-size normalisation, N - 1 partners per disk, as edmd2d's)
    equals edmd2d.radial_distribution of the same float32 frames to rounding, and of
    the float64 positions the simulation had to within the few pairs that float32
    moves across a bin edge."""
    freud = pytest.importorskip("freud", reason="freud-analysis is not installed "
                                "(pip install freud-analysis) to cross-check g(r)")
    sim = ed.make_gas(600, 0.6, seed=seed_of(3))
    sim.advance(until=5.0)
    times = [6.0, 7.0, 8.0, 9.0]
    exact = []
    writer = gsd.Writer(tmp_path / "fluid.gsd")
    for t in times:
        sim.advance(until=t)
        writer.write(sim)
        exact.append(sim.positions)
    writer.close()
    width, height = sim.box.size
    with hoomd.open(tmp_path / "fluid.gsd", "r") as frames:
        stored = [np.asarray(f.particles.position, dtype=np.float64) for f in frames]
        configuration = frames[0].configuration
    assert configuration.dimensions == 2 and configuration.box[2] == 0.0
    r_max, bins = 5.0, 50
    rdf = freud.density.RDF(bins=bins, r_max=r_max, normalization_mode="finite_size")
    fbox = freud.box.Box(width, height, is2D=True)
    for points in stored:
        rdf.compute(system=(fbox, points), reset=False)
    # GSD centres the box at the origin; edmd2d's box starts at 0.
    shifted = np.mod(np.array(stored)[:, :, :2] + [width / 2, height / 2], [width, height])
    r, g_file = ed.radial_distribution(shifted, sim.box, r_max=r_max, bins=bins)
    _, g_exact = ed.radial_distribution(np.array(exact), sim.box, r_max=r_max, bins=bins)
    np.testing.assert_allclose(rdf.bin_centers, r, rtol=1e-6)
    # freud measures the float32 distances in float32 and edmd2d in float64, so a pair
    # within a rounding of a bin edge may fall on either side: allow two such pairs per
    # bin.  One pair (counted from both ends) in a bin is 2 / (frames N (N - 1) / A
    # times the shell's area) of g, 3.7e-4 at r = 4.65.
    n, area = sim.n, width * height
    edges = np.linspace(0.0, r_max, bins + 1)
    one_pair = 2.0 / (len(stored) * n * (n - 1) / area * np.pi * np.diff(edges ** 2))
    assert (np.abs(rdf.rdf - g_file) <= 2.0 * one_pair + 1e-5 * g_file).all()
    # A bin of g ~ 1 near r = 4 holds ~ 4 * 600 * 0.4 pairs per frame: one pair moved
    # by float32 changes it by ~1e-4.
    np.testing.assert_allclose(g_file, g_exact, atol=2e-3)
    assert g_exact.max() > 2.0  # (the contact peak of a dense fluid)


def test_describe_and_copy_until(tmp_path):
    radii = np.where(np.arange(30) < 20, 0.5, 0.3)
    sim = ed.make_gas(30, 0.3, radii=radii, seed=seed_of(3))
    path = tmp_path / "gas.gsd"
    gsd.record(sim, path, times=[0.0, 0.5, 1.0, 1.5])
    info = gsd.describe(path)
    assert info["frames"] == 4 and info["times"] == (0.0, 1.5) and info["n"] == 30
    assert sorted(s["count"] for s in info["species"]) == list(
        np.unique(sim.species, return_counts=True)[1])
    assert info["periodic"] == (True, True) and info["walls"] == 0
    assert info["collisions"] == sim.counts.collisions
    # The frames up to a time, into another file or in place.
    gsd.copy_until(path, tmp_path / "cut.gsd", 1.0)
    assert gsd.describe(tmp_path / "cut.gsd")["times"] == (0.0, 1.0)
    gsd.copy_until(path, path, 0.7)
    assert gsd.describe(path)["frames"] == 2
    (tmp_path / "text.gsd").write_text("not a GSD file\n")
    with pytest.raises(ValueError, match="not a GSD file"):
        gsd.describe(tmp_path / "text.gsd")
    with pytest.raises(ValueError, match="not a GSD file"):
        gsd.copy_until(tmp_path / "text.gsd", tmp_path / "out.gsd", 1.0)
    # Frames written by another program carry no time to cut at.
    import gsd.hoomd as hoomd

    with hoomd.open(str(tmp_path / "other.gsd"), "w") as f:
        frame = hoomd.Frame()
        frame.particles.N = 1
        frame.particles.position = [[0.0, 0.0, 0.0]]
        f.append(frame)
    with pytest.raises(ValueError, match="not written by edmd2d"):
        gsd.copy_until(tmp_path / "other.gsd", tmp_path / "out.gsd", 1.0)
    assert not (tmp_path / "out.gsd").exists()


def test_frames_say_which_disks_are_at_rest(tmp_path):
    sim = ed.make_gas(60, 0.15, periodic=False, aspect=0.5, seed=4, restitution=0.9,
                      wall_restitution=0.9, gravity=(0.0, -1.0))
    path = tmp_path / "bed.gsd"
    gsd.record(sim, path, [1.0, 20.0, 100.0])
    with hoomd.open(str(path), "r") as traj:
        flags = [np.asarray(f.log["particles/edmd2d/resting"]) for f in traj]
    assert flags[0].dtype == np.uint8 and flags[0].shape == (60,)
    assert flags[0].sum() == 0  # falling
    assert 0 < flags[1].sum() < 60  # settling
    assert flags[2].tolist() == sim.resting.astype(int).tolist() == [1] * 60
    # Without resting there is nothing to say.
    gsd.record(mixed_channel(), tmp_path / "gas.gsd", [1.0])
    with hoomd.open(str(tmp_path / "gas.gsd"), "r") as traj:
        assert "particles/edmd2d/resting" not in traj[0].log


def test_an_open_gate_is_logged_and_read_back_with_a_disk_passing_through_it(tmp_path):
    # Two disks fall through an open gate (wall segment 1) across the box; a frame
    # taken as they straddle it reads back with the gate open.
    box = ed.Box(6.0, 10.0, periodic=False)
    walls = [ed.Wall((0.0, 2.0), (1.0, 1.0)), ed.Wall((0.0, 5.0), (6.0, 5.0))]
    sim = ed.Simulation([[2.0, 5.6], [4.0, 5.6]], [[0.0, 0.0], [0.0, -0.5]], 0.5, box=box,
                        walls=walls, open_walls=[1], gravity=(0.0, -1.0))
    path = tmp_path / "gate.gsd"
    gsd.record(sim, path, [0.6])
    assert (np.abs(sim.positions[:, 1] - 5.0) < 0.5).all()  # in the gate's line
    with hoomd.open(str(path), "r") as traj:
        assert traj[0].log["edmd2d/open_walls"].tolist() == [0, 1]
    again = gsd.read(path)
    assert again.open_walls.tolist() == [False, True]
    np.testing.assert_allclose(again.positions, sim.positions, atol=1e-5)
