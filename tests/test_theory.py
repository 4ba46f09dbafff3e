"""Reference values: hard-disk equations of state and 2D kinetic theory."""

from __future__ import annotations

import doctest
import math

import numpy as np
import pytest
from scipy import integrate

from conftest import seed_of
from edmd2d import theory


def second_order_coefficient(f, eta=1e-4):
    """(f(eta) - 1 - 2 eta) / eta^2: the eta^2 coefficient, to O(eta)."""
    return (f(eta) - 1.0 - 2.0 * eta) / eta**2


def test_virial_series_has_the_exact_low_order_coefficients():
    # B2 / a = 2, B3 / a^2 = 16/3 - 4 sqrt(3)/pi, B4 / a^3 = 16 - 36 sqrt(3)/pi + 80/pi^2
    # (a the disk area): Z = 1 + 2 eta + 3.1280 eta^2 + 4.2579 eta^3 + ...
    eta = 0.01
    b3 = (theory.virial_z(eta, 3) - theory.virial_z(eta, 2)) / eta**2
    b4 = (theory.virial_z(eta, 4) - theory.virial_z(eta, 3)) / eta**3
    assert theory.virial_z(eta, 2) == pytest.approx(1 + 2 * eta, rel=1e-15)
    assert b3 == pytest.approx(16 / 3 - 4 * math.sqrt(3) / math.pi, rel=1e-9)
    assert b4 == pytest.approx(16 - 36 * math.sqrt(3) / math.pi + 80 / math.pi**2, rel=1e-7)
    assert b3 == pytest.approx(3.1280, abs=1e-4) and b4 == pytest.approx(4.2579, abs=1e-4)


def test_closed_forms_agree_with_the_virial_series_at_low_density():
    # Henderson: 1 + 2 eta + 3.125 eta^2 (B3 within 0.1%); SHY: exact B2 only.
    for eta in (0.01, 0.05):
        assert theory.henderson_z(eta) == pytest.approx(theory.virial_z(eta), abs=10 * eta**3)
        assert theory.santos_z(eta) == pytest.approx(theory.virial_z(eta), abs=2 * eta**2)
    assert second_order_coefficient(theory.henderson_z) == pytest.approx(3.125, abs=1e-3)
    # SHY: 4 - (2 eta_max - 1) / eta_max^2 = 3.0105, 4% below the exact 3.1280.
    assert second_order_coefficient(theory.santos_z) == pytest.approx(3.0105, abs=1e-3)
    assert second_order_coefficient(theory.virial_z) == pytest.approx(3.1280, abs=1e-3)


def test_santos_diverges_at_close_packing():
    assert theory.ETA_CLOSE_PACKED == pytest.approx(0.9068996821, rel=1e-10)
    assert theory.santos_z(theory.ETA_CLOSE_PACKED - 1e-6) > 1e5
    with pytest.raises(ValueError, match="packing fraction"):
        theory.santos_z(theory.ETA_CLOSE_PACKED)


def test_vectorised_and_validated():
    eta = np.array([0.1, 0.3, 0.5])
    for f in (theory.henderson_z, theory.santos_z, theory.virial_z):
        z = f(eta)
        assert z.shape == (3,) and np.all(np.diff(z) > 0)
        assert isinstance(f(0.2), float)
        for bad in (-0.1, 1.0, math.nan):
            with pytest.raises(ValueError, match="packing fraction"):
                f(bad)
    with pytest.raises(ValueError, match="order"):
        theory.virial_z(0.1, order=11)
    with pytest.raises(ValueError, match="order"):
        theory.virial_z(0.1, order=1)


def test_contact_value_inverts_the_virial_relation():
    eta = 0.45
    g = theory.contact_value(theory.henderson_z(eta), eta)
    assert 1 + 2 * eta * g == pytest.approx(theory.henderson_z(eta), rel=1e-14)
    # The dilute limit: g(sigma) -> 1 (from B2 alone).
    assert theory.contact_value(theory.virial_z(1e-8), 1e-8) == pytest.approx(1.0, rel=1e-6)
    with pytest.raises(ValueError, match="packing fraction"):
        theory.contact_value(1.0, 0.0)


