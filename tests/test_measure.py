"""measure(): exact hand-computed cases, the hard-disk equation of state against the
literature, kinetic theory, mixtures and walled boxes.

Statistical tests are seeded (deterministic) and their tolerances are built from the
block-average error bar of the run itself plus documented systematic allowances; each
test also bounds the error bar, so that a broken (inflated) error estimate cannot make
a test pass vacuously.  The default runs are short; ``-m slow`` runs longer versions.
"""

from __future__ import annotations

import doctest
import importlib
import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d import theory

# The module (edmd2d.measurements) and the exported function measure() are distinct.
measure_module = importlib.import_module("edmd2d.measurements")

# Measured Z_N approaches Z_inf from below as -c Z / N with c ~ 0.4 at eta = 0.3 and
# 0.5 (python examples/eos_table.py --finite-size: N = 256 ... 16384); allow 2.5 times that.
FINITE_SIZE = 1.0

# Tolerance in units of the block-average standard error.  With 10-20 blocks the error
# estimate itself is uncertain by ~25%, so 4 sigma keeps a correct result inside with
# room, while the guards on the error bar keep the tests sharp.
K_SIGMA = 4.0


def equilibrated_gas(n, eta, seed, collisions_per_disk=100, **kwargs):
    """make_gas, then run until the lattice start has melted (~100 collisions per disk)."""
    sim = ed.make_gas(n, eta, seed=seed, **kwargs)
    sim.advance(collisions=collisions_per_disk * n // 2)
    return sim


def enskog_rate(eta, z):
    """Collision rate per disk of equal unit disks (sigma = 1, m = 1, kT = 1)."""
    return theory.enskog_collision_rate(theory.number_density(eta), 1.0,
                                        theory.contact_value(z, eta))


def virial_series_tail(eta):
    """A bound on the terms the B_10 virial series leaves out: the coefficients of
    eta^(k-1) grow like k + 0.2 up to k = 10 (theory.virial_z); bound them by k + 1."""
    return sum((k + 1) * eta ** (k - 1) for k in range(11, 200))


def reference_z(eta):
    """Literature interval (lo, hi) for Z of the infinite system.

    Dilute to moderate fluid (eta <= 0.3): the virial series to B_10 (exact B_2..B_4,
    Clisby-McCoy B_5..B_10) plus a bound on the truncated terms.  Dense fluid up to
    eta = 0.6: between the Santos-Lopez de Haro-Yuste EOS (below the data there) and
    Henderson's (above), the two classic closed forms.  (Beyond ~0.62 the SHY curve
    rises above the data: examples/equation_of_state.py.)
    """
    if eta <= 0.3:
        z = theory.virial_z(eta)
        return z, z + virial_series_tail(eta)
    return theory.santos_z(eta), theory.henderson_z(eta)


# --------------------------------------------------------------------------- exact cases
def test_two_disks_head_on_periodic_exact():
    # Disks of radius 0.5 at x = 2 and 5, velocities +-1, in a periodic 10 x 10 box:
    # they meet at t = 1 and then every (W - 2) / 2 = 4 time units through the boundary.
    # Each collision: impulse J = mu * 4 = 2, contact distance 1, so sum J r = 2 C.
    # Momentum is conserved (dof = 2N - 2 = 2): kT = (1 + 1) / 2 = 1.
    # Z = 1 + 2C / (2 t N kT) = 1 + (C / t) / 2 = 1 + 1 / (W - 2);  rate = 2C / (N t).
    box = ed.Box(10.0, 10.0)
    sim = ed.Simulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]], radii=0.5,
                        box=box)
    sim.advance(until=0.5)
    m = sim.measure(duration=40.0, blocks=10)
    assert m.collisions == 10
    assert m.degrees_of_freedom == 2
    assert m.temperature == pytest.approx(1.0, rel=1e-14)
    assert m.compressibility_factor == pytest.approx(1.0 + 1.0 / 8.0, rel=1e-12)
    assert m.pressure == pytest.approx(1.125 * 2 / 100.0, rel=1e-12)
    assert m.collision_rate == pytest.approx(0.25, rel=1e-12)
    assert m.mean_free_time == pytest.approx(4.0, rel=1e-12)
    assert m.mean_free_path == pytest.approx(4.0, rel=1e-12)  # each disk flies 4 between hits
    # Every block holds exactly one collision: the block values agree.
    assert m.compressibility_factor_error == pytest.approx(0.0, abs=1e-12)
    assert math.isnan(m.wall_pressure)
    assert all(math.isnan(p) for p in m.box_wall_pressures)
    assert m.segment_force == 0.0
    assert sim.time == pytest.approx(40.5)


