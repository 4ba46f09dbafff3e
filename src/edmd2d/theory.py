"""Reference values for hard disks: equations of state and 2D kinetic theory.

Notation: ``eta`` is the packing (area) fraction ``n pi sigma^2 / 4`` of disks of
diameter ``sigma`` at number density ``n``; ``Z = P A / (N kT)`` is the compressibility
factor; ``k_B = 1``.  Everything is two-dimensional.

The formulas and where they come from:

- Henderson's equation of state, D. Henderson, Mol. Phys. 30, 971 (1975):
  ``Z = (1 + eta^2 / 8) / (1 - eta)^2``; expanded, ``1 + 2 eta + 3.125 eta^2 + ...``
  (exact ``B_2``, ``B_3`` within 0.1%).
- Santos, Lopez de Haro and Bravo Yuste, J. Chem. Phys. 103, 4622 (1995), Eq. (2):
  ``Z = 1 / (1 - 2 eta + (2 eta_max - 1) eta^2 / eta_max^2)`` with the close-packing
  fraction ``eta_max = pi sqrt(3) / 6`` (exact second virial coefficient, pole at close
  packing).
- The virial series ``Z = 1 + sum_k (B_k / a^(k-1)) eta^(k-1)`` (``a`` the disk area):
  ``B_2 / a = 2``, ``B_3 / a^2 = 16/3 - 4 sqrt(3)/pi``,
  ``B_4 / a^3 = 16 - 36 sqrt(3)/pi + 80/pi^2`` exactly, and ``B_5 ... B_10`` from
  N. Clisby and B. M. McCoy, J. Stat. Phys. 122, 15 (2006) (as ``B_k / B_2^(k-1)``:
  0.33355604, 0.1988425, 0.1148728, 0.0649930, 0.0362193, 0.0199537).  Truncated
  after ``B_10`` it is accurate to about 1e-4 at ``eta = 0.3`` (the next terms are
  ``~ 11 eta^10``) but falls short by ~0.02 at ``eta = 0.5``.
- Kolafa and Rottner's simulation-based equation of state of the hard-disk fluid,
  J. Kolafa and M. Rottner, Mol. Phys. 104, 3435 (2006), Eq. (7) with the
  coefficients of their fit up to the reduced density ``rho sigma^2 = 0.90``
  (``eta = 0.7069``): a polynomial in ``x = eta / (1 - eta)`` whose first terms give
  the exact ``B_2 ... B_4`` and Clisby and McCoy's ``B_5``, fitted to molecular
  dynamics extrapolated to infinite size.  It is the reference for the dense fluid:
  their data at ``rho sigma^2 <= 0.88`` (``eta <= 0.691``) have relative errors of
  1e-6 to 3e-5, and the fit follows them within their errors.
- The contact value of the pair distribution from the (2D) virial theorem for hard
  disks, ``Z = 1 + 2 eta g(sigma)``.
- The collision rate per disk in equilibrium, ``omega = 2 n sigma g(sigma)
  sqrt(pi kT / m)``: the flux of partners through the contact circle, ``n g(sigma)``
  times the 2D cross-section ``2 sigma`` times the mean relative speed
  ``sqrt(pi kT / (2 mu)) = sqrt(pi kT / m)`` (reduced mass ``mu = m / 2``).  This is
  Enskog's collision frequency; in equilibrium it is exact once ``g(sigma)`` is.
- The shear viscosity of the dilute gas (Chapman-Enskog for hard disks): in the
  first Sonine approximation ``eta_1 = (1 / (2 sigma)) sqrt(m kT / pi)``; the higher
  approximations, from the exact collision brackets of the tensor Sonine polynomials
  ``L_p^(2)(c^2)`` for hard disks, multiply it by ``51/50`` (second), ``20605/20168``
  (third, 1.021668), ... converging to ``1.0219707`` (twenty terms; a Monte Carlo
  estimate of the same brackets agrees to 1e-4).  This 2.2 % is the 2D counterpart
  of the 1.6 % of hard spheres.
- Enskog's theory of the dense gas (D. M. Gass, J. Chem. Phys. 54, 1898 (1971); the
  ``d``-dimensional form of V. Garzo and J. W. Dufty, Phys. Rev. E 59, 5895 (1999)
  with ``d = 2`` and elastic collisions): ``eta_E = eta_0 (1 + eta g)^2 / g +
  (8 / pi) eta^2 g eta_1``, with ``g = g(sigma)`` the pair distribution at contact.
  The first term (kinetic transport and its collisional transfer) is proportional
  to the dilute solution of the Boltzmann equation and takes its Sonine correction
  (``eta_0``); the second, the collisional transfer of the local equilibrium, is the
  absolute number ``(4 / pi^(3/2)) eta^2 g sqrt(m kT) / sigma`` and takes none.
  First-Sonine, ``eta_E / eta_1 = 1 / g + 2 eta + (1 + 8 / pi) eta^2 g``, Gass's
  formula.
- The thermal conductivity and self-diffusion of the dilute gas, by the same method:
  first Sonine ``lambda_1 = (2 / sigma) sqrt(kT / (pi m))`` (``4 eta_1 / m``) and
  ``D_1 = (1 / (2 n sigma)) sqrt(kT / (pi m))``; the vector functions ``L_p^(1)(c^2)
  c_x`` (from ``p = 1`` for heat, ``p = 0`` momentum being conserved; from ``p = 0``
  for a tagged disk among identical ones) give ``39/38``, ``6331/6152``, ...
  converging to ``1.0297240418`` for ``lambda`` and ``43/42``, ``104377/101688``, ...
  converging to ``1.0270940111`` for ``D`` (exact rational brackets to 26 terms; the
  same computation in 3D gives the classic ``1 + 1/44`` and ``1 + 1/58``).  In
  Enskog's theory ``lambda_E = lambda_0 (1 + 3 eta g / 2)^2 / g + (4 / pi) eta^2 g
  lambda_1`` (the Sonine factor again on the kinetic group only), the bulk viscosity
  ``zeta_E = (16 / pi) eta^2 g eta_1`` (collisional transfer of the local equilibrium
  alone) and ``D_E = D_0 / g``.
- The long-time tail (M. H. Ernst, E. H. Hauge and J. M. J. van Leeuwen, Phys. Rev.
  A 4, 2055 (1971)): in ``d`` dimensions ``<v_x(0) v_x(t)> ~ ((d - 1) / d) (kT / m)
  / n [4 pi (D + nu) t]^(-d/2)``, in 2D ``kT / (8 pi m n (D + nu) t)``; in a periodic
  box the sum over its wave vectors cuts it off at ``t ~ L^2 / (4 pi^2 (D + nu))``,
  so that ``D`` grows as ``kT / (8 pi (eta + m n D)) ln N`` at fixed density.
- A dilute bed of nearly elastic disks on a floor vibrating as ``A sin(omega t)`` (the
  regime of V. Kumaran, J. Fluid Mech. 364, 163 (1998): dissipation small, many
  collisions per flight, ``A`` small against the bed's height ``kT / (m g)``): to
  leading order the velocities are Maxwellian at one temperature and the density is
  barometric.  A disk arriving at the floor with normal speed ``c`` meets it, at a
  rate proportional to ``c + U``, moving at ``U = A omega cos(phase)``, and leaves
  with ``c + 2 U``; averaged over the phase, ``(c + U) 2 m (c U + U^2)`` is ``4 m c
  <U^2>``, and over the flux of a Maxwellian the floor delivers ``S = 4 n_0 m <U^2>
  sqrt(kT / (2 pi m))`` per unit length (``n_0`` the density at the floor, ``<U^2> =
  (A omega)^2 / 2``).  Collisions with normal relative speed ``g_n`` lose ``(1 -
  e^2) m g_n^2 / 4``; at the rate ``n^2 sigma sqrt(pi kT / m)`` per unit area (half
  the collision rate above times ``n``, for ``g(sigma) = 1``) with ``<g_n^2> = 4 kT /
  m`` per collision, a unit area loses ``(1 - e^2) n^2 sigma kT sqrt(pi kT / m)``
  (the rate of Haff's law); integrated over the barometric profile, a unit length of
  floor loses ``(1 - e^2) (N / L) sigma n_0 sqrt(pi / m) kT^(3/2) / 2``.  The two
  balance at ``kT = (2 sqrt(2) / pi) m (A omega)^2 / epsilon`` with ``epsilon = (1 -
  e^2) N sigma / L``: the temperature grows as the square of the floor's velocity
  amplitude, does not depend on gravity, and its corrections are of relative order
  ``A omega / sqrt(kT / m) ~ epsilon^(1/2)`` (docs/moving-walls.md measures them).  A
  floor of restitution ``e_w`` gives ``(1 + e_w) / 2`` of that power and takes what a
  floor at rest takes, ``(1 - e_w^2) n_0 kT^(3/2) / sqrt(2 pi m)``: then ``kT = (1 +
  e_w) m (A omega)^2 / (pi epsilon / sqrt(2) + 1 - e_w^2)``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ._validate import as_positive_float

__all__ = [
    "ETA_CLOSE_PACKED",
    "ETA_KOLAFA_ROTTNER_MAX",
    "henderson_z",
    "santos_z",
    "virial_z",
    "kolafa_rottner_z",
    "adiabatic_temperature",
    "piston_shock",
    "contact_value",
    "enskog_collision_rate",
    "homogeneous_cooling",
    "haff_temperature",
    "collisional_dissipation",
    "vibrating_wall_power",
    "vibrated_bed_temperature",
    "number_density",
    "mean_speed",
    "SONINE_VISCOSITY",
    "dilute_viscosity",
    "enskog_viscosity",
    "SONINE_CONDUCTIVITY",
    "SONINE_DIFFUSION",
    "dilute_thermal_conductivity",
    "enskog_thermal_conductivity",
    "enskog_bulk_viscosity",
    "enskog_diffusion",
    "long_time_tail",
    "rough_cooling_rates",
    "rough_hcs_ratio",
    "rough_hcs_cooling_rate",
    "maxwell_boltzmann_speed_pdf",
]

#: Close-packing fraction of equal disks (triangular lattice), ``pi sqrt(3) / 6``.
ETA_CLOSE_PACKED = math.pi * math.sqrt(3.0) / 6.0

# Reduced virial coefficients B_k / B_2^(k-1), k = 3..10: B_3, B_4 exact, B_5..B_10
# from Clisby and McCoy (2006).
_B_RATIOS = (
    4.0 / 3.0 - math.sqrt(3.0) / math.pi,
    2.0 - 9.0 * math.sqrt(3.0) / (2.0 * math.pi) + 10.0 / math.pi**2,
    0.33355604,
    0.1988425,
    0.1148728,
    0.0649930,
    0.0362193,
    0.0199537,
)


# Kolafa and Rottner (2006), Eq. (7), the fit with rho_max = 0.90 (s = 0.927): the
# coefficients A_i of Z = sum_i A_i x^i, x = eta / (1 - eta), as printed in Sec. 3.2.
_KOLAFA_ROTTNER = {
    0: 1.0, 1: 2.0, 2: 1.12801775, 3: 0.00181895291, 4: -0.0526134737,
    5: 0.0504960168, 6: -0.0325537792, 7: 0.0134578632, 8: 0.00140888182,
    9: -0.00834273601, 10: 0.00694127367, 11: -0.00262254723, 12: 0.000355746352,
    22: -5.24672938e-9, 57: 5.88054639e-23,
}
#: The largest packing fraction of Kolafa and Rottner's fit, ``pi 0.90 / 4``.
ETA_KOLAFA_ROTTNER_MAX = math.pi * 0.90 / 4.0


def _eta(eta, upper=1.0):
    arr = np.asarray(eta, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr < 0) or np.any(arr >= upper):
        raise ValueError(f"packing fraction must be in [0, {upper:.6g}), got {eta!r}")
    return arr


def _out(arr):
    return float(arr) if np.ndim(arr) == 0 else arr


def henderson_z(eta: ArrayLike) -> float | np.ndarray:
    """Henderson's hard-disk equation of state, ``Z = (1 + eta^2/8) / (1 - eta)^2``.

    D. Henderson, Mol. Phys. 30, 971 (1975).  Expanded, ``1 + 2 eta + 3.125 eta^2 +
    4.25 eta^3 + ...``: the exact second virial coefficient and the third within 0.1%
    (compare :func:`virial_z`).

    Parameters
    ----------
    eta : float or array_like
        Packing fraction in [0, 1).

    Returns
    -------
    float or ndarray

    Examples
    --------
    >>> henderson_z(0.5)
    4.125
    """
    e = _eta(eta)
    return _out((1.0 + e**2 / 8.0) / (1.0 - e) ** 2)


def santos_z(eta: ArrayLike) -> float | np.ndarray:
    """The Santos-Lopez de Haro-Yuste equation of state for hard disks.

    ``Z = 1 / (1 - 2 eta + (2 eta_max - 1) eta^2 / eta_max^2)``, ``eta_max = pi sqrt(3)/6``:
    A. Santos, M. Lopez de Haro and S. Bravo Yuste, J. Chem. Phys. 103, 4622 (1995).
    It has the exact second virial coefficient and diverges at close packing; in the
    dense fluid it lies below Henderson's formula (4.043 against 4.125 at ``eta = 0.5``).

    Parameters
    ----------
    eta : float or array_like
        Packing fraction in [0, pi sqrt(3) / 6).

    Returns
    -------
    float or ndarray
        ``Z = P A / (N kT)``.

    Examples
    --------
    >>> round(santos_z(0.5), 4)
    4.0426
    """
    e = _eta(eta, ETA_CLOSE_PACKED)
    em = ETA_CLOSE_PACKED
    return _out(1.0 / (1.0 - 2.0 * e + (2.0 * em - 1.0) * e**2 / em**2))


def virial_z(eta: ArrayLike, order: int = 10) -> float | np.ndarray:
    """The virial series of hard disks up to ``B_order`` (2 <= order <= 10).

    ``Z = 1 + sum_{k=2}^{order} 2^(k-1) (B_k / B_2^(k-1)) eta^(k-1)`` with ``B_2 / a = 2``
    (``a`` the disk area), ``B_3``, ``B_4`` exact and ``B_5 .. B_10`` of Clisby and McCoy,
    J. Stat. Phys. 122, 15 (2006).  A truncated series: excellent in the dilute fluid,
    too low by ~0.02 at ``eta = 0.5`` with ``order=10``.

    Parameters
    ----------
    eta : float or array_like
        Packing fraction in [0, 1).
    order : int, default 10
        The last virial coefficient included, 2 to 10.

    Returns
    -------
    float or ndarray
        ``Z`` of the truncated series.

    Raises
    ------
    ValueError
        For an ``order`` outside 2..10 or a packing fraction outside [0, 1).

    Examples
    --------
    The exact third virial coefficient, ``Z = 1 + 2 eta + 3.128 eta^2 + ...``:

    >>> round((virial_z(1e-3, order=3) - 1 - 2e-3) / 1e-6, 4)
    3.128
    """
    e = _eta(eta)
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or not (
        2 <= order <= 10
    ):
        raise ValueError(f"order must be an integer in 2..10, got {order!r}")
    z = 1.0 + 2.0 * e
    for k, ratio in enumerate(_B_RATIOS[: order - 2], start=3):
        z = z + 2.0 ** (k - 1) * ratio * e ** (k - 1)
    return _out(z)


def kolafa_rottner_z(eta: ArrayLike) -> float | np.ndarray:
    """Kolafa and Rottner's equation of state of the hard-disk fluid: the reference
    for the dense fluid.

    ``Z = sum_i A_i x^i`` with ``x = eta / (1 - eta)``: J. Kolafa and M. Rottner, Mol.
    Phys. 104, 3435 (2006), Eq. (7), the fit to their molecular dynamics (extrapolated
    to infinite size) up to the reduced density ``rho sigma^2 = 0.90``, that is
    ``eta <= 0.7069`` (:data:`ETA_KOLAFA_ROTTNER_MAX`).  Its first coefficients give
    the exact virial coefficients ``B_2 ... B_4`` and ``B_5`` (``A_2 = 16/3 - 4 sqrt(3)
    / pi - 2``).  Accuracy: the data it was fitted to have relative errors of 2e-6 at
    ``eta = 0.31`` to 3e-5 at ``eta = 0.69``, and it follows them within their errors
    (``s = 0.927``); above ``rho sigma^2 = 0.89`` (``eta = 0.699``), near the
    liquid-hexatic transition, the authors warn that finite-size effects may affect
    it, and it is not an equation of state of the hexatic or solid phases.  Against it,
    Henderson's formula is 1.2 % high at ``eta = 0.6`` and Santos et al.'s 0.8 % low.

    Parameters
    ----------
    eta : float or array_like
        Packing fraction in [0, 0.7069].

    Returns
    -------
    float or ndarray

    Raises
    ------
    ValueError
        For a packing fraction outside the fit's range.

    Examples
    --------
    >>> round(kolafa_rottner_z(0.5), 6)
    4.106364
    """
    e = _eta(eta, upper=math.nextafter(ETA_KOLAFA_ROTTNER_MAX, 1.0))
    x = e / (1.0 - e)
    return _out(sum(a * x**i for i, a in _KOLAFA_ROTTNER.items()))


def adiabatic_temperature(eta_start: float, eta_end: float, temperature: float = 1.0,
                          z=None) -> float:
    """The temperature of a hard-disk fluid compressed (or expanded) slowly, with no
    heat exchanged, from the packing fraction ``eta_start`` at ``temperature`` to
    ``eta_end``: its adiabat.

    The energy of hard disks is all kinetic, ``U = N kT`` in 2D, and the work of a slow
    piston is ``-P dA``: ``N k dT = -N kT Z dA / A``, so ``d ln T / d ln eta = Z(eta)``
    and ``T_end = T exp(integral of Z(eta) / eta from eta_start to eta_end)``.  For an
    ideal gas (``Z = 1``) that is ``T A = const``.

    Parameters
    ----------
    eta_start, eta_end : float
        Packing fractions in the fluid, in ``(0, 0.7069]`` for the default ``z``.
    temperature : float, default 1
        The temperature at ``eta_start``.
    z : callable, optional
        The equation of state ``Z(eta)``; default :func:`kolafa_rottner_z`.

    Returns
    -------
    float

    Examples
    --------
    >>> round(adiabatic_temperature(0.01, 0.02, z=lambda eta: 1.0), 12)  # T A = const
    2.0
    >>> round(adiabatic_temperature(0.1, 0.3), 4)
    5.3423
    """
    # (scipy.integrate only here: importing it with the package costs 0.25 s.)
    from scipy.integrate import quad

    if z is None:
        z = kolafa_rottner_z
    for name, value in (("eta_start", eta_start), ("eta_end", eta_end)):
        if not 0.0 < float(value) < 1.0:
            raise ValueError(f"{name} must lie in (0, 1), got {value!r}")
    integral, _ = quad(lambda eta: float(z(eta)) / eta, float(eta_start), float(eta_end),
                        epsabs=0.0, epsrel=1e-12)
    return float(temperature) * math.exp(integral)


def piston_shock(speed: float, eta: float, temperature: float = 1.0, mass: float = 1.0,
                 diameter: float = 1.0, z=None) -> tuple[float, float, float]:
    """The shock wave that a piston driven at a constant ``speed`` into a hard-disk
    fluid at rest sends ahead of it (Rankine and Hugoniot's jump conditions with the
    fluid's equation of state): the shock's speed, and the packing fraction and
    temperature of the fluid between it and the piston.

    Behind the shock the fluid moves with the piston, ``u``; the shock runs at ``D``
    into the fluid at rest (density ``n_1``, pressure ``p_1``, temperature ``T_1``).
    Across it mass, momentum and energy are conserved: ``n_1 D = n_2 (D - u)``, ``p_2 -
    p_1 = m n_1 D u`` and ``n_1 D (e_2 - e_1 + m u^2 / 2) = p_2 u``, with ``e = kT`` per
    disk (the energy of hard disks is all kinetic) and ``p = n kT Z(eta)``.  For an
    ideal gas (``Z = 1``, ``gamma = 2`` in 2D) they give the classic ``u / c_1 = (2 /
    (gamma + 1)) (M - 1 / M)`` with ``M = D / c_1``, ``c_1 = sqrt(gamma kT_1 / m)``, and a
    density ratio of at most 3.  The piston's work beyond the adiabat
    (:func:`adiabatic_temperature`) is what the shock dissipates.

    Parameters
    ----------
    speed : float
        The piston's speed ``u`` (> 0) towards the fluid.
    eta : float
        The packing fraction ahead of the shock.
    temperature, mass, diameter : float, default 1.0
        ``kT_1``, ``m``, ``sigma``.
    z : callable, optional
        The equation of state ``Z(eta)``; default :func:`kolafa_rottner_z`, whose
        range (``eta <= 0.7069``) bounds the shock's strength.

    Returns
    -------
    (float, float, float)
        ``D``, ``eta_2`` and ``kT_2``.

    Examples
    --------
    >>> d, eta2, t2 = piston_shock(2.0, 0.01, z=lambda eta: 1.0)  # an ideal gas
    >>> m = d / 2.0 ** 0.5
    >>> round(2.0 / 3.0 * (m - 1.0 / m) * 2.0 ** 0.5, 12), round(eta2 / 0.01, 4)
    (2.0, 2.2808)
    """
    # (scipy.optimize only here: importing it with the package costs time.)
    from scipy.optimize import brentq

    u = as_positive_float("speed", speed)
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    sigma = as_positive_float("diameter", diameter)
    if not 0.0 < float(eta) < 1.0:
        raise ValueError(f"eta must lie in (0, 1), got {eta!r}")
    if z is None:
        z = kolafa_rottner_z
    top = 0.7 if z is kolafa_rottner_z else 0.9
    if float(eta) >= top:
        raise ValueError(f"eta must lie below {top}, got {eta!r}")
    area = math.pi * sigma * sigma / 4.0
    n1 = float(eta) / area
    p1 = n1 * kt * float(z(float(eta)))

    def behind(d):
        n2 = n1 * d / (d - u)
        p2 = p1 + m * n1 * d * u
        return n2, p2, kt - 0.5 * m * u * u + p2 * u / (n1 * d)

    def mismatch(d):
        n2, p2, t2 = behind(d)
        return n2 * t2 * float(z(n2 * area)) - p2

    # (from the densest state the equation of state allows to a shock far faster
    # than the piston and the sound, where the mismatch changes sign)
    low = u / (1.0 - float(eta) / top)
    high = 10.0 * (u + math.sqrt(kt / m)) / (1.0 - float(eta) / top)
    if mismatch(low) <= 0.0:
        raise ValueError(f"a piston at speed {u} compresses eta = {eta} beyond {top}, "
                         "where the equation of state ends")
    d = brentq(mismatch, low, high, xtol=1e-300, rtol=4 * np.finfo(float).eps)
    n2, _, t2 = behind(d)
    return float(d), float(n2 * area), float(t2)


def contact_value(z: ArrayLike, eta: ArrayLike) -> float | np.ndarray:
    """The pair distribution at contact from ``Z``: ``g(sigma) = (Z - 1) / (2 eta)``.

    This is the 2D virial theorem for hard disks, ``Z = 1 + (pi / 2) n sigma^2
    g(sigma) = 1 + 2 eta g(sigma)`` (in 3D it would be ``1 + 4 eta g(sigma)``).

    Parameters
    ----------
    z : float or array_like
        Compressibility factor ``P A / (N kT)``.
    eta : float or array_like
        Packing fraction, > 0.

    Returns
    -------
    float or ndarray
        ``g(sigma)``.

    Examples
    --------
    >>> contact_value(henderson_z(0.5), 0.5)
    3.125
    """
    e = np.asarray(eta, dtype=float)
    if np.any(e <= 0):
        raise ValueError(f"packing fraction must be > 0, got {eta!r}")
    return _out((np.asarray(z, dtype=float) - 1.0) / (2.0 * e))


def number_density(eta: ArrayLike, diameter: float = 1.0) -> float | np.ndarray:
    """Number density of equal disks, ``n = 4 eta / (pi sigma^2)``.

    Parameters
    ----------
    eta : float or array_like
        Packing fraction.
    diameter : float, default 1.0
        ``sigma``, > 0.

    Returns
    -------
    float or ndarray
        Disks per unit area.

    Examples
    --------
    >>> round(number_density(math.pi / 4), 12)
    1.0
    """
    d = as_positive_float("diameter", diameter)
    return _out(4.0 * np.asarray(eta, dtype=float) / (math.pi * d**2))


def enskog_collision_rate(n: ArrayLike, diameter: float, g_contact: ArrayLike,
                          temperature: float = 1.0, mass: float = 1.0) -> float | np.ndarray:
    """Collisions per disk per unit time, ``omega = 2 n sigma g(sigma) sqrt(pi kT / m)``.

    Derivation (2D, equal disks): a partner hits the contact circle of radius ``sigma``
    with relative velocity ``u`` at the rate ``n g(sigma) sigma integral (u . e)_+ d phi =
    2 sigma n g(sigma) |u|``; averaging ``|u|`` over the Maxwell-Boltzmann distribution
    of the relative velocity (reduced mass ``m / 2``) gives ``<|u|> = sqrt(pi kT / m)``.
    The 3D formula ``4 n sigma^2 g sqrt(pi kT / m)`` is a different one.

    Parameters
    ----------
    n : float
        Number density ``N / A``.
    diameter : float
        ``sigma``.
    g_contact : float
        Pair distribution at contact, e.g. ``contact_value(henderson_z(eta), eta)``.
    temperature, mass : float, default 1.0

    Returns
    -------
    float or ndarray
        ``omega``: each disk's collisions per unit time (a collision counts once for
        each of its two disks).

    Examples
    --------
    >>> eta = 0.3
    >>> g = contact_value(henderson_z(eta), eta)
    >>> round(enskog_collision_rate(number_density(eta), 1.0, g), 4)
    2.4007
    """
    sigma = as_positive_float("diameter", diameter)
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    return _out(2.0 * np.asarray(n, dtype=float) * sigma * np.asarray(g_contact, dtype=float)
                * math.sqrt(math.pi * kt / m))


def mean_speed(temperature: float = 1.0, mass: float = 1.0) -> float:
    """Mean speed in 2D Maxwell-Boltzmann equilibrium, ``<|v|> = sqrt(pi kT / (2 m))``.

    Parameters
    ----------
    temperature, mass : float, default 1.0
        ``kT`` and ``m``, > 0.

    Returns
    -------
    float

    Examples
    --------
    >>> round(mean_speed(), 6)
    1.253314
    """
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    return math.sqrt(math.pi * kt / (2.0 * m))


def maxwell_boltzmann_speed_pdf(v: ArrayLike, temperature: float = 1.0,
                                mass: float = 1.0) -> float | np.ndarray:
    """The 2D Maxwell-Boltzmann speed density ``f(v) = (m v / kT) exp(-m v^2 / (2 kT))``.

    (In 3D the density grows as ``v^2``; in 2D the shell is a circle, hence ``v``.)

    Parameters
    ----------
    v : float or array_like
        Speeds (the density is 0 below 0).
    temperature, mass : float, default 1.0
        ``kT`` and ``m``, > 0.

    Returns
    -------
    float or ndarray

    Examples
    --------
    >>> from scipy.integrate import quad
    >>> round(quad(maxwell_boltzmann_speed_pdf, 0, 50)[0], 12)
    1.0
    """
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    v = np.asarray(v, dtype=float)
    return _out(np.where(v >= 0, (m * v / kt) * np.exp(-m * v**2 / (2.0 * kt)), 0.0))


def homogeneous_cooling(restitution: float,
                        collisions_per_disk: ArrayLike) -> float | np.ndarray:
    """Granular temperature of a homogeneous cooling gas against collisions per disk,
    ``T / T0 = exp(-(1 - e^2) C / 2)`` (2D, smooth disks; derived in
    ``docs/restitution.md``).

    Parameters
    ----------
    restitution : float
        Coefficient of normal restitution ``e`` in (0, 1].
    collisions_per_disk : float or array_like
        ``C``, collisions per disk since ``T0`` (each collision counts for both disks).

    Returns
    -------
    float or ndarray
        ``T / T0``.

    Examples
    --------
    >>> round(homogeneous_cooling(0.9, 10.0), 4)
    0.3867
    """
    e = _restitution(restitution)
    return _out(np.exp(-(1.0 - e * e) * np.asarray(collisions_per_disk, dtype=float) / 2.0))


#: The dilute shear viscosity of hard disks over its first Sonine approximation:
#: the converged Chapman-Enskog value (see the module notes).
SONINE_VISCOSITY = 1.0219706808


def dilute_viscosity(temperature: float = 1.0, mass: float = 1.0, diameter: float = 1.0,
                     sonine: bool = True) -> float:
    """Shear viscosity of a dilute gas of hard disks (Chapman-Enskog, 2D):
    ``eta_0 = f (1 / (2 sigma)) sqrt(m kT / pi)`` with ``f = SONINE_VISCOSITY`` (the
    converged value), or ``f = 1`` (the first Sonine approximation).

    It does not depend on the density: fewer carriers of momentum, each carrying it
    further.  (In 2D the dilute limit is reached only in the sense of this
    expansion: the long-time tail adds a term that grows with the logarithm of the
    system's size; see :doc:`/shear`.)

    Parameters
    ----------
    temperature, mass, diameter : float, default 1.0
        ``kT``, ``m``, ``sigma``, each > 0.
    sonine : bool, default True
        The converged value (else the first Sonine approximation).

    Returns
    -------
    float

    Examples
    --------
    >>> round(dilute_viscosity(sonine=False), 6)   # 1 / (2 sqrt(pi))
    0.282095
    >>> round(dilute_viscosity(), 6)
    0.288293
    """
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    sigma = as_positive_float("diameter", diameter)
    first = math.sqrt(m * kt / math.pi) / (2.0 * sigma)
    return first * (SONINE_VISCOSITY if sonine else 1.0)


def enskog_viscosity(eta: ArrayLike, g_contact: ArrayLike | None = None,
                     temperature: float = 1.0, mass: float = 1.0, diameter: float = 1.0,
                     sonine: bool = True) -> float | np.ndarray:
    """Shear viscosity of hard disks in Enskog's theory (2D):
    ``eta_E = eta_0 (1 + eta g)^2 / g + (8 / pi) eta^2 g eta_1``.

    ``eta_0`` is :func:`dilute_viscosity` (converged, or the first Sonine
    approximation ``eta_1`` with ``sonine=False``, which gives Gass's formula
    ``eta_1 [1 / g + 2 eta + (1 + 8 / pi) eta^2 g]``); the last term, the collisional
    transfer of the local equilibrium, takes no Sonine correction (module notes).
    Enskog's theory takes collisions as uncorrelated; against simulations of hard
    disks it holds within a few per cent up to packing fractions of about 0.5 and
    falls short closer to freezing (:doc:`/shear`).

    Parameters
    ----------
    eta : float or array_like
        Packing fraction, in ``(0, 1)``.
    g_contact : float or array_like, optional
        The pair distribution at contact; default Henderson's,
        ``contact_value(henderson_z(eta), eta) = (1 - 7 eta / 16) / (1 - eta)^2``.
    temperature, mass, diameter : float, default 1.0
    sonine : bool, default True

    Returns
    -------
    float or ndarray

    Examples
    --------
    >>> round(enskog_viscosity(0.3), 4)
    0.4962
    >>> round(enskog_viscosity(0.3, sonine=False)
    ...       / dilute_viscosity(sonine=False), 4)   # Gass: 1/g + 2 eta + (1 + 8/pi) eta^2 g
    1.7299
    """
    e, g = _enskog_args(eta, g_contact)
    first = dilute_viscosity(temperature, mass, diameter, sonine=False)
    eta0 = first * (SONINE_VISCOSITY if sonine else 1.0)
    return _out(eta0 * (1.0 + e * g) ** 2 / g + (8.0 / math.pi) * e * e * g * first)


def _enskog_args(eta, g_contact):
    """The packing fraction and the contact value (default Henderson's) as arrays."""
    e = _eta(eta)
    # (Henderson's contact value in the form that stays exact as eta -> 0, where
    # (Z - 1) / (2 eta) would cancel.)
    g = ((1.0 - 7.0 * e / 16.0) / (1.0 - e) ** 2 if g_contact is None
         else np.asarray(g_contact, dtype=float))
    if not np.all(g > 0):
        raise ValueError(f"g_contact must be > 0, got {g_contact!r}")
    return e, g


#: The dilute thermal conductivity of hard disks over its first Sonine
#: approximation: the converged Chapman-Enskog value (see the module notes).
SONINE_CONDUCTIVITY = 1.0297240418
#: The dilute self-diffusion coefficient of hard disks over its first Sonine
#: approximation, converged.
SONINE_DIFFUSION = 1.0270940111


def dilute_thermal_conductivity(temperature: float = 1.0, mass: float = 1.0,
                                diameter: float = 1.0, sonine: bool = True) -> float:
    """Thermal conductivity of a dilute gas of hard disks (Chapman-Enskog, 2D, ``k_B =
    1``): ``lambda_0 = f (2 / sigma) sqrt(kT / (pi m))``, ``f = SONINE_CONDUCTIVITY``
    (converged) or 1 (the first Sonine approximation, ``4 eta_1 / m``: ``d (d + 2) /
    (2 (d - 1))`` times ``eta_1 / m`` in ``d`` dimensions).

    Parameters
    ----------
    temperature, mass, diameter : float, default 1.0
        ``kT``, ``m``, ``sigma``, each > 0.
    sonine : bool, default True

    Returns
    -------
    float

    Examples
    --------
    >>> round(dilute_thermal_conductivity(sonine=False), 6)   # 2 / sqrt(pi)
    1.128379
    >>> round(dilute_thermal_conductivity(), 6)
    1.161919
    """
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    sigma = as_positive_float("diameter", diameter)
    first = 2.0 * math.sqrt(kt / (math.pi * m)) / sigma
    return first * (SONINE_CONDUCTIVITY if sonine else 1.0)


def enskog_thermal_conductivity(eta: ArrayLike, g_contact: ArrayLike | None = None,
                                temperature: float = 1.0, mass: float = 1.0,
                                diameter: float = 1.0,
                                sonine: bool = True) -> float | np.ndarray:
    """Thermal conductivity of hard disks in Enskog's theory (2D, ``k_B = 1``):
    ``lambda_E = lambda_0 (1 + 3 eta g / 2)^2 / g + (4 / pi) eta^2 g lambda_1``.

    ``lambda_0`` is :func:`dilute_thermal_conductivity` (converged, or ``lambda_1``
    with ``sonine=False``, which gives ``lambda_1 [1 / g + 3 eta + (9 / 4 + 4 / pi)
    eta^2 g]``); the last term, the collisional transfer of the local equilibrium,
    takes no Sonine correction, as for :func:`enskog_viscosity`.

    Parameters
    ----------
    eta : float or array_like
        Packing fraction, in ``(0, 1)``.
    g_contact : float or array_like, optional
        The pair distribution at contact; default Henderson's.
    temperature, mass, diameter : float, default 1.0
    sonine : bool, default True

    Returns
    -------
    float or ndarray

    Examples
    --------
    >>> round(enskog_thermal_conductivity(0.3, sonine=False)
    ...       / dilute_thermal_conductivity(sonine=False), 4)
    2.0262
    """
    e, g = _enskog_args(eta, g_contact)
    first = dilute_thermal_conductivity(temperature, mass, diameter, sonine=False)
    lam0 = first * (SONINE_CONDUCTIVITY if sonine else 1.0)
    return _out(lam0 * (1.0 + 1.5 * e * g) ** 2 / g + (4.0 / math.pi) * e * e * g * first)


def enskog_bulk_viscosity(eta: ArrayLike, g_contact: ArrayLike | None = None,
                          temperature: float = 1.0, mass: float = 1.0,
                          diameter: float = 1.0) -> float | np.ndarray:
    """Bulk viscosity of hard disks in Enskog's theory (2D):
    ``zeta_E = (16 / pi) eta^2 g eta_1``, ``eta_1`` the first Sonine approximation of
    :func:`dilute_viscosity`.  It is collisional transfer of the local equilibrium
    alone (a dilute gas of hard disks has none), so no Sonine correction enters.

    Parameters
    ----------
    eta : float or array_like
        Packing fraction, in ``(0, 1)``.
    g_contact : float or array_like, optional
        The pair distribution at contact; default Henderson's.
    temperature, mass, diameter : float, default 1.0

    Returns
    -------
    float or ndarray

    Examples
    --------
    >>> round(enskog_bulk_viscosity(0.3), 4)
    0.2292
    """
    e, g = _enskog_args(eta, g_contact)
    first = dilute_viscosity(temperature, mass, diameter, sonine=False)
    return _out((16.0 / math.pi) * e * e * g * first)


def enskog_diffusion(eta: ArrayLike, g_contact: ArrayLike | None = None,
                     temperature: float = 1.0, mass: float = 1.0, diameter: float = 1.0,
                     sonine: bool = True) -> float | np.ndarray:
    """Self-diffusion coefficient of hard disks in Enskog's theory (2D):
    ``D_E = D_0 / g`` with the dilute ``D_0 = f (1 / (2 n sigma)) sqrt(kT / (pi m))``
    at the number density ``n = 4 eta / (pi sigma^2)``, ``f = SONINE_DIFFUSION``
    (converged) or 1 (first Sonine approximation).

    ``kT / (m D_E)`` with ``f = 1`` is the exact initial decay rate of the velocity
    autocorrelation (:mod:`edmd2d.transport`).  In 2D the measured ``D`` exceeds
    ``D_E`` by a term that grows with the logarithm of the time window and of the
    box (the long-time tail, :doc:`/transport`).

    Parameters
    ----------
    eta : float or array_like
        Packing fraction, in ``(0, 1)``.
    g_contact : float or array_like, optional
        The pair distribution at contact; default Henderson's.
    temperature, mass, diameter : float, default 1.0
    sonine : bool, default True

    Returns
    -------
    float or ndarray

    Examples
    --------
    >>> round(enskog_diffusion(0.05), 4)
    4.1993
    """
    e, g = _enskog_args(eta, g_contact)
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    sigma = as_positive_float("diameter", diameter)
    n = 4.0 * e / (math.pi * sigma * sigma)
    first = math.sqrt(kt / (math.pi * m)) / (2.0 * n * sigma)
    return _out(first * (SONINE_DIFFUSION if sonine else 1.0) / g)


def long_time_tail(viscosity: float, diffusion: float, density: float,
                   temperature: float = 1.0, mass: float = 1.0) -> float:
    """The amplitude ``A = kT / (8 pi m n (D + nu))``, ``nu = eta / (m n)``, of the
    long-time tail of hard disks (mode coupling: Ernst, Hauge and van Leeuwen): the
    velocity autocorrelation per axis decays as ``<v_x(0) v_x(t)> ~ A / t``, so the
    self-diffusion coefficient grows as ``A ln t`` with the time window and, in a
    periodic box whose longest waves cut the tail off, as ``A ln N`` with the number
    of disks at a fixed density (:doc:`/transport`).  The viscosity that enters is
    ``eta + m n D``, not ``eta`` alone.

    Parameters
    ----------
    viscosity : float
        The shear viscosity ``eta``, > 0.
    diffusion : float
        The self-diffusion coefficient ``D``, > 0.
    density : float
        The number density ``n``, > 0.
    temperature, mass : float, default 1.0

    Returns
    -------
    float

    Examples
    --------
    >>> round(long_time_tail(0.4962, 0.5525, number_density(0.3)), 4)
    0.0563
    """
    eta = as_positive_float("viscosity", viscosity)
    d = as_positive_float("diffusion", diffusion)
    n = as_positive_float("density", density)
    kt = as_positive_float("temperature", temperature)
    m = as_positive_float("mass", mass)
    return kt / (8.0 * math.pi * (eta + m * n * d))


def _rough_coefficients(e: float, beta: float, q: float) -> tuple[float, float, float]:
    """``(A, B, C)`` of the cooling equations of rough disks (see
    :func:`rough_hcs_ratio`), checked."""
    e = _restitution(e)
    if not -1.0 <= beta <= 1.0:
        raise ValueError(f"beta must lie in [-1, 1], got {beta!r}")
    if not 0.0 < q <= 1.0:
        raise ValueError(f"q must lie in (0, 1], got {q!r}")
    eta = q * (1.0 + beta) / (2.0 * (1.0 + q))
    return (0.5 * (1.0 - e * e) + eta * (1.0 - eta), eta * eta / q,
            (eta / q) * (1.0 - eta / q))


def rough_cooling_rates(e: float, beta: float, q: float, t_tr: float,
                        t_rot: float) -> tuple[float, float]:
    """The cooling of a homogeneous gas of rough disks (2D, molecular chaos and
    Maxwellian velocities and spins, after Huthmann and Zippelius, Phys. Rev. E 56,
    R6275 (1997) and Luding, Huthmann, McNamara and Zippelius, Phys. Rev. E 58, 3416
    (1998), derived anew for disks): ``dT_tr/dt = omega (-A T_tr + B T_rot)`` and
    ``dT_rot/dt = 2 omega (B T_tr - C T_rot)`` over the collision rate per disk
    ``omega``, with ``eta = q (1 + beta) / (2 (1 + q))``, ``A = (1 - e^2)/2 + eta (1 -
    eta)``, ``B = eta^2 / q`` and ``C = (eta / q)(1 - eta / q)``; ``T_tr = <m v_x^2>``,
    ``T_rot = <I w^2>``.  The factor 2 is that of two translational degrees of freedom
    against one rotational.

    Parameters
    ----------
    e : float
        Normal restitution, in ``(0, 1]``.
    beta : float
        Tangential restitution, in ``[-1, 1]``.
    q : float
        ``I / (m r^2)``, in ``(0, 1]``.
    t_tr, t_rot : float
        The temperatures.

    Returns
    -------
    (float, float)
        ``dT_tr/dt / omega`` and ``dT_rot/dt / omega``.

    Examples
    --------
    >>> [abs(round(x, 12)) for x in rough_cooling_rates(1.0, 1.0, 0.5, 1.0, 1.0)]
    [0.0, 0.0]
    """
    a, b, c = _rough_coefficients(e, beta, q)
    return -a * t_tr + b * t_rot, 2.0 * (b * t_tr - c * t_rot)


def rough_hcs_ratio(e: float, beta: float, q: float = 0.5) -> float:
    """``T_rot / T_tr`` of rough disks in the homogeneous cooling state (where both
    temperatures decay at one rate; the cooling equations of
    :func:`rough_cooling_rates`): the positive root of ``B R^2 + (2 C - A) R - 2 B =
    0``.  ``1`` for ``e = 1`` and ``beta = 1``, where no energy is lost
    (equipartition); any other ``beta`` dissipates the tangential motion, elastic or
    not.

    Parameters
    ----------
    e : float
        Normal restitution, in ``(0, 1]``.
    beta : float
        Tangential restitution, in ``(-1, 1]`` (smooth disks do not exchange).
    q : float, default 0.5
        ``I / (m r^2)``, in ``(0, 1]``.

    Returns
    -------
    float

    Examples
    --------
    >>> round(rough_hcs_ratio(1.0, 1.0), 12), round(rough_hcs_ratio(0.9, 0.0), 4)
    (1.0, 0.4695)
    """
    a, b, c = _rough_coefficients(e, beta, q)
    if b == 0.0:
        raise ValueError("beta = -1: smooth disks have no cooling state of rotation")
    p = a - 2.0 * c
    root = math.sqrt(p * p + 8.0 * b * b)
    # (The two forms of the root; the one without cancellation.)
    return (p + root) / (2.0 * b) if p >= 0.0 else 4.0 * b / (root - p)


def rough_hcs_cooling_rate(e: float, beta: float, q: float = 0.5) -> float:
    """The cooling rate of rough disks in the homogeneous cooling state over the
    collision rate per disk: ``-d ln T / dt / omega = A - B R`` (the same for both
    temperatures; :func:`rough_hcs_ratio`).  Haff's law follows: ``T(t) = T(0) / (1 +
    t / tau)^2`` with ``tau = 2 / (omega_0 (A - B R))``.

    Parameters
    ----------
    e, beta, q : float
        As for :func:`rough_hcs_ratio`.

    Returns
    -------
    float

    Examples
    --------
    >>> round(rough_hcs_cooling_rate(1.0, 1.0), 12)
    0.0
    """
    a, b, _ = _rough_coefficients(e, beta, q)
    return a - b * rough_hcs_ratio(e, beta, q)


def haff_temperature(restitution: float, time: ArrayLike,
                     collision_rate: float) -> float | np.ndarray:
    """Haff's law for a homogeneous cooling gas, ``T / T0 = 1 / (1 + t / t_H)^2`` with
    ``t_H = 4 / ((1 - e^2) omega0)``.

    Parameters
    ----------
    restitution : float
        Coefficient of normal restitution ``e`` in (0, 1].
    time : float or array_like
        Time since ``T0``.
    collision_rate : float
        ``omega0``, collisions per disk per unit time at ``T0`` (for example
        :func:`enskog_collision_rate`).

    Returns
    -------
    float or ndarray
        ``T / T0``.

    Examples
    --------
    >>> round(haff_temperature(0.9, 10.0, 0.25), 4)
    0.799
    """
    e = _restitution(restitution)
    omega = as_positive_float("collision_rate", collision_rate)
    return _out(1.0 / (1.0 + (1.0 - e * e) * omega * np.asarray(time, dtype=float) / 4.0) ** 2)


def collisional_dissipation(n: ArrayLike, restitution: float, temperature: ArrayLike = 1.0,
                            diameter: float = 1.0, mass: float = 1.0,
                            g_contact: ArrayLike = 1.0) -> float | np.ndarray:
    """Energy lost in collisions per unit area and time by a gas of inelastic disks
    with Maxwellian velocities, ``(1 - e^2) n^2 sigma g(sigma) kT sqrt(pi kT / m)``.

    A collision with normal relative speed ``g_n`` loses ``(1 - e^2) m g_n^2 / 4``
    (reduced mass ``m / 2``); weighted by the rate at which they happen, collisions
    have ``<g_n^2> = 4 kT / m``, and a unit area has ``n omega / 2`` of them per unit
    time (:func:`enskog_collision_rate`).  The same rate gives Haff's law
    (:func:`haff_temperature`).

    Parameters
    ----------
    n : float or array_like
        Number density.
    restitution : float
        ``e`` in (0, 1].
    temperature : float or array_like, default 1.0
        ``kT`` (the granular temperature, ``m <v_x^2>``).
    diameter, mass : float, default 1.0
    g_contact : float or array_like, default 1.0
        The pair distribution at contact (1 in a dilute gas).

    Returns
    -------
    float or ndarray
        Energy per unit area and unit time.

    Examples
    --------
    >>> round(collisional_dissipation(0.02, 0.9, 4.0), 6)
    0.001078
    """
    e = _restitution(restitution)
    sigma = as_positive_float("diameter", diameter)
    m = as_positive_float("mass", mass)
    kt = _positive_array("temperature", temperature)
    return _out((1.0 - e * e) * np.asarray(n, dtype=float) ** 2 * sigma
                * np.asarray(g_contact, dtype=float) * kt * np.sqrt(math.pi * kt / m))


def vibrating_wall_power(n: ArrayLike, amplitude: float, omega: float,
                         temperature: ArrayLike = 1.0, mass: float = 1.0,
                         wall_restitution: float = 1.0) -> float | np.ndarray:
    """Mean power that a wall vibrating as ``A sin(omega t)`` along its normal gives a
    Maxwellian gas, per unit length of wall, to leading order in ``A omega / sqrt(kT /
    m)``: ``S = n (A omega)^2 sqrt(2 m kT / pi)`` for an elastic wall (``4 n m <U^2>
    sqrt(kT / (2 pi m))``).

    Derived in the module notes; ``n`` is the density of the gas at the wall and ``A``
    small against the distances over which it changes.  A wall with restitution
    ``e_w`` (the relative normal velocity reversed times ``e_w``) changes a disk's
    energy by ``(m / 2) (2 (1 + e_w) U w - (1 - e_w^2) w^2)`` (``w`` the speed at which
    they meet): it gives ``(1 + e_w) / 2`` of the elastic wall's power and takes
    ``(1 - e_w^2) n kT^(3/2) / sqrt(2 pi m)``, what it would take at rest; the
    difference is returned.

    Parameters
    ----------
    n : float or array_like
        Number density at the wall.
    amplitude, omega : float
        ``A`` and ``omega`` (> 0).
    temperature : float or array_like, default 1.0
        ``kT`` of the gas at the wall.
    mass : float, default 1.0
    wall_restitution : float, default 1.0
        ``e_w`` in (0, 1].

    Returns
    -------
    float or ndarray
        Energy per unit length of wall and unit time (negative where the wall's
        losses exceed its gains).

    Examples
    --------
    >>> round(vibrating_wall_power(0.02, 0.5, 5.0, 100.0), 4)
    0.9974
    >>> round(vibrating_wall_power(0.02, 0.5, 5.0, 100.0, wall_restitution=0.99), 4)
    0.8336
    """
    a = as_positive_float("amplitude", amplitude)
    w = as_positive_float("omega", omega)
    m = as_positive_float("mass", mass)
    ew = _restitution(wall_restitution, "wall_restitution")
    kt = _positive_array("temperature", temperature)
    n = np.asarray(n, dtype=float)
    gain = 0.5 * (1.0 + ew) * n * (a * w) ** 2 * np.sqrt(2.0 * m * kt / math.pi)
    return _out(gain - (1.0 - ew * ew) * n * kt ** 1.5 / math.sqrt(2.0 * math.pi * m))


def vibrated_bed_temperature(amplitude: float, omega: float, restitution: float,
                             disks_per_length: float, diameter: float = 1.0,
                             mass: float = 1.0, wall_restitution: float = 1.0) -> float:
    """Granular temperature of a dilute, nearly elastic bed on a floor vibrating as
    ``A sin(omega t)``, to leading order (Kumaran's regime): for an elastic floor
    ``kT = (2 sqrt(2) / pi) m (A omega)^2 / epsilon``, ``epsilon = (1 - e^2) N sigma /
    L``; for a floor of restitution ``e_w``, ``kT = (1 + e_w) m (A omega)^2 / (pi
    epsilon / sqrt(2) + 1 - e_w^2)``.

    The floor's power (:func:`vibrating_wall_power`) balances the collisions' losses
    (:func:`collisional_dissipation`) integrated over the barometric profile (module
    notes).  It holds where ``epsilon`` is small (the first corrections are of
    relative order ``epsilon^(1/2)``), the disks collide many times in a flight
    (``N sigma / L`` well above 1), the bed is dilute (``(N / L) sigma^2 m g / kT``
    small) and the floor's amplitude is small against the bed's height ``kT / (m
    g)``; an inelastic floor must lose little, ``1 - e_w`` of the order of
    ``epsilon``, or it keeps the bed cold.  Gravity drops out.

    Parameters
    ----------
    amplitude, omega : float
        The floor's amplitude ``A`` and angular frequency ``omega`` (> 0).
    restitution : float
        ``e`` of disk-disk collisions, in (0, 1].
    disks_per_length : float
        ``N / L``, disks per unit length of floor (> 0).
    diameter, mass : float, default 1.0
    wall_restitution : float, default 1.0
        The floor's ``e_w``, in (0, 1].

    Returns
    -------
    float
        ``kT`` (``m <v_x^2> = m <v_y^2>``).

    Examples
    --------
    >>> round(vibrated_bed_temperature(0.5, 5.0, 0.99, 4.0), 3)
    70.691
    >>> round(vibrated_bed_temperature(0.5, 5.0, 0.99, 4.0, wall_restitution=0.99), 3)
    63.222
    """
    e = _restitution(restitution)
    ew = _restitution(wall_restitution, "wall_restitution")
    if e == 1.0 and ew == 1.0:
        raise ValueError("restitution or wall_restitution must be below 1: elastic disks "
                         "on an elastic floor never reach a steady temperature")
    a = as_positive_float("amplitude", amplitude)
    w = as_positive_float("omega", omega)
    per_length = as_positive_float("disks_per_length", disks_per_length)
    sigma = as_positive_float("diameter", diameter)
    m = as_positive_float("mass", mass)
    epsilon = (1.0 - e * e) * per_length * sigma
    return ((1.0 + ew) * m * (a * w) ** 2
            / (math.pi * epsilon / math.sqrt(2.0) + 1.0 - ew * ew))


def _positive_array(name: str, value: ArrayLike) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(arr > 0.0):
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return arr


def _restitution(e, name: str = "restitution") -> float:
    value = float(e)
    if not 0.0 < value <= 1.0:
        raise ValueError(f"{name} must lie in (0, 1], got {e!r}")
    return value