def test_maxwell_boltzmann_speed_moments():
    kt, m = 1.7, 2.3
    pdf = lambda v: theory.maxwell_boltzmann_speed_pdf(v, kt, m)  # noqa: E731
    top = 40 * math.sqrt(kt / m)
    assert integrate.quad(pdf, 0, top)[0] == pytest.approx(1.0, rel=1e-10)
    mean = integrate.quad(lambda v: v * pdf(v), 0, top)[0]
    assert mean == pytest.approx(theory.mean_speed(kt, m), rel=1e-10)
    # 2D equipartition: <m v^2 / 2> = kT (two quadratic degrees of freedom).
    second = integrate.quad(lambda v: v * v * pdf(v), 0, top)[0]
    assert 0.5 * m * second == pytest.approx(kt, rel=1e-10)
    assert theory.maxwell_boltzmann_speed_pdf(-1.0) == 0.0
    with pytest.raises(ValueError, match="temperature"):
        theory.maxwell_boltzmann_speed_pdf(1.0, temperature=0.0)


def test_enskog_rate_matches_the_relative_speed_average():
    # omega = n g sigma * integral over the contact circle of the approach flux:
    # <|u| * 2 sigma> with u the relative velocity of two Maxwellian disks (mass m,
    # temperature kT): u is Gaussian with variance 2 kT / m per component.  Compute
    # <|u|> by quadrature and compare with sqrt(pi kT / m).
    kt, m = 0.8, 1.5
    s2 = 2 * kt / m
    mean_u = integrate.quad(lambda u: u * (u / s2) * math.exp(-u * u / (2 * s2)), 0, 60)[0]
    assert mean_u == pytest.approx(math.sqrt(math.pi * kt / m), rel=1e-10)
    n, sigma, g = 0.3, 1.2, 2.1
    omega = theory.enskog_collision_rate(n, sigma, g, temperature=kt, mass=m)
    assert omega == pytest.approx(n * g * 2 * sigma * mean_u, rel=1e-10)
    assert theory.number_density(0.5, diameter=2.0) == pytest.approx(0.5 / math.pi)
    with pytest.raises(ValueError, match="diameter"):
        theory.enskog_collision_rate(n, 0.0, g)


def test_docstring_examples():
    result = doctest.testmod(theory)
    assert result.attempted > 0 and result.failed == 0


def test_haffs_law_is_the_exponential_law_at_the_collision_count_it_implies():
    # With omega = omega0 sqrt(T / T0), Haff's T(t) accumulates C(t) = omega0 t_H
    # ln(1 + t / t_H) collisions per disk, and exp(-(1 - e^2) C / 2) at that C is
    # Haff's T again: the two laws are one, integrated against time or collisions.
    e, omega0 = 0.8, 0.3
    t_h = 4.0 / ((1 - e * e) * omega0)
    t = np.linspace(0.0, 5.0 * t_h, 11)
    c = omega0 * t_h * np.log1p(t / t_h)
    np.testing.assert_allclose(theory.haff_temperature(e, t, omega0),
                               theory.homogeneous_cooling(e, c), rtol=1e-12)
    assert theory.homogeneous_cooling(1.0, 50.0) == 1.0
    with pytest.raises(ValueError, match="restitution must lie in"):
        theory.haff_temperature(0.0, 1.0, 1.0)


# Kolafa and Rottner (2006), Table 1: reduced density rho sigma^2, Z and its standard
# error, from molecular dynamics extrapolated to infinite size (the data their
# equation of state was fitted to).
KOLAFA_ROTTNER_TABLE = [
    (0.40, 2.1514393, 52e-7), (0.45, 2.4276680, 65e-7), (0.50, 2.7601235, 79e-7),
    (0.55, 3.1647878, 98e-7), (0.60, 3.663691, 12e-6), (0.65, 4.287926, 15e-6),
    (0.70, 5.082362, 19e-6), (0.75, 6.113391, 26e-6), (0.80, 7.476491, 36e-6),
    (0.83, 8.494891, 50e-6), (0.84, 8.866011, 59e-6), (0.85, 9.245785, 72e-6),
    (0.86, 9.621609, 82e-6), (0.87, 9.96782, 13e-5), (0.88, 10.2309, 3e-4),
    (0.89, 10.3176, 11e-4), (0.90, 10.2059, 11e-4),
]