@pytest.mark.parametrize("mirror", [1.0, -1.0])
def test_two_disks_on_a_diagonal_give_the_shear_pressure_exactly(mirror):
    # Two disks (radius 0.5, mass 1) 1.5 apart along the diagonal n = (mirror, 1) /
    # sqrt(2), closing at speed sqrt(2), in a periodic 10 x 10 box: they meet once in
    # the window (at t = 0.5 / sqrt(2)), with the impulse J = mu (1 + e) sqrt(2) =
    # sqrt(2) at the distance 1, so sum J |r| n_x n_y = mirror sqrt(2) / 2; their
    # velocities only swap, so sum m v_x v_y = mirror / 2 throughout, and with both
    # momenta conserved kT_xy = (mirror / 2) / (N - 1).  P_xy A = N kT_xy + sum J |r|
    # n_x n_y / t: it changes sign with the mirror image, P_xx does not.
    d = 1.5 / np.sqrt(2.0)
    sim = ed.Simulation([[5.0, 5.0], [5.0 + mirror * d, 5.0 + d]],
                        [[0.5 * mirror, 0.5], [-0.5 * mirror, -0.5]], radii=0.5,
                        box=ed.Box(10.0, 10.0))
    m = sim.measure(duration=4.0, blocks=2)
    assert m.collisions == 1
    expected = (2.0 * 0.5 + np.sqrt(2.0) / 2.0 / 4.0) / 100.0
    assert m.pressure_xy == pytest.approx(mirror * expected, rel=1e-12)
    assert m.pressure_xx == pytest.approx(expected, rel=1e-12)
    assert m.pressure_tensor[1, 0] == m.pressure_tensor[0, 1] == m.pressure_xy


def test_one_disk_between_walls_exact():
    # A disk (radius 0.5, mass 1, speed 2 along x) in a closed 10 x 6 box bounces between
    # x = 0.5 and x = 9.5: impulse 2 m v = 4 on each x-wall every 2 * 9 / 2 = 9 time units.
    # No momentum is conserved: dof = 2N = 2, kT = m v^2 / 2 = 2.
    box = ed.Box(10.0, 6.0, periodic=False)
    sim = ed.Simulation([[5.0, 3.0]], [[2.0, 0.0]], radii=0.5, box=box)
    sim.advance(until=1.0)
    m = sim.measure(duration=90.0, blocks=5)
    assert m.collisions == 0 and m.wall_collisions == 20
    assert m.degrees_of_freedom == 2
    assert m.temperature == pytest.approx(2.0)
    assert m.compressibility_factor == pytest.approx(1.0)
    force = 4.0 / 9.0
    assert m.box_wall_pressures == pytest.approx((force / 6, force / 6, 0.0, 0.0))
    assert m.wall_pressure == pytest.approx(2 * force / (2 * 6 + 2 * 10))
    # The virial theorem with the walls: (W - 2a) F_x + (H - 2a) F_y = 2 P A.
    assert 9.0 * force == pytest.approx(2 * m.pressure * box.area)
    assert m.collision_rate == 0.0 and m.mean_free_time == math.inf


def test_channel_and_obstacles_change_the_degrees_of_freedom():
    sim = ed.make_gas(50, 0.3, periodic=(True, False), seed=seed_of(1))
    assert measure_module.degrees_of_freedom(sim) == (99, (True, False))
    sim = ed.make_gas(50, 0.3, periodic=False, seed=seed_of(1))
    assert measure_module.degrees_of_freedom(sim) == (100, (False, False))
    sim = ed.Simulation([[1, 1], [3, 3], [6, 6]], [[1, 0], [0, 1], [0, 0]], radii=0.5,
                        masses=[1.0, 1.0, np.inf], box=ed.Box(10, 10))
    assert measure_module.degrees_of_freedom(sim) == (4, (False, False))
    # kT of the movable disks only, without subtracting the (not conserved) drift.
    assert ed.kinetic_temperature(sim) == pytest.approx(2 / 4)
    sim = ed.Simulation([[1, 1], [3, 3]], [[1, 0], [1, 0]], radii=0.5, box=ed.Box(10, 10),
                        walls=[ed.Wall((5, 0), (5, 4))])
    assert measure_module.degrees_of_freedom(sim) == (4, (False, False))


