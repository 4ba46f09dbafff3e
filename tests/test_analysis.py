"""Structure and dynamics helpers: g(r), speed statistics, MSD, psi_6."""

from __future__ import annotations

import doctest
import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d import analysis, theory


def frame_scatter_z(pts, box, **kwargs):
    """g(r) of all frames, and each bin's deviation from 1 in units of the standard
    error that the scatter of the frames' own g(r) gives.  Pair counts are not Poisson
    in a box with walls (a point near a wall has fewer partners), so the error comes
    from the frames, which are independent: the deviations are Student's t with
    ``frames - 1`` degrees of freedom."""
    r, g = ed.radial_distribution(pts, box, **kwargs)
    each = np.array([ed.radial_distribution(p, box, **kwargs)[1] for p in pts])
    np.testing.assert_allclose(each.mean(axis=0), g, rtol=1e-12)  # (n fixed per frame)
    error = each.std(axis=0, ddof=1) / math.sqrt(len(pts))
    pooled = each.mean(axis=1)  # each frame's mean over the bins
    pooled_z = (pooled.mean() - 1.0) / (pooled.std(ddof=1) / math.sqrt(len(pts)))
    return r, g, (g - 1.0) / error, pooled_z


# --------------------------------------------------------------------------- g(r)
@pytest.mark.parametrize("periodic", [True, (True, False), (False, True), False])
def test_rdf_of_uniform_points_is_one(periodic):
    # Uniform independent points are an ideal gas: g(r) = 1 in every box.  In a walled
    # box pairs at large r are rarer (the edge correction): without it g(10) here would
    # be ~40% low, far outside the Poisson tolerance.
    rng = np.random.default_rng(seed_of(5))
    box = ed.Box(30.0, 24.0, periodic=periodic)
    frames, n, bins, r_max = 40, 500, 20, 10.0 if periodic is True else 20.0
    if periodic is not True:
        r_max = 10.0
    pts = rng.uniform([0, 0], [box.width, box.height], size=(frames, n, 2))
    r, g, z, pooled_z = frame_scatter_z(pts, box, r_max=r_max, bins=bins)
    # 20 bins of t with 39 degrees of freedom: a chance of 3e-4 that one passes 5.
    assert np.abs(z).max() < 5.0
    # The mean over all bins, whose frame-to-frame scatter is 0.3 % in a walled box
    # (the bins of a frame move together): no normalisation error beyond it.
    assert abs(pooled_z) < 5.0


def test_rdf_margin_for_disk_centres():
    # Centres confined to [a, L - a] (disks of radius a between walls): margin=a.
    rng = np.random.default_rng(seed_of(6))
    box = ed.Box(20.0, 20.0, periodic=False)
    a = 2.0
    pts = rng.uniform(a, 20.0 - a, size=(40, 400, 2))
    r, g, z, _ = frame_scatter_z(pts, box, r_max=8.0, bins=16, margin=a)
    assert np.abs(z).max() < 5.0  # (as above, 16 bins)
    # Ignoring the margin normalises by the wrong region: a large, visible error.
    _, g_wrong = ed.radial_distribution(pts, box, r_max=8.0, bins=16)
    assert np.abs(g_wrong - 1).max() > 0.2


def test_rdf_minimum_image_pair():
    box = ed.Box(10.0, 10.0)
    r, g = ed.radial_distribution([[0.2, 5.0], [9.7, 5.0]], box, r_max=2.0, bins=4)
    # One pair at distance 0.5 through the boundary, in the bin [0.5, 1.0).
    assert np.flatnonzero(g).tolist() == [1]
    # Its g: one pair over the ideal 1 * (pi (1^2 - 0.5^2) / 100) pairs.
    assert g[1] == pytest.approx(1.0 / (math.pi * 0.75 / 100.0))
    # Through a wall there is no image: the pair is 9.5 apart.
    walled = ed.Box(10.0, 10.0, periodic=False)
    _, g = ed.radial_distribution([[0.2, 5.0], [9.7, 5.0]], walled, r_max=2.0, bins=4)
    assert not g.any()