def test_kolafa_rottner_follows_its_data_within_their_errors():
    """The fit against the simulation data printed beside it: within 2.5 standard
    errors at every density (the fit's normalised deviation is s = 0.927, so each
    point is about one error away), that is to 1e-5 relative up to eta = 0.69."""
    for rho, z, error in KOLAFA_ROTTNER_TABLE:
        eta = math.pi * rho / 4.0
        assert abs(theory.kolafa_rottner_z(eta) - z) < 2.5 * error, rho


def test_kolafa_rottner_has_the_exact_virial_coefficients():
    """Expanded in eta (the coefficient of eta^k in x^i, x = eta / (1 - eta), is
    C(k - 1, i - 1)), the first four terms are B_2 ... B_5 of the virial series: exact
    for B_2 ... B_4, Clisby and McCoy's for B_5, to the printed digits."""
    coefficients = theory._KOLAFA_ROTTNER
    virial = [2.0] + [2.0 ** (k - 1) * r for k, r in enumerate(theory._B_RATIOS, start=3)]
    for k in range(1, 5):
        b_k = sum(a * math.comb(k - 1, i - 1) for i, a in coefficients.items()
                  if 1 <= i <= k)
        assert b_k == pytest.approx(virial[k - 1], rel=2e-9), k


def test_kolafa_rottner_range_and_the_other_equations_of_state():
    """Refused beyond its fit; where Henderson's and Santos et al.'s equations of state
    stand against it in the dense fluid (+1.2 % and -0.8 % at eta = 0.6); the virial
    series to B_10 agrees at low density."""
    with pytest.raises(ValueError, match="packing fraction must be in"):
        theory.kolafa_rottner_z(0.71)
    assert theory.kolafa_rottner_z(theory.ETA_KOLAFA_ROTTNER_MAX) > 10.0
    z = theory.kolafa_rottner_z(0.6)
    assert theory.henderson_z(0.6) / z - 1 == pytest.approx(0.0118, abs=5e-4)
    assert theory.santos_z(0.6) / z - 1 == pytest.approx(-0.0083, abs=5e-4)
    assert theory.kolafa_rottner_z(0.2) == pytest.approx(theory.virial_z(0.2), rel=1e-6)
    np.testing.assert_array_equal(theory.kolafa_rottner_z(np.array([0.1, 0.3])),
                                  [theory.kolafa_rottner_z(0.1), theory.kolafa_rottner_z(0.3)])


def _brackets(order, nodes, family="viscosity"):
    """The collision brackets ``[psi_p, psi_q]`` of elastic hard disks (``c`` in units
    of ``sqrt(2 kT / m)``) for the trial functions of a transport coefficient, by
    Gauss rules over the centre-of-mass velocity (Hermite), the relative speed
    (Laguerre), its direction (uniform) and the impact parameter (Legendre):
    ``(1 / 4 pi^2) int dc dc1 exp(-c^2 - c1^2) int_{-1}^{1} db |g| D psi_p D psi_q``.

    ``family``: ``"viscosity"``, ``psi_p = L_p^(2)(c^2) c_x c_y`` (``p < order``),
    ``D psi`` the change of ``psi(c) + psi(c1)`` in the collision (``g' = g - 2 (g.k)
    k``, ``k`` at ``arcsin b`` from ``g``); ``"heat"``, ``psi_p = L_p^(1)(c^2) c_x``
    (``1 <= p <= order``: ``p = 0`` is momentum, conserved); ``"diffusion"``, the same
    functions from ``p = 0``, of a tagged disk among identical ones, ``D psi`` the
    change of ``psi(c)`` alone (the bracket of a tracer, up to a factor that ratios
    do not see).  Every integrand is a polynomial (odd powers of ``sqrt(1 - b^2)``
    come with odd powers of ``b`` and cancel between ``b`` and ``-b``), so the rules
    are exact once they have enough nodes."""
    from numpy.polynomial.hermite import hermgauss
    from numpy.polynomial.legendre import leggauss
    from scipy.special import eval_genlaguerre, roots_genlaguerre

    t, w = hermgauss(nodes)
    gx, gy = np.meshgrid(t / math.sqrt(2.0), t / math.sqrt(2.0), indexing="ij")
    centre = np.stack([gx.ravel(), gy.ravel()], axis=-1)
    w_centre = np.outer(w, w).ravel() / 2.0
    u, w_u = roots_genlaguerre(nodes, 0.5)
    speed, w_speed = np.sqrt(2.0 * u), w_u * math.sqrt(2.0)
    n_dir = 4 * order + 8
    direction = 2.0 * math.pi * np.arange(n_dir) / n_dir
    b, w_b = leggauss(2 * nodes)
    ic, iv, idr, ib = (a.ravel() for a in np.meshgrid(
        np.arange(len(centre)), np.arange(nodes), np.arange(n_dir), np.arange(len(b)),
        indexing="ij"))
    weight = w_centre[ic] * w_speed[iv] * (2.0 * math.pi / n_dir) * w_b[ib]
    phi = direction[idr]
    g = speed[iv, None] * np.stack([np.cos(phi), np.sin(phi)], axis=-1)
    k = np.stack([np.cos(phi + np.arcsin(b[ib])), np.sin(phi + np.arcsin(b[ib]))], axis=-1)
    g_after = g - 2.0 * np.sum(g * k, axis=-1)[:, None] * k
    c0 = centre[ic]
    alpha, first, shape = {"viscosity": (2.0, 0, lambda c: c[:, 0] * c[:, 1]),
                           "heat": (1.0, 1, lambda c: c[:, 0]),
                           "diffusion": (1.0, 0, lambda c: c[:, 0])}[family]

    def psi(c):
        x = np.sum(c * c, axis=-1)
        return np.stack([eval_genlaguerre(p, alpha, x) * shape(c)
                         for p in range(first, first + order)])

    change = psi(c0 + g / 2) - psi(c0 + g_after / 2)
    if family != "diffusion":
        change += psi(c0 - g / 2) - psi(c0 - g_after / 2)
    return (change * weight) @ change.T / (4.0 * math.pi**2)


