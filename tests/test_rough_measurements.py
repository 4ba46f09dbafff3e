"""What is measured on rough disks (rotational temperature, angular velocity
distribution, cooling), and where they go: configuration files, the command line,
GSD frames, pictures."""

from __future__ import annotations

import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d import theory


def _equilibrated(seed):
    """1000 elastic, perfectly rough disks of two masses and inertias, ~50 collisions
    per disk from spins at rest: translation and rotation in equilibrium."""
    rng = np.random.default_rng(seed)
    gas = ed.make_gas(1000, 0.3, seed=seed)
    mass = np.where(rng.random(gas.n) < 0.5, 1.0, 3.0)
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, mass, box=gas.box,
                        tangential_restitution=1.0,
                        inertia=np.where(rng.random(gas.n) < 0.5, 0.5, 0.25), seed=seed)
    sim.advance(collisions=25 * sim.n)
    return sim


def test_equilibrium_rotational_temperature_and_maxwellian_spins():
    from scipy import stats

    for k in range(3):
        sim = _equilibrated(seed_of(60) + k)
        m = sim.measure(20.0, blocks=10)
        # The ratio of one snapshot scatters by sqrt(2/N + 1/N) ~ 5 % at N = 1000; 11
        # boundaries a few collisions apart: ~1.6 %.  A margin of 8 % is 5 of those.
        assert m.rotational_temperature / m.temperature == pytest.approx(1.0, abs=0.08)
        assert 0 < m.rotational_temperature_error < 0.05 * m.rotational_temperature
        assert "rotational temperature" in m.summary()
        # Each spin in its thermal unit is a standard normal whatever its mass and
        # inertia (the scaled kurtosis of 1000 normal samples scatters by 0.15).
        w, f = ed.angular_velocity_distribution(sim, bins=40, w_max=4.0)
        assert np.sum(f) * (w[1] - w[0]) == pytest.approx(1.0)
        q = sim.families["rough"].inertia
        scaled = sim.angular_velocities * np.sqrt(q * sim.masses * sim.radii ** 2
                                                  / ed.rotational_temperature(sim))
        assert stats.kstest(scaled, "norm").pvalue > 1e-4
        assert np.mean(scaled ** 4) / np.mean(scaled ** 2) ** 2 == pytest.approx(3.0, abs=0.75)