def test_centre_of_mass_drift_carries_no_heat():
    # In a periodic box a uniform drift is conserved and is not thermal motion.
    sim = ed.make_gas(100, 0.2, seed=seed_of(4))
    kt = ed.kinetic_temperature(sim)
    sim.set_velocities(sim.velocities + [3.0, -1.0])
    assert ed.kinetic_temperature(sim) == pytest.approx(kt, rel=1e-12)


def test_measurement_at_rest_and_bad_input():
    sim = ed.Simulation([[2.0, 5.0], [5.0, 5.0]], np.zeros((2, 2)), radii=0.5,
                        box=ed.Box(10, 10))
    m = ed.measure(sim, 1.0)
    assert m.temperature == 0.0 and m.collisions == 0
    assert math.isnan(m.compressibility_factor)
    with pytest.raises(TypeError, match="Simulation"):
        ed.measure(np.zeros((2, 2)), 1.0)
    with pytest.raises(ValueError, match="duration"):
        sim.measure(duration=0.0)
    with pytest.raises(ValueError, match="duration"):
        sim.measure(duration=math.inf)
    with pytest.raises(TypeError, match="duration"):
        sim.measure(duration="1")
    with pytest.raises(ValueError, match="blocks"):
        sim.measure(duration=1.0, blocks=0)
    with pytest.raises(TypeError, match="blocks"):
        sim.measure(duration=1.0, blocks=2.5)
    single = sim.measure(duration=1.0, blocks=1)
    assert math.isnan(single.pressure_error)


def test_summary_lists_the_values():
    sim = ed.make_gas(30, 0.2, periodic=False, seed=seed_of(2))
    text = sim.measure(duration=5.0).summary()
    assert "compressibility Z" in text and "wall pressure" in text


def test_docstring_examples():
    result = doctest.testmod(measure_module)
    assert result.attempted > 0 and result.failed == 0


# --------------------------------------------------------------------------- equation of state
ETAS = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6)


def run_eos(eta, n, collisions, seed, blocks=10):
    sim = equilibrated_gas(n, eta, seed)
    duration = 2.0 * collisions / (n * enskog_rate(eta, theory.henderson_z(eta)))
    return sim.measure(duration=duration, blocks=blocks)


@pytest.fixture(scope="module")
def eos_runs():
    """N = 1000 disks, ~1e6 collisions at each packing fraction (about 1 s each)."""
    return {eta: run_eos(eta, 1000, 1_000_000, seed=seed_of(10) + k) for k, eta in enumerate(ETAS)}


def check_eos(m, eta, rel_error_bound):
    lo, hi = reference_z(eta)
    z, err = m.compressibility_factor, m.compressibility_factor_error
    # Guard: the error bar is finite and as small as such a run gives (so the test
    # stays sharp); then Z must lie in the literature interval widened by K_SIGMA error
    # bars and the finite-size allowance (finite systems lie below, by ~0.4 Z / N).
    assert 0 < err < rel_error_bound * z
    slack = K_SIGMA * err
    assert lo - slack - FINITE_SIZE * hi / m.n <= z <= hi + slack, (eta, z, err, lo, hi)


@pytest.mark.parametrize("eta", ETAS)
def test_equation_of_state(eos_runs, eta):
    # ~1e6 collisions give a relative error of Z of about 5e-4 (eta = 0.5); bound 2e-3.
    check_eos(eos_runs[eta], eta, 2e-3)