def _sonine_ratios(brackets):
    """``c_N / c_1`` for ``N = 1 .. len(brackets)``: the coefficient from the first
    ``N`` trial functions (only the first has a source) over the first approximation."""
    return [brackets[0, 0] * np.linalg.inv(brackets[:n, :n])[0, 0]
            for n in range(1, len(brackets) + 1)]


def test_the_sonine_correction_of_the_dilute_viscosity_from_the_collision_brackets():
    """An independent computation of the Chapman-Enskog viscosity of hard disks: the
    first bracket is ``sqrt(pi / 8)``, which gives ``eta_1 = (1 / 2 sigma) sqrt(m kT /
    pi)`` (``eta_N = sqrt(m kT) / (2^(5/2) sigma) (M^-1)_00`` for the ``N x N``
    brackets ``M``); the second and third approximations are ``51/50`` and
    ``20605/20168`` times it, and the sixth lies within 6e-6 below the converged
    ``theory.SONINE_VISCOSITY`` (twenty terms), the sequence growing to it."""
    brackets = _brackets(6, 14)
    assert brackets[0, 0] == pytest.approx(math.sqrt(math.pi / 8), rel=1e-12)
    first = math.sqrt(1.0) / 2.0**2.5 / brackets[0, 0]
    assert first == pytest.approx(theory.dilute_viscosity(sonine=False), rel=1e-12)
    ratios = _sonine_ratios(brackets)
    assert ratios[1] == pytest.approx(51 / 50, rel=1e-12)
    assert ratios[2] == pytest.approx(20605 / 20168, rel=1e-12)
    assert all(b > a for a, b in zip(ratios, ratios[1:]))
    assert 0.0 < theory.SONINE_VISCOSITY - ratios[5] < 6e-6


@pytest.mark.parametrize("family, second, third, sixth_below, converged", [
    ("heat", 39 / 38, 6331 / 6152, 1.4e-5, theory.SONINE_CONDUCTIVITY),
    ("diffusion", 43 / 42, 104377 / 101688, 1.8e-5, theory.SONINE_DIFFUSION),
])
def test_the_sonine_corrections_of_heat_conduction_and_self_diffusion(
        family, second, third, sixth_below, converged):
    """The same computation for the thermal conductivity (heat-flux functions
    ``L_p^(1)(c^2) c_x``, ``p >= 1``) and for self-diffusion (the same functions from
    ``p = 0``, with the bracket of a tagged disk): the second and third approximations
    are the exact ratios, the sequence grows, and the sixth lies just below the
    converged ``theory`` constants (twenty terms, in exact arithmetic)."""
    ratios = _sonine_ratios(_brackets(6, 14, family))
    assert ratios[1] == pytest.approx(second, rel=1e-12)
    assert ratios[2] == pytest.approx(third, rel=1e-12)
    assert all(b > a for a, b in zip(ratios, ratios[1:]))
    assert 0.0 < converged - ratios[5] < sixth_below