def test_homogeneous_cooling_ratio_of_a_dilute_rough_gas():
    # e = 0.9, beta = 1: the Maxwellian theory's ratio 1.1566 lies within 0.2 % of the
    # Boltzmann equation's (a DSMC without the Gaussian closure: 1.1593 +- 0.0012), so
    # the dilute gas must reach it.  Samples of one gas of 2000 scatter by ~3.5 %; 28
    # of them from 4 gases, 5 to 40 collisions per disk (the start, equipartition,
    # relaxes within ~5): a mean within 4 % is beyond 4 of its standard errors.
    ratios = []
    for k in range(4):
        sim = ed.make_gas(2000, 0.05, seed=seed_of(61) + k, restitution=0.9,
                          tangential_restitution=1.0)
        inertia = 0.5 * sim.masses * sim.radii ** 2
        rng = np.random.default_rng(seed_of(62) + k)
        sim.set_angular_velocities(rng.normal(size=sim.n) / np.sqrt(inertia))
        sim.advance(collisions=5 * sim.n // 2)
        for _ in range(7):
            sim.advance(collisions=5 * sim.n // 2)
            ratios.append(ed.rotational_temperature(sim) / ed.kinetic_temperature(sim))
    expected = theory.rough_hcs_ratio(0.9, 1.0, 0.5)
    assert np.mean(ratios) == pytest.approx(expected, rel=0.04)


def test_cooling_books_the_rotation():
    sim = ed.make_gas(400, 0.2, seed=seed_of(63), restitution=0.8,
                      tangential_restitution=0.2, friction=0.4, angular_velocities=1.5)
    start = sim.total_energy()
    c = ed.cooling(sim, np.linspace(0.0, 3.0, 7))
    np.testing.assert_allclose(c.kinetic_energy + c.rotational_energy + c.dissipated_energy,
                               start, rtol=1e-11)
    np.testing.assert_allclose(c.rotational_temperature,
                               2.0 * c.rotational_energy / sim.n, rtol=1e-12)
    assert c.rotational_energy[-1] < 0.8 * c.rotational_energy[0]
    smooth = ed.cooling(ed.make_gas(50, 0.2, seed=1, restitution=0.9), [0.0, 1.0])
    assert np.all(np.isnan(smooth.rotational_temperature))
    assert np.all(smooth.rotational_energy == 0.0)
    assert math.isnan(ed.make_gas(50, 0.2, seed=1).measure(1.0).rotational_temperature)


def test_spins_and_angles_are_set_and_refused_by_name():
    sim = ed.make_gas(20, 0.3, seed=seed_of(64), tangential_restitution=0.5,
                      angles=np.linspace(0.0, 1.0, 20), angular_velocities=2.0)
    np.testing.assert_array_equal(sim.angles, np.linspace(0.0, 1.0, 20))
    sim.advance(until=1.5)
    before = sim.angles
    sim.set_angular_velocities(np.arange(20.0))
    np.testing.assert_array_equal(sim.angles, before)  # (read forward to now first)
    np.testing.assert_array_equal(sim.angular_velocities, np.arange(20.0))
    with pytest.raises(ValueError, match="angular_velocities"):
        sim.set_angular_velocities([1.0, 2.0])
    with pytest.raises(ValueError, match="smooth"):
        ed.make_gas(10, 0.3, seed=1).set_angular_velocities(1.0)
    with pytest.raises(ValueError, match="smooth"):
        ed.rotational_temperature(ed.make_gas(10, 0.3, seed=1))
    with pytest.raises(ValueError, match="angles needs tangential_restitution"):
        ed.make_gas(10, 0.3, seed=1, angles=0.3)
    with pytest.raises(ValueError, match="angles"):
        ed.make_gas(10, 0.3, seed=1, tangential_restitution=0.5, angles=[np.nan] * 10)


def test_a_spin_set_between_collisions_turns_the_angle_at_that_rate():
    box = ed.Box(10.0, 10.0)
    sim = ed.Simulation([[2.0, 5.0], [8.0, 5.0]], [[0.0, 0.0], [0.0, 0.0]], 0.5,
                        box=box, tangential_restitution=1.0, angular_velocities=[1.0, 0.0])
    sim.advance(until=1.0)
    sim.set_angular_velocities([-2.0, 3.0])
    sim.advance(until=2.5)
    np.testing.assert_allclose(sim.angles, [1.0 - 3.0, 4.5], rtol=1e-15)


def test_gsd_frames_carry_hoomds_angular_momentum_and_the_angles(tmp_path):
    gsd_hoomd = pytest.importorskip("gsd.hoomd")
    from edmd2d.io import gsd as gsd_io

    sim = ed.make_gas(40, 0.3, seed=seed_of(65), tangential_restitution=0.7, inertia=0.4,
                      angular_velocities=np.linspace(-3.0, 3.0, 40))
    sim.advance(until=3.0)
    path = tmp_path / "t.gsd"
    gsd_io.record(sim, path, [sim.time])
    back = gsd_io.read(path)
    np.testing.assert_array_equal(back.angles, sim.angles)
    np.testing.assert_array_equal(back.angular_velocities, sim.angular_velocities)
    with gsd_hoomd.open(path) as frames:
        frame = frames[0]
    # HOOMD's body-frame angular momentum S = im(q* P) / 2, about z: I w.
    q = frame.particles.orientation.astype(float)
    p = frame.particles.angmom.astype(float)
    s_z = 0.5 * (q[:, 0] * p[:, 3] - q[:, 3] * p[:, 0])
    inertia = 0.4 * sim.masses * sim.radii ** 2
    np.testing.assert_allclose(s_z, inertia * sim.angular_velocities, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(p[:, 1:3], 0.0)
    # A frame without the logged angles gives them from the orientation (modulo 2 pi).
    del frame.log["particles/edmd2d/angle"]
    old = tmp_path / "old.gsd"
    with gsd_hoomd.open(old, "w") as out:
        out.append(frame)
    turned = gsd_io.read(old).angles - sim.angles
    np.testing.assert_allclose(np.angle(np.exp(1j * turned)), 0.0, atol=1e-6)


def test_configuration_files_and_the_command_line_take_rough_disks(tmp_path, capsys):
    pytest.importorskip("gsd")
    from edmd2d import config
    from edmd2d.cli import main

    text = """\
[gas]
n = 150
packing_fraction = 0.3

[model]
seed = 3
restitution = 0.9
tangential_restitution = 0.4
friction = 0.3
wall_tangential_restitution = -1.0
inertia = 0.4
angular_velocities = 0.5

[run]
duration = 2.0
blocks = 2
"""
    path = tmp_path / "rough.toml"
    path.write_text(text)
    sim, _ = config.build(config.load(path), 3)
    rough = sim.families["rough"]
    assert (rough.beta, rough.friction, rough.wall_beta) == (0.4, 0.3, -1.0)
    np.testing.assert_array_equal(rough.inertia, 0.4)
    np.testing.assert_array_equal(sim.angular_velocities, 0.5)
    out = tmp_path / "out"
    assert main(["run", str(path), "-o", str(out), "--no-progress"]) == 0
    assert "rotational" in (out / "results.json").read_text()
    capsys.readouterr()
    assert main(["info", str(out / "checkpoint.edmd2d")]) == 0
    assert "rough tangential_restitution 0.4, friction 0.3" in capsys.readouterr().out
    path.write_text(text.replace("friction = 0.3", "friction = -0.3"))
    with pytest.raises(config.ConfigError, match="model.friction"):
        config.load(path)


def test_pictures_mark_each_disks_angle():
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    from edmd2d import viz

    sim = ed.make_gas(12, 0.3, seed=seed_of(66), tangential_restitution=1.0,
                      angles=np.linspace(0.0, 3.0, 12))
    ax = viz.draw(sim, color_by=None)
    marks = next(c for c in ax.collections if c.get_gid() == "edmd2d-angles")
    segments = marks.get_segments()[:12]
    direction = np.array([s[1] - s[0] for s in segments])
    np.testing.assert_allclose(np.arctan2(direction[:, 1], direction[:, 0]),
                               np.angle(np.exp(1j * sim.angles)), atol=1e-12)
    np.testing.assert_allclose(np.hypot(*direction.T), sim.radii, rtol=1e-12)
    plain = viz.draw(ed.make_gas(12, 0.3, seed=1))
    assert "edmd2d-angles" not in [c.get_gid() for c in plain.collections]
    with pytest.raises(ValueError, match="angle_marks"):
        viz.draw(ed.make_gas(12, 0.3, seed=1), angle_marks=True)
