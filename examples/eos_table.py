"""The hard-disk equation of state and collision rate, measured, next to the literature.

Physics: for hard disks the pressure is entirely kinetic plus collisional.  The virial
theorem in 2D gives ``Z = P A / (N kT) = 1 + sum J |r_ij| / (2 t N kT)`` from the
impulses of the collisions, and in equilibrium the same contact value
``g(sigma) = (Z - 1) / (2 eta)`` fixes the collision rate per disk,
``omega = 2 n sigma g(sigma) sqrt(pi kT / m)``.  This script measures both at packing
fractions 0.3, 0.5 and 0.6 and prints them beside Kolafa and Rottner's equation of
state (the reference for the fluid, from simulations extrapolated to infinite size),
Henderson's and the Santos-Lopez de Haro-Yuste formulas and the virial series to B_10.

    python examples/eos_table.py                  # N = 4096, 2e7 collisions per point
    python examples/eos_table.py --n 1024 --collisions 2e6
    python examples/eos_table.py --finite-size    # Z for N = 256 ... 16384
"""

from __future__ import annotations

import argparse
import math
import time

import edmd2d as ed
from edmd2d import theory

SEED = 2024


def enskog(eta, z):
    """Collision rate per disk of unit disks (sigma = m = kT = 1) for a given Z."""
    return theory.enskog_collision_rate(theory.number_density(eta), 1.0,
                                        theory.contact_value(z, eta))


def run(n, eta, collisions, blocks=20, seed=SEED):
    sim = ed.make_gas(n, eta, seed=seed)
    sim.advance(collisions=100 * n // 2)  # melt the lattice start: 100 collisions per disk
    duration = 2.0 * collisions / (n * enskog(eta, theory.henderson_z(eta)))
    start = time.perf_counter()
    m = sim.measure(duration=duration, blocks=blocks)
    return m, time.perf_counter() - start


def table(n, collisions, etas=(0.3, 0.5, 0.6)):
    print(f"N = {n} disks (radius 0.5, m = 1, kT = 1, periodic square box), seed {SEED};")
    print(f"~{collisions:.3g} collisions per point after 100 collisions per disk; "
          "errors: standard error over 20 blocks.\n")
    for eta in etas:
        m, seconds = run(n, eta, collisions)
        z, z_err = m.compressibility_factor, m.compressibility_factor_error
        print(f"eta = {eta}: run length t = {m.duration:.1f} ({m.collisions} collisions, "
              f"{seconds:.1f} s)")
        print(f"  Z measured                {z:.5f} +- {z_err:.5f}")
        for name, ref in (("Kolafa-Rottner 2006", theory.kolafa_rottner_z(eta)),
                          ("Henderson 1975", theory.henderson_z(eta)),
                          ("Santos et al. 1995", theory.santos_z(eta)),
                          ("virial series B2..B10", theory.virial_z(eta))):
            print(f"  Z {name:<24}{ref:.5f}   (measured - ref = {z - ref:+.5f}, "
                  f"{(z - ref) / z_err:+.1f} sigma)")
        g_virial = theory.contact_value(z, eta)
        print(f"  collision rate            {m.collision_rate:.5f} +- "
              f"{m.collision_rate_error:.5f}"
              " per disk per unit time")
        for name, ref in (("measured Z", z), ("Kolafa-Rottner", theory.kolafa_rottner_z(eta)),
                          ("Henderson", theory.henderson_z(eta)),
                          ("Santos et al.", theory.santos_z(eta))):
            print(f"  Enskog rate, g(sigma) from {name:<14}{enskog(eta, ref):.5f}")
        g_rate = m.collision_rate / (2 * theory.number_density(eta)
                                     * math.sqrt(math.pi * m.temperature))
        print(f"  g(sigma): from virial {g_virial:.5f}, from collision rate {g_rate:.5f}")
        print(f"  mean free time {m.mean_free_time:.5f}, mean free path "
              f"{m.mean_free_path:.5f}, kT = {m.temperature:.12f}\n")


def finite_size(collisions):
    print("Finite-size dependence of Z (same number of collisions per point):")
    for eta in (0.3, 0.5):
        for n in (256, 1024, 4096, 16384):
            m, _ = run(n, eta, collisions)
            print(f"  eta {eta}  N {n:6d}  Z {m.compressibility_factor:.5f} +- "
                  f"{m.compressibility_factor_error:.5f}")
        print(f"  eta {eta}  Henderson {theory.henderson_z(eta):.5f}  virial series "
              f"{theory.virial_z(eta):.5f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=4096, help="number of disks")
    parser.add_argument("--collisions", type=float, default=2e7,
                        help="collisions per measurement")
    parser.add_argument("--finite-size", action="store_true",
                        help="Z against N instead of the table")
    args = parser.parse_args()
    if args.finite_size:
        finite_size(int(args.collisions))
    else:
        table(args.n, int(args.collisions))