def test_enskog_viscosity_limits_and_gass_formula():
    """Dilute, Enskog's viscosity tends to the dilute one; first-Sonine it is Gass's
    ``eta_1 [1/g + 2 eta + (1 + 8/pi) eta^2 g]``; the Sonine factor multiplies the
    kinetic part only; it scales as ``sqrt(m kT) / sigma``."""
    assert theory.enskog_viscosity(1e-12) == pytest.approx(theory.dilute_viscosity(), rel=1e-10)
    eta = np.array([0.1, 0.3, 0.5])
    g = theory.contact_value(theory.henderson_z(eta), eta)
    gass = 1.0 / g + 2.0 * eta + (1.0 + 8.0 / math.pi) * eta**2 * g
    first = theory.dilute_viscosity(sonine=False)
    np.testing.assert_allclose(theory.enskog_viscosity(eta, sonine=False), first * gass,
                               rtol=1e-14)
    kinetic = first * (1.0 + eta * g) ** 2 / g
    np.testing.assert_allclose(
        theory.enskog_viscosity(eta) - theory.enskog_viscosity(eta, sonine=False),
        (theory.SONINE_VISCOSITY - 1.0) * kinetic, rtol=1e-12)
    assert theory.enskog_viscosity(0.3, temperature=4.0, mass=2.0, diameter=0.5) == \
        pytest.approx(theory.enskog_viscosity(0.3) * math.sqrt(8.0) / 0.5, rel=1e-14)
    assert theory.enskog_viscosity(0.3, g_contact=2.0) != theory.enskog_viscosity(0.3)


def test_enskog_conduction_bulk_viscosity_and_diffusion():
    """Dilute, each tends to its Chapman-Enskog value (the bulk viscosity to 0);
    first-Sonine the conductivity is ``lambda_1 [1/g + 3 eta + (9/4 + 4/pi) eta^2 g]``
    (Gass); the Sonine factor multiplies the kinetic group only; the bulk viscosity
    is ``(16/pi) eta^2 g eta_1``, which is also the conductivity's collisional transfer
    of the local equilibrium (``k_B / m`` times it, in 2D); ``D_E = D_0 / g`` with
    ``D_0 = f sqrt(kT / (pi m)) / (2 n sigma)``; each scales with ``kT``, ``m`` and
    ``sigma`` as its units say."""
    eta = np.array([0.1, 0.3, 0.5])
    g = theory.contact_value(theory.henderson_z(eta), eta)
    lam1 = theory.dilute_thermal_conductivity(sonine=False)
    assert lam1 == pytest.approx(4.0 * theory.dilute_viscosity(sonine=False), rel=1e-14)
    assert theory.enskog_thermal_conductivity(1e-12) == pytest.approx(
        theory.dilute_thermal_conductivity(), rel=1e-10)
    np.testing.assert_allclose(
        theory.enskog_thermal_conductivity(eta, sonine=False),
        lam1 * (1.0 / g + 3.0 * eta + (9.0 / 4.0 + 4.0 / math.pi) * eta**2 * g), rtol=1e-14)
    np.testing.assert_allclose(
        theory.enskog_thermal_conductivity(eta)
        - theory.enskog_thermal_conductivity(eta, sonine=False),
        (theory.SONINE_CONDUCTIVITY - 1.0) * lam1 * (1.0 + 1.5 * eta * g) ** 2 / g,
        rtol=1e-12)
    zeta = theory.enskog_bulk_viscosity(eta)
    np.testing.assert_allclose(zeta, 16.0 / math.pi * eta**2 * g
                               * theory.dilute_viscosity(sonine=False), rtol=1e-14)
    np.testing.assert_allclose(zeta, 4.0 / math.pi * eta**2 * g * lam1, rtol=1e-14)
    n = theory.number_density(eta)
    np.testing.assert_allclose(
        theory.enskog_diffusion(eta),
        theory.SONINE_DIFFUSION / (2.0 * n * math.sqrt(math.pi)) / g, rtol=1e-14)
    assert theory.enskog_diffusion(0.3, g_contact=1.0, sonine=False) == pytest.approx(
        1.0 / (2.0 * theory.number_density(0.3) * math.sqrt(math.pi)), rel=1e-14)
    kt, m, d = 4.0, 2.0, 0.5
    assert theory.enskog_thermal_conductivity(0.3, temperature=kt, mass=m, diameter=d) == \
        pytest.approx(theory.enskog_thermal_conductivity(0.3) * math.sqrt(kt / m) / d,
                      rel=1e-14)
    assert theory.enskog_bulk_viscosity(0.3, temperature=kt, mass=m, diameter=d) == \
        pytest.approx(theory.enskog_bulk_viscosity(0.3) * math.sqrt(kt * m) / d, rel=1e-14)
    assert theory.enskog_diffusion(0.3, temperature=kt, mass=m, diameter=d) == \
        pytest.approx(theory.enskog_diffusion(0.3) * math.sqrt(kt / m) * d, rel=1e-14)
    with pytest.raises(ValueError, match="g_contact"):
        theory.enskog_diffusion(0.3, g_contact=-1.0)