def test_rdf_hard_disk_fluid_contact_value_matches_virial():
    # g(r) of a dense fluid: zero inside the core, and its contact value (extrapolated
    # with an exponential fit over [sigma, 1.1 sigma]) equals (Z - 1) / (2 eta) of the
    # virial.  200 frames give the fit a ~1% scatter; allow 3%.
    sim = ed.make_gas(1000, 0.5, seed=seed_of(3))
    sim.advance(collisions=100 * 500)
    z = sim.measure(duration=100.0).compressibility_factor
    frames = []
    for _ in range(200):
        sim.advance(until=sim.time + 0.5)
        frames.append(sim.positions)
    r, g = ed.radial_distribution(np.array(frames), sim.box, r_max=1.5, bins=150)
    assert not g[r < 1.0].any()
    sel = (r > 1.0) & (r < 1.1)
    slope, intercept = np.polyfit(r[sel] - 1.0, np.log(g[sel]), 1)
    assert slope < 0
    assert math.exp(intercept) == pytest.approx(theory.contact_value(z, 0.5), rel=0.03)


def test_rdf_of_a_simulation_uses_its_box_and_radii():
    sim = ed.make_gas(200, 0.1, periodic=False, seed=seed_of(4))
    sim.advance(until=50.0)  # (stopping at a collision would leave a pair at contact)
    r, g = ed.radial_distribution(sim, r_max=5.0, bins=50)
    assert len(r) == 50 and not g[r < 0.99].any()
    r2, g2 = ed.radial_distribution(sim.positions, sim.box, r_max=5.0, bins=50, margin=0.5)
    assert np.allclose(g, g2)


def test_rdf_bad_input():
    box = ed.Box(10.0, 10.0)
    pts = np.random.default_rng(seed_of(0)).uniform(0, 10, (50, 2))
    with pytest.raises(ValueError, match="r_max"):
        ed.radial_distribution(pts, box, r_max=6.0)
    with pytest.raises(TypeError, match="box is required"):
        ed.radial_distribution(pts)
    with pytest.raises(TypeError, match="edmd2d.Box"):
        ed.radial_distribution(pts, (10, 10))
    with pytest.raises(ValueError, match="bins"):
        ed.radial_distribution(pts, box, bins=0)
    with pytest.raises(ValueError, match="shape"):
        ed.radial_distribution(np.zeros((5, 3)), box)
    with pytest.raises(ValueError, match="at least 2"):
        ed.radial_distribution(np.zeros((1, 2)), box)
    with pytest.raises(ValueError, match="margin"):
        ed.radial_distribution(pts, ed.Box(10, 10, periodic=False), margin=5.0)
    with pytest.raises(ValueError, match="outside the walled y"):
        ed.radial_distribution(pts + [0, 1], ed.Box(10, 10, periodic=(True, False)))
    sim = ed.make_gas(10, 0.1, seed=seed_of(0))
    with pytest.raises(TypeError, match="own box"):
        ed.radial_distribution(sim, box)


# --------------------------------------------------------------------------- speeds
def test_speed_distribution_matches_maxwell_boltzmann():
    rng = np.random.default_rng(seed_of(2))
    vel = rng.normal(size=(200_000, 2)) * math.sqrt(2.0)  # kT / m = 2
    v, f = ed.speed_distribution(vel, bins=40, v_max=8.0)
    expected = theory.maxwell_boltzmann_speed_pdf(v, temperature=2.0)
    width = v[1] - v[0]
    # Each bin holds ~ N f width samples: Poisson error sqrt(N f width) / (N width).
    err = np.sqrt(expected * width * len(vel)) / (len(vel) * width) + 1e-3
    assert np.all(np.abs(f - expected) < 5 * err)


def test_maxwell_boltzmann_test_uses_masses():
    rng = np.random.default_rng(seed_of(3))
    mass = np.where(np.arange(4000) % 2 == 0, 1.0, 4.0)
    vel = rng.normal(size=(4000, 2)) / np.sqrt(mass)[:, None]  # kT = 1
    assert ed.maxwell_boltzmann_test(vel, masses=mass, temperature=1.0).pvalue > 0.01
    assert ed.maxwell_boltzmann_test(vel, masses=1.0, temperature=1.0).pvalue < 1e-10
    with pytest.raises(ValueError, match="temperature"):
        ed.maxwell_boltzmann_test(vel, temperature=0.0)
    with pytest.raises(ValueError, match="masses"):
        ed.maxwell_boltzmann_test(vel, masses=-mass)
    with pytest.raises(ValueError, match="temperature must be > 0"):
        ed.maxwell_boltzmann_test(np.zeros((3, 2)))