@pytest.mark.parametrize("eta", ETAS)
def test_collision_rate_enskog_and_virial_agree(eos_runs, eta):
    m = eos_runs[eta]
    n_density = m.n / m.area
    kt = m.temperature
    # Contact value from the virial (Z = 1 + 2 eta g) and from the collision rate
    # (omega = 2 n sigma g sqrt(pi kT / m)): one g(sigma), two measurements.
    g_virial = theory.contact_value(m.compressibility_factor, eta)
    g_rate = m.collision_rate / (2 * n_density * math.sqrt(math.pi * kt))
    err_virial = m.compressibility_factor_error / (2 * eta)
    err_rate = m.collision_rate_error / (2 * n_density * math.sqrt(math.pi * kt))
    assert 0 < err_rate < 2e-3 * g_rate
    # Both come from the same collisions and fluctuate together, so the independent-
    # error sum is conservative; the finite-N difference is below 0.15 g / N.
    assert abs(g_virial - g_rate) <= K_SIGMA * math.hypot(err_virial, err_rate) + g_rate / m.n
    # And the rate against Enskog's formula with the literature contact value.
    lo, hi = reference_z(eta)
    rate_lo, rate_hi = enskog_rate(eta, lo), enskog_rate(eta, hi)
    slack = K_SIGMA * m.collision_rate_error
    assert (rate_lo * (1 - FINITE_SIZE * hi / ((hi - 1) * m.n)) - slack
            <= m.collision_rate <= rate_hi + slack)