def test_long_time_tail_amplitude():
    """``kT / (8 pi m n (D + nu))``: for the viscosity ``eta + m n D``."""
    a = theory.long_time_tail(0.5, 0.4, 0.3, temperature=2.0, mass=3.0)
    assert a == pytest.approx(2.0 / (8.0 * math.pi * (0.5 + 3.0 * 0.3 * 0.4)), rel=1e-15)
    with pytest.raises(ValueError, match="diffusion"):
        theory.long_time_tail(0.5, -0.4, 0.3)


@pytest.mark.parametrize("e, beta, q, t_rot", [(0.9, 0.0, 0.5, 0.3), (1.0, 0.6, 0.4, 1.7),
                                               (0.7, -0.5, 1.0, 1.0)])
def test_the_cooling_of_rough_disks_from_sampled_collisions(e, beta, q, t_rot):
    """The mean energy changes per collision that the cooling equations stand on, by
    sampling collisions of Maxwellian disks with Gaussian spins (weight ``|g_n|``
    on approaching pairs, the normal uniform), against ``omega``-free forms of
    :func:`theory.rough_cooling_rates`: per collision the two disks lose
    ``<dE_tr> = 2 dT_tr/dt / omega`` and gain ``<dE_rot> = dT_rot/dt / omega`` (two
    disks, and one rotational degree of freedom each).  2 x 10^6 samples: errors
    ~0.3 %; 2 % allowed."""
    rng = np.random.default_rng(5)
    n, m, r, t_tr = 2_000_000, 1.0, 0.5, 1.0
    inertia = q * m * r * r
    v1, v2 = rng.normal(0.0, math.sqrt(t_tr / m), (2, n, 2))
    w1, w2 = rng.normal(0.0, math.sqrt(t_rot / inertia), (2, n))
    angle = rng.uniform(0.0, 2.0 * math.pi, n)
    nx, ny = np.cos(angle), np.sin(angle)
    tx, ty = -ny, nx
    g_n = (v1[:, 0] - v2[:, 0]) * nx + (v1[:, 1] - v2[:, 1]) * ny
    weight = np.maximum(-g_n, 0.0)
    g_t = (v1[:, 0] - v2[:, 0]) * tx + (v1[:, 1] - v2[:, 1]) * ty - r * (w1 + w2)
    j_n = -(1.0 + e) * 0.5 * m * g_n
    j_t = -(1.0 + beta) * g_t / (2.0 / m + 2.0 * r * r / inertia)
    dv = np.stack([j_n * nx + j_t * tx, j_n * ny + j_t * ty], axis=1) / m
    u1, u2 = v1 + dv, v2 - dv
    x1, x2 = w1 - r * j_t / inertia, w2 - r * j_t / inertia
    de_tr = 0.5 * m * (np.sum(u1 ** 2 + u2 ** 2, axis=1) - np.sum(v1 ** 2 + v2 ** 2, axis=1))
    de_rot = 0.5 * inertia * (x1 ** 2 + x2 ** 2 - w1 ** 2 - w2 ** 2)
    sampled = (weight @ de_tr / weight.sum(), weight @ de_rot / weight.sum())
    rate_tr, rate_rot = theory.rough_cooling_rates(e, beta, q, t_tr, t_rot)
    scale = t_tr + t_rot
    assert sampled[0] == pytest.approx(2.0 * rate_tr, abs=0.02 * scale)
    assert sampled[1] == pytest.approx(rate_rot, abs=0.02 * scale)