def test_mixture_equipartition_and_maxwell_boltzmann():
    # Disks of mass 1 and 4 (radii 0.5, 0.7): after relaxation each species carries
    # kT of kinetic energy per disk (2D equipartition) and the energies are exponential.
    n = 1000
    radii = np.where(np.arange(n) % 2 == 0, 0.5, 0.7)
    masses = np.where(np.arange(n) % 2 == 0, 1.0, 4.0)
    sim = ed.make_gas(n, 0.35, radii=radii, masses=masses, seed=seed_of(9))
    # Give all the energy to the light disks: far from equilibrium.
    vel = sim.velocities.copy()
    vel[1::2] = 0.0
    sim.set_velocities(vel - (masses @ vel) / masses.sum())
    kt = ed.kinetic_temperature(sim)
    assert ed.maxwell_boltzmann_test(sim).pvalue < 1e-10
    sim.advance(collisions=30 * n)
    assert ed.maxwell_boltzmann_test(sim).pvalue > 0.01
    light, heavy = [], []
    for _ in range(5):
        sim.advance(collisions=10 * n)
        e = 0.5 * sim.masses * np.einsum("ij,ij->i", sim.velocities, sim.velocities)
        light.append(e[0::2].mean())
        heavy.append(e[1::2].mean())
    # Each mean over 500 exponential energies has a relative error 1/sqrt(500) = 4.5%;
    # five snapshots 10 collision times apart: ~2%, so 8% is four standard errors.  The
    # start had the heavy disks at rest (their mean energy 0, not kT).
    assert np.mean(light) == pytest.approx(kt, rel=0.08)
    assert np.mean(heavy) == pytest.approx(kt, rel=0.08)


def test_speed_distribution_bad_input():
    with pytest.raises(ValueError, match="bins"):
        ed.speed_distribution(np.ones((3, 2)), bins=0)
    with pytest.raises(ValueError, match="shape"):
        ed.speed_distribution(np.ones((3, 3)))
    with pytest.raises(ValueError, match="v_max"):
        ed.speed_distribution(np.ones((3, 2)), v_max=-1.0)
    with pytest.raises(TypeError, match="masses"):
        ed.maxwell_boltzmann_test(ed.make_gas(5, 0.1, seed=seed_of(0)), masses=1.0)


# --------------------------------------------------------------------------- MSD
def test_msd_of_a_free_disk_across_periodic_boundaries():
    # One disk alone in a small periodic box flies straight, wrapping many times: the
    # unwrapped displacement is v t exactly.
    sim = ed.Simulation([[1.0, 1.0]], [[1.3, -0.7]], radii=0.5, box=ed.Box(3.0, 3.0))
    times, pos = ed.trajectory(sim, 0.9, 30)
    assert times[-1] == pytest.approx(0.9 * 29) and sim.time == pytest.approx(times[-1])
    msd = ed.mean_squared_displacement(pos)
    lag_time = 0.9 * np.arange(30)
    assert msd == pytest.approx((1.3**2 + 0.7**2) * lag_time**2, rel=1e-12, abs=1e-12)
    assert abs(pos[-1, 0, 0] - pos[0, 0, 0]) > 3 * 3.0  # crossed the box several times