def test_mean_free_path_dilute_limit(eos_runs):
    # Kinetic theory: lambda = <v> / omega; in 2D <v> = sqrt(pi kT / 2m).
    m = eos_runs[0.1]
    # The mean speed of N = 1000 Maxwellian disks scatters by 0.52 / sqrt(N) ~ 1.6%.
    assert m.mean_speed == pytest.approx(theory.mean_speed(m.temperature), rel=0.05)
    assert m.mean_free_path == pytest.approx(m.mean_speed / m.collision_rate, rel=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("eta", ETAS)
def test_equation_of_state_long(eta):
    # 4096 disks, 1.5e7 collisions: relative errors ~1e-4, the finite-size allowance
    # 2.5e-4 Z; the literature interval is then the limiting factor.
    m = run_eos(eta, 4096, 15_000_000, seed=seed_of(100), blocks=20)
    check_eos(m, eta, 5e-4)


# --------------------------------------------------------------------------- mixtures
def mixture_virial_identity(n, eta, windows, window_collisions, seed):
    """Measured collision virial against the equilibrium identity, window by window.

    For hard disks in equilibrium the normal relative speed u of a colliding pair
    (i, j) is flux-weighted Maxwellian, p(u) ~ u exp(-mu u^2 / 2kT), so one collision
    adds on average J r = 2 mu u sigma_ij = sigma_ij sqrt(2 pi mu kT) to the virial
    (mu = m_i m_j / (m_i + m_j)).  Counting the collisions of each pair type predicts
    the virial sum; the ratio measured / predicted must be 1.
    """
    radii = np.where(np.arange(n) % 2 == 0, 0.5, 0.7)
    masses = np.where(np.arange(n) % 2 == 0, 1.0, 2.0)
    sim = ed.make_gas(n, eta, radii=radii, masses=masses, seed=seed)
    sim.advance(collisions=100 * n)
    rad, mass = sim.radii, sim.masses
    e0, p0 = sim.kinetic_energy(), sim.momentum()
    kt = ed.kinetic_temperature(sim)
    ratios = []
    for _ in range(windows):
        sim._record_events(3 * window_collisions)
        before = sim._accumulators()["virial"]
        sim.advance(collisions=window_collisions)
        virial = sim._accumulators()["virial"] - before
        pairs = np.array([(i, j) for _, kind, i, j in sim._recorded_events() if kind == "disk"])
        assert len(pairs) == window_collisions
        sigma = rad[pairs[:, 0]] + rad[pairs[:, 1]]
        mu = mass[pairs[:, 0]] * mass[pairs[:, 1]] / (mass[pairs[:, 0]] + mass[pairs[:, 1]])
        ratios.append(virial / np.sum(sigma * np.sqrt(2 * np.pi * mu * kt)))
    return sim, np.array(ratios), e0, p0, kt


@pytest.mark.parametrize("eta", [0.3, 0.55])
def test_mixture_conserves_and_satisfies_the_virial_identity(eta):
    sim, ratios, e0, p0, kt = mixture_virial_identity(400, eta, 8, 40_000, seed=seed_of(7))
    # Conservation to rounding after ~4e5 collisions.
    assert sim.kinetic_energy() == pytest.approx(e0, rel=1e-11)
    assert np.abs(sim.momentum() - p0).max() < 1e-9
    assert ed.kinetic_temperature(sim) == pytest.approx(kt, rel=1e-11)
    # A collision's J r has a relative spread of 0.52 (Rayleigh), so one window of 4e4
    # collisions gives ~0.3%; the window-to-window spread measures it with correlations.
    err = np.std(ratios, ddof=1) / math.sqrt(len(ratios))
    assert 0 < err < 3e-3
    # Finite N: the microcanonical velocity distribution deviates at O(1/N).
    assert abs(ratios.mean() - 1.0) < K_SIGMA * err + 1.0 / len(sim)


@pytest.mark.slow
def test_mixture_virial_identity_long():
    # 2000 disks, 20 windows of 2e5 collisions: the window error drops to ~1e-4 and the
    # 1/N allowance to 5e-4.
    sim, ratios, *_ = mixture_virial_identity(2000, 0.5, 20, 200_000, seed=seed_of(17))
    err = np.std(ratios, ddof=1) / math.sqrt(len(ratios))
    assert 0 < err < 5e-4
    assert abs(ratios.mean() - 1.0) < K_SIGMA * err + 1.0 / len(sim)


def test_dilute_mixture_second_virial_coefficient():
    # The exact second virial coefficient of a 2D mixture: Z = 1 + B2 n + O(n^2) with
    # B2 = (pi / 2) sum_ij x_i x_j sigma_ij^2, sigma_ij = r_i + r_j.  At eta = 0.02 the
    # next term is about 3 eta^2 = 1.2e-3 for equal disks; allow 5 eta^2.
    n, eta = 400, 0.02
    radii = np.where(np.arange(n) % 2 == 0, 0.5, 0.7)
    sim = ed.make_gas(n, eta, radii=radii, seed=seed_of(3))
    sim.advance(collisions=20 * n)
    m = sim.measure(duration=3000.0, blocks=10)
    sigma = radii[:, None] + radii[None, :]
    b2 = 0.5 * math.pi * np.mean(sigma**2)  # x_i x_j sums = mean over all ordered pairs
    expected = 1.0 + b2 * n / sim.box.area
    assert 0 < m.compressibility_factor_error < 1e-3
    assert abs(m.compressibility_factor - expected) < K_SIGMA * m.compressibility_factor_error \
        + 5 * eta**2
    assert m.temperature == pytest.approx(1.0, rel=1e-12)


# --------------------------------------------------------------------------- walled boxes
def test_closed_box_wall_virial_identity():
    # Closed box, equal disks of radius a: the virial theorem including the wall forces
    # is (W - 2a) F_x + (H - 2a) F_y = 2 P A exactly in the time average (F: mean force
    # on one wall; the walls act on the centres at distance a).  The pressure side and
    # the wall side come from different accumulators (pair virial vs wall impulses).
    sim = equilibrated_gas(600, 0.4, seed=seed_of(5), periodic=False, aspect=1.5)
    e0 = sim.kinetic_energy()
    m = sim.measure(duration=400.0, blocks=20)
    box, a = sim.box, 0.5
    px0, pxw, py0, pyh = m.box_wall_pressures
    fx = 0.5 * (px0 + pxw) * box.height
    fy = 0.5 * (py0 + pyh) * box.width
    lhs = (box.width - 2 * a) * fx + (box.height - 2 * a) * fy
    rhs = 2 * m.pressure * box.area
    # Errors: the wall pressure's block error (all four walls) and the pressure's; the
    # two are correlated, adding them is conservative.
    err = 2 * box.area * m.pressure_error + lhs * m.wall_pressure_error / m.wall_pressure
    assert 0 < err < 0.01 * rhs
    assert abs(lhs - rhs) < K_SIGMA * err
    # Opposite walls feel the same pressure; energy is conserved at the walls.
    assert px0 == pytest.approx(pxw, rel=0.03) and py0 == pytest.approx(pyh, rel=0.03)
    assert sim.kinetic_energy() == pytest.approx(e0, rel=1e-11)
    assert m.degrees_of_freedom == 2 * 600


def test_walled_mixture_is_conserved_and_balanced():
    # A closed box of a 50:50 mixture (radii 0.5 / 0.7, masses 1 / 2): energy conserved
    # to rounding, no momentum conservation (dof = 2N), and opposite walls balanced
    # (the mean forces on x = 0 and x = W are equal in equilibrium).
    n = 500
    radii = np.where(np.arange(n) % 2 == 0, 0.5, 0.7)
    masses = np.where(np.arange(n) % 2 == 0, 1.0, 2.0)
    sim = ed.make_gas(n, 0.45, radii=radii, masses=masses, periodic=False, seed=seed_of(21))
    sim.advance(collisions=50 * n)
    e0 = sim.kinetic_energy()
    blocks = [sim.measure(duration=20.0, blocks=1) for _ in range(10)]
    assert sim.kinetic_energy() == pytest.approx(e0, rel=1e-11)
    assert {m.degrees_of_freedom for m in blocks} == {2 * n}
    assert all(m.temperature == pytest.approx(e0 / n, rel=1e-11) for m in blocks)
    walls = np.array([m.box_wall_pressures for m in blocks])
    diff_x, diff_y = walls[:, 0] - walls[:, 1], walls[:, 2] - walls[:, 3]
    for diff in (diff_x, diff_y):
        err = diff.std(ddof=1) / math.sqrt(len(diff))
        assert 0 < err < 0.02 * walls.mean()
        assert abs(diff.mean()) < K_SIGMA * err


def channel_wall_vs_bulk(n, eta, frames_per_block, blocks, seed, dt=2.0):
    """Wall pressure of a channel (periodic in x, walls at y = 0 and H) and the density
    in the middle of the channel, block by block (frames ``dt`` apart).

    In mechanical equilibrium the normal pressure P_yy is the same at every height, so
    the force per length on a planar wall is the bulk pressure of the fluid in the
    middle, at the middle's density (away from the wall layers).
    """
    sim = equilibrated_gas(n, eta, seed, periodic=(True, False), aspect=2.0)
    box = sim.box
    lo, hi = 0.25 * box.height, 0.75 * box.height
    wall_p, density = [], []
    for _ in range(blocks):
        p_frames, n_frames = [], []
        for _ in range(frames_per_block):
            p_frames.append(sim.measure(duration=dt, blocks=1).wall_pressure)
            y = sim.positions[:, 1]
            n_frames.append(np.count_nonzero((y > lo) & (y < hi)))
        wall_p.append(np.mean(p_frames))
        density.append(np.mean(n_frames) / ((hi - lo) * box.width))
    return np.array(wall_p), np.array(density), ed.kinetic_temperature(sim)


def check_channel(n, frames_per_block, blocks, seed, rel_error_bound):
    wall_p, density, kt = channel_wall_vs_bulk(n, 0.3, frames_per_block, blocks, seed)
    p_wall = wall_p.mean()
    p_wall_err = wall_p.std(ddof=1) / math.sqrt(len(wall_p))
    n_bulk = density.mean()
    n_err = density.std(ddof=1) / math.sqrt(len(density))
    eta_bulk = n_bulk * math.pi / 4
    p_bulk = n_bulk * kt * theory.virial_z(eta_bulk)  # the series is exact to ~1e-4 here
    # dP/dn = kT d(eta Z)/d eta carries the density's error into the bulk pressure.
    h = 1e-4
    dp_dn = kt * ((eta_bulk + h) * theory.virial_z(eta_bulk + h)
                  - (eta_bulk - h) * theory.virial_z(eta_bulk - h)) / (2 * h)
    err = math.hypot(p_wall_err, dp_dn * n_err)
    assert 0 < err < rel_error_bound * p_bulk
    # The finite channel adds an O(1/N) shift, as in the periodic EOS.
    assert abs(p_wall - p_bulk) < K_SIGMA * err + FINITE_SIZE * p_bulk / n


def test_channel_wall_pressure_equals_bulk_pressure():
    check_channel(800, 20, 10, seed=seed_of(8), rel_error_bound=0.01)


@pytest.mark.slow
def test_channel_wall_pressure_equals_bulk_pressure_long():
    check_channel(3000, 50, 20, seed=seed_of(18), rel_error_bound=0.003)


# --------------------------------------------------------------------------- relaxation
def equal_speed_gas(n, eta, seed):
    """A gas whose disks all have speed sqrt(kT_target * f / N) (f = 2N - 2): pairs of
    disks get opposite velocities, so the total momentum is exactly zero."""
    sim = ed.make_gas(n, eta, seed=seed)
    rng = np.random.default_rng(seed)
    angle = rng.uniform(0, 2 * np.pi, n // 2)
    half = np.column_stack([np.cos(angle), np.sin(angle)])
    vel = np.empty((n, 2))
    vel[0::2], vel[1::2] = half, -half
    vel *= math.sqrt((2 * n - 2) / n)  # kT = 1 with f = 2N - 2
    sim.set_velocities(vel)
    return sim


def speed_moment_ratio(sim):
    """<v^4> / <v^2>^2: 1 for equal speeds, 2 for 2D Maxwell-Boltzmann."""
    v2 = np.einsum("ij,ij->i", sim.velocities, sim.velocities)
    return float(np.mean(v2**2) / np.mean(v2) ** 2)


def test_relaxation_to_maxwell_boltzmann():
    n = 2000
    sim = equal_speed_gas(n, 0.25, seed=seed_of(11))
    assert speed_moment_ratio(sim) == pytest.approx(1.0)
    assert ed.maxwell_boltzmann_test(sim).pvalue < 1e-30
    assert np.allclose(sim.momentum(), 0.0, atol=1e-10)
    # After ~10 collisions per disk the speeds are Maxwellian: KS test of e / kT against
    # the unit exponential (seeded, so deterministic; H0 true gives p ~ U(0, 1)).
    sim.advance(collisions=10 * n // 2)
    assert ed.maxwell_boltzmann_test(sim).pvalue > 0.01
    # The fourth moment: R = <v^4>/<v^2>^2 has standard error 2 / sqrt(N) for N
    # Maxwellian disks (delta method on exponential energies); average 5 snapshots
    # several collision times apart.
    ratios = []
    for _ in range(5):
        sim.advance(collisions=5 * n // 2)
        ratios.append(speed_moment_ratio(sim))
    assert abs(np.mean(ratios) - 2.0) < K_SIGMA * 2 / math.sqrt(n)
    assert ed.kinetic_temperature(sim) == pytest.approx(1.0, rel=1e-11)


def test_pressure_tensor_diagonal():
    # Periodic fluid: isotropic, and the mean of the diagonal is the scalar pressure
    # (exactly for the virial part; the kinetic part is split per axis).
    sim = ed.make_gas(1500, 0.5, seed=seed_of(21))
    sim.advance(collisions=60_000)
    m = sim.measure(duration=15.0)
    assert 0.5 * (m.pressure_xx + m.pressure_yy) == pytest.approx(m.pressure, rel=2e-3)
    # The two axes are equivalent: their difference is noise of a few error bars.
    assert abs(m.pressure_xx - m.pressure_yy) < 6 * m.pressure_error * np.sqrt(2) + 0.01
    # At rest, a fluid carries no shear stress: P_xy is noise, within 5 of its own
    # block error bars (20 blocks: a false alarm about once in 10^4 runs), and that
    # error bar is of the size of the diagonal's.
    m = sim.measure(duration=30.0, blocks=20)
    err = m.pressure_tensor_error[0, 1]
    assert 0.2 * m.pressure_tensor_error[0, 0] < err < 5.0 * m.pressure_tensor_error[0, 0]
    assert abs(m.pressure_xy) < 5.0 * err
    assert np.trace(m.pressure_tensor) / 2 == pytest.approx(m.pressure, rel=2e-3)


def test_channel_normal_pressure_equals_wall_pressure():
    # In a channel (periodic in x, walls at y = 0 and H) the momentum flux normal to the
    # walls is the force per length on them.  Centres cannot enter the layers of
    # thickness r at the walls, so the virial P_yy over the whole area A = W H relates to
    # it as P_yy A = P_wall W (H - 2r).  Both sides come from the same run; their
    # estimators differ (wall impulses vs collision virial), so allow 1.5%.
    sim = ed.make_gas(2000, 0.4, periodic=(True, False), aspect=4.0, seed=seed_of(22))
    sim.advance(collisions=100_000)
    m = sim.measure(duration=40.0)
    height = sim.box.height
    assert m.pressure_yy * height / (height - 2 * 0.5) == pytest.approx(m.wall_pressure,
                                                                        rel=0.015)