def test_the_cooling_state_of_rough_disks():
    """``R = T_rot / T_tr`` makes both temperatures decay at one rate, is 1 without
    losses, and is what the cooling equations settle into from any start."""
    for e, beta, q in ((0.9, 0.0, 0.5), (0.5, 0.8, 0.4), (1.0, 0.3, 1.0), (0.95, 1.0, 0.5)):
        ratio = theory.rough_hcs_ratio(e, beta, q)
        a, b = theory.rough_cooling_rates(e, beta, q, 1.0, ratio)
        assert a / 1.0 == pytest.approx(b / ratio, rel=1e-12)
        assert theory.rough_hcs_cooling_rate(e, beta, q) == pytest.approx(-a, rel=1e-12)
        t_tr, t_rot = 1.0, 0.0  # (Euler steps of a hundredth of a collision per disk)
        for _ in range(10_000):
            da, db = theory.rough_cooling_rates(e, beta, q, t_tr, t_rot)
            t_tr, t_rot = t_tr + 1e-2 * da, t_rot + 1e-2 * db
        assert t_rot / t_tr == pytest.approx(ratio, rel=1e-3)
    assert theory.rough_hcs_ratio(1.0, 1.0) == pytest.approx(1.0, rel=1e-14)
    with pytest.raises(ValueError, match="smooth"):
        theory.rough_hcs_ratio(0.9, -1.0)
    with pytest.raises(ValueError, match="beta"):
        theory.rough_hcs_ratio(0.9, 1.5)


def test_the_vibrating_wall_power_is_the_flux_weighted_mean_gain():
    """Monte Carlo of the floor's power: disks of a Maxwellian gas (kT = m = n = 1)
    arrive with normal speed ``c`` at the rate ``n f(c) (c + U)``, the wall moving at
    ``U = V cos(phase)`` with the phase uniform, and gain ``2 m U (U + c)``.  With
    ``V = 0.1`` the leading order is 0.06 % from the exact phase average; 2e6 samples
    give 0.3 % errors; the bound is 4 of them.  (The sampling and the closed form
    make the same assumptions: this checks the averaging; the engine's shaken bed in
    tests/test_shaken_bed.py checks the physics.)"""
    rng = np.random.default_rng(seed_of(5))
    v = 0.1
    c = np.abs(rng.normal(size=2_000_000))  # normal speeds of those moving towards it
    u = v * np.cos(rng.uniform(0.0, 2.0 * np.pi, c.size))
    # the rate of arrivals with speed c (density n f(c) on c > 0, half of the gas's)
    # is weighted by (c + U); the mean over the half-Maxwellian of that times the gain
    gain = np.where(c + u > 0.0, 0.5 * (c + u) * 2.0 * u * (u + c), 0.0)
    found = float(gain.mean())
    error = float(gain.std() / np.sqrt(c.size))
    assert found == pytest.approx(theory.vibrating_wall_power(1.0, v, 1.0), abs=4 * error)