def test_msd_of_a_gas_ballistic_then_slower():
    sim = ed.make_gas(500, 0.3, seed=seed_of(12))
    sim.advance(collisions=50 * 250)
    v2 = np.mean(np.einsum("ij,ij->i", sim.velocities, sim.velocities))
    mft = 1.0 / theory.enskog_collision_rate(
        theory.number_density(0.3), 1.0, theory.contact_value(theory.henderson_z(0.3), 0.3))
    dt = 0.002 * mft
    _, pos = ed.trajectory(sim, dt, 5)
    msd = ed.mean_squared_displacement(pos)
    # Within 0.008 mean free times at most ~1% of the disks collide: free flight.
    assert msd[1:] == pytest.approx(v2 * (dt * np.arange(1, 5)) ** 2, rel=0.02)
    # Over 30 mean free times collisions randomise the direction: far below v^2 t^2,
    # and growing roughly linearly (diffusion, MSD ~ 4 D t).
    _, pos = ed.trajectory(sim, 3 * mft, 11)
    msd = ed.mean_squared_displacement(pos)
    assert msd[10] < 0.1 * v2 * (30 * mft) ** 2
    assert 1.3 < msd[10] / msd[5] < 2.7


def test_msd_bad_input():
    with pytest.raises(ValueError, match="max_lag"):
        ed.mean_squared_displacement(np.zeros((3, 2, 2)), max_lag=3)
    with pytest.raises(ValueError, match="shape"):
        ed.mean_squared_displacement(np.zeros((3, 2)))
    assert ed.mean_squared_displacement(np.zeros((3, 2, 2)), max_lag=1).tolist() == [0, 0]
    with pytest.raises(TypeError, match="Simulation"):
        ed.trajectory(np.zeros((3, 2)), 1.0, 3)
    sim = ed.make_gas(5, 0.1, seed=seed_of(0))
    with pytest.raises(ValueError, match="interval"):
        ed.trajectory(sim, 0.0, 3)
    with pytest.raises(ValueError, match="frames"):
        ed.trajectory(sim, 1.0, 0)


# --------------------------------------------------------------------------- psi_6
def triangular_lattice(nx, ny, spacing=1.0, angle=0.0, origin=(0.0, 0.0)):
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    x = (i + 0.5 * (j % 2)).ravel() * spacing
    y = (j * math.sqrt(3) / 2).ravel() * spacing
    c, s = math.cos(angle), math.sin(angle)
    return np.column_stack([c * x - s * y, s * x + c * y]) + origin


@pytest.mark.parametrize("neighbors", ["voronoi", 1.2])
def test_psi6_of_a_periodic_triangular_lattice_is_one(neighbors):
    pts = triangular_lattice(12, 10, spacing=1.1) + [0.3, 0.2]
    box = ed.Box(12 * 1.1, 10 * 1.1 * math.sqrt(3) / 2)
    psi, local = ed.hexatic_order(pts, box, neighbors=1.3 if neighbors == 1.2 else neighbors)
    assert abs(psi) == pytest.approx(1.0, abs=1e-12)
    assert np.abs(local) == pytest.approx(np.ones(len(pts)), abs=1e-12)
    # Along x the bonds are at 0 and 60 degrees: psi_6 = exp(0) = 1.
    assert psi.real == pytest.approx(1.0, abs=1e-12)


def test_psi6_of_a_rotated_lattice_in_a_walled_box():
    # Rotation changes the phase, not the magnitude: exp(6 i * angle).
    angle = 0.2
    pts = triangular_lattice(10, 10, angle=angle, origin=(8.0, 2.0))
    box = ed.Box(30.0, 30.0, periodic=False)
    psi, local = ed.hexatic_order(pts, box, neighbors=1.1)
    assert np.abs(local) == pytest.approx(np.ones(len(pts)), abs=1e-12)
    assert psi == pytest.approx(np.exp(6j * angle), abs=1e-12)


def test_psi6_of_a_square_lattice_vanishes():
    i, j = np.meshgrid(np.arange(10), np.arange(10))
    pts = np.column_stack([i.ravel(), j.ravel()]) + 0.5
    psi, local = ed.hexatic_order(pts, ed.Box(10.0, 10.0), neighbors=1.1)
    assert abs(psi) < 1e-12 and np.abs(local).max() < 1e-12


def test_psi6_of_a_fluid_is_small_and_voronoi_degree_is_six():
    sim = ed.make_gas(1000, 0.4, seed=seed_of(13))
    sim.advance(collisions=100 * 500)
    psi, local = ed.hexatic_order(sim)
    # An isotropic fluid: |Psi_6| ~ 1/sqrt(N) times a short correlation factor.
    assert abs(psi) < 0.1
    assert 0.2 < np.mean(np.abs(local)) < 0.8
    # Euler: a triangulation of the torus has on average exactly 6 edges per vertex.
    i, _ = analysis._voronoi_pairs(sim.positions, sim.box)
    assert 2 * len(i) == 6 * len(sim)