def test_the_vibrated_bed_temperature_balances_power_and_losses():
    """At the leading-order temperature the floor's power equals the collisions'
    losses integrated over the barometric profile ``n0 exp(-m g z / kT)`` (by
    quadrature), whatever the gravity; and it scales as ``(A omega)^2 / epsilon``."""
    for g in (0.5, 1.0, 3.0):
        kt = theory.vibrated_bed_temperature(0.5, 4.0, 0.98, 3.0, diameter=1.2, mass=2.0)
        n0 = 3.0 * 2.0 * g / kt  # N / L = n0 kT / (m g)
        power = theory.vibrating_wall_power(n0, 0.5, 4.0, kt, mass=2.0)
        loss, _ = integrate.quad(lambda z, n0=n0, kt=kt, g=g: theory.collisional_dissipation(
            n0 * math.exp(-2.0 * g * z / kt), 0.98, kt, 1.2, 2.0), 0.0, math.inf)
        assert power == pytest.approx(loss, rel=1e-9)
        # a floor of restitution 0.99: its net power balances the same losses
        kt = theory.vibrated_bed_temperature(0.5, 4.0, 0.98, 3.0, diameter=1.2, mass=2.0,
                                             wall_restitution=0.99)
        n0 = 3.0 * 2.0 * g / kt
        power = theory.vibrating_wall_power(n0, 0.5, 4.0, kt, mass=2.0,
                                            wall_restitution=0.99)
        loss, _ = integrate.quad(lambda z, n0=n0, kt=kt, g=g: theory.collisional_dissipation(
            n0 * math.exp(-2.0 * g * z / kt), 0.98, kt, 1.2, 2.0), 0.0, math.inf)
        assert power == pytest.approx(loss, rel=1e-9)
    # elastic disks on an inelastic floor: the floor's gains and losses balance alone
    kt = theory.vibrated_bed_temperature(0.5, 4.0, 1.0, 3.0, wall_restitution=0.9)
    assert theory.vibrating_wall_power(1.0, 0.5, 4.0, kt, wall_restitution=0.9) == (
        pytest.approx(0.0, abs=1e-12 * kt))
    base = theory.vibrated_bed_temperature(0.5, 4.0, 0.98, 3.0)
    assert theory.vibrated_bed_temperature(1.0, 4.0, 0.98, 3.0) == pytest.approx(4 * base)
    assert theory.vibrated_bed_temperature(0.5, 4.0, 0.98, 6.0) == pytest.approx(base / 2)
    with pytest.raises(ValueError, match="below 1"):
        theory.vibrated_bed_temperature(0.5, 4.0, 1.0, 3.0)
    with pytest.raises(ValueError, match="wall_restitution"):
        theory.vibrated_bed_temperature(0.5, 4.0, 0.9, 3.0, wall_restitution=1.5)
    with pytest.raises(ValueError, match="amplitude"):
        theory.vibrated_bed_temperature(0.0, 4.0, 0.9, 3.0)
    with pytest.raises(ValueError, match="disks_per_length"):
        theory.vibrated_bed_temperature(0.5, 4.0, 0.9, -1.0)
    with pytest.raises(ValueError, match="temperature"):
        theory.vibrating_wall_power(0.1, 0.5, 4.0, -1.0)
    with pytest.raises(ValueError, match="restitution"):
        theory.collisional_dissipation(0.1, 1.5)


def test_collisional_dissipation_is_the_rate_of_haffs_law():
    """Per disk, the loss ``D / n`` is ``(1 - e^2) kT omega / 2`` with Enskog's
    collision rate: the rate at which :func:`homogeneous_cooling` cools, per unit
    time."""
    n, kt, e, g = 0.05, 2.0, 0.9, 1.3
    omega = theory.enskog_collision_rate(n, 1.0, g, kt)
    assert theory.collisional_dissipation(n, e, kt, g_contact=g) / n == pytest.approx(
        (1 - e * e) * kt * omega / 2.0, rel=1e-14)


def test_the_piston_shock_of_an_ideal_gas_is_the_classic_one():
    """With ``Z = 1`` (``gamma = 2``): ``u / c_1 = (2 / 3)(M - 1 / M)``, density ratio
    ``3 M^2 / (M^2 + 2)`` and temperature ratio ``(4 M^2 - 1)(M^2 + 2) / (9 M^2)``
    (the textbook forms for ``gamma = 2``); the hard-disk fluid's shock is faster and
    compresses less; and a piston so fast that the fluid would pass the equation of
    state's range is refused."""
    for u in (0.3, 1.0, 5.0):
        d, eta2, t2 = theory.piston_shock(u, 0.02, temperature=1.5, mass=2.0,
                                          z=lambda eta: 1.0)
        c1 = math.sqrt(2.0 * 1.5 / 2.0)
        mach = d / c1
        assert u / c1 == pytest.approx(2.0 / 3.0 * (mach - 1.0 / mach), rel=1e-12)
        assert eta2 / 0.02 == pytest.approx(3 * mach**2 / (mach**2 + 2), rel=1e-12)
        assert t2 / 1.5 == pytest.approx((4 * mach**2 - 1) * (mach**2 + 2) / (9 * mach**2),
                                         rel=1e-12)
    ideal = theory.piston_shock(2.0, 0.2, z=lambda eta: 1.0)
    dense = theory.piston_shock(2.0, 0.2)
    assert dense[0] > ideal[0] and dense[1] < ideal[1]
    with pytest.raises(ValueError, match="beyond"):
        theory.piston_shock(50.0, 0.6)
    with pytest.raises(ValueError, match="speed"):
        theory.piston_shock(-1.0, 0.2)