def test_psi6_bad_input():
    box = ed.Box(10.0, 10.0)
    pts = np.random.default_rng(seed_of(1)).uniform(0, 10, (20, 2))
    with pytest.raises(ValueError, match="neighbors"):
        ed.hexatic_order(pts, box, neighbors="delaunay")
    with pytest.raises(ValueError, match="cutoff"):
        ed.hexatic_order(pts, box, neighbors=6.0)
    with pytest.raises(ValueError, match="at least 3"):
        ed.hexatic_order(pts[:2], box)
    with pytest.raises(ValueError, match="one configuration"):
        ed.hexatic_order(np.array([pts, pts]), box)


def test_docstring_examples():
    result = doctest.testmod(analysis)
    assert result.attempted > 0 and result.failed == 0


_RDF_MEMORY = r"""
import resource, sys
import numpy as np
import edmd2d as ed
n = 100_000
box = ed.Box(400.0, 400.0)
pos = np.random.default_rng(0).uniform(0.0, 400.0, (n, 2))
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
r, g = ed.radial_distribution(pos, box)
grown = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) * 1024
print(r[-1], abs(g[len(g) // 2:] - 1).max(), grown / n)
"""


def test_rdf_default_range_runs_in_memory_linear_in_n():
    # 10^5 disks: half the box (the earlier default) would count 10^9-10^10 pairs.
    # Five mean spacings (here 5 * 400 / sqrt(10^5) = 6.3) are counted, not listed:
    # the process grows by well under a kilobyte per disk.
    import os
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _RDF_MEMORY], capture_output=True,
                         text=True, timeout=300, check=True, env=dict(os.environ)).stdout
    r_last, deviation, bytes_per_disk = map(float, out.split())
    assert 6.0 < r_last < 6.33
    assert deviation < 0.05  # (uniform points: g = 1)
    assert bytes_per_disk < 1000


@pytest.mark.parametrize("periodic", [True, False, (True, False)])
def test_voronoi_cells_tile_the_box(periodic):
    """Cells wrap on periodic axes and end at walls (mirror images): they tile the box,
    and a lattice gas has local packing fractions around its packing fraction."""
    sim = ed.make_gas(300, 0.5, periodic=periodic, seed=seed_of(1))
    areas = ed.voronoi_cell_areas(sim)
    assert areas.sum() == pytest.approx(sim.box.area, rel=1e-12)
    assert np.all(areas > 0)
    assert ed.local_packing_fractions(sim).mean() == pytest.approx(0.5, abs=0.01)


def test_voronoi_cells_of_lattices():
    """Unit squares of a square lattice in a walled box; the triangular lattice at
    contact packs every disk at pi / (2 sqrt 3)."""
    i, j = np.meshgrid(np.arange(5), np.arange(4))
    pts = np.column_stack([i.ravel() + 0.5, j.ravel() + 0.5])
    np.testing.assert_allclose(ed.voronoi_cell_areas(pts, ed.Box(5.0, 4.0, periodic=False)),
                               1.0, rtol=1e-12)
    i, j = np.meshgrid(np.arange(6), np.arange(6))
    s = 1.0 + 1e-12
    tri = np.column_stack([((i + 0.5 * (j % 2)) * s).ravel(), (j * s * np.sqrt(3) / 2).ravel()])
    sim = ed.Simulation(tri, np.zeros_like(tri), 0.5, box=ed.Box(6 * s, 6 * s * np.sqrt(3) / 2))
    np.testing.assert_allclose(ed.local_packing_fractions(sim), np.pi / (2 * np.sqrt(3)),
                               rtol=1e-10)
    with pytest.raises(ValueError, match="share a centre"):
        ed.voronoi_cell_areas([[1.0, 1.0], [1.0, 1.0], [2.0, 2.0]], ed.Box(4.0, 4.0))
    with pytest.raises(TypeError, match="Simulation"):
        ed.local_packing_fractions(pts)
