"""Fingerprints of trajectories: a short hash of the exact state that fixed seeds give.

Two machines (or two environments) that print the same fingerprints computed the same
trajectories to the last bit; where one line differs, the first differing line says
which step diverged: the builders (``make_gas``, ``random_gas``), the elastic engine,
the thermostat's random draws, or the compression's rescaling.  CI prints them, so
that machines can be compared from their CI logs alone::

    python benchmarks/fingerprints.py            # about 10 s once the engine is compiled

The first lines name the versions and the machine: Python, NumPy, SciPy, numba,
llvmlite, the C library, the processor and the BLAS kernel that NumPy's OpenBLAS
chose for it (``OPENBLAS_CORETYPE`` overrides that choice).  See
``docs/guide/reproducibility.md`` for what is reproducible where.
"""

from __future__ import annotations

import hashlib
import math
import os
import platform
import sys

import numpy as np

import edmd2d as ed


def digest(*arrays) -> str:
    """The first 16 hex digits of the SHA-256 of the arrays' float64 bytes."""
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
    return h.hexdigest()[:16]


def state(sim) -> str:
    """The digest of a simulation's time, positions and velocities."""
    return digest([sim.time], sim.positions, sim.velocities)


def blas() -> str:
    """The BLAS library NumPy calls and the kernel it chose ("unknown" without
    threadpoolctl, which the ``test`` extra installs)."""
    try:
        import threadpoolctl
    except ImportError:
        return "unknown (threadpoolctl not installed)"
    infos = [i for i in threadpoolctl.threadpool_info() if i.get("user_api") == "blas"]
    return "; ".join(f"{i.get('internal_api')} {i.get('version')} "
                     f"kernel={i.get('architecture')}" for i in infos) or "none found"


def machine() -> list[str]:
    import llvmlite
    import numba
    import scipy

    libc = " ".join(platform.libc_ver())
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f
                       if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return [f"python {sys.version.split()[0]}, numpy {np.__version__}, scipy "
            f"{scipy.__version__}, numba {numba.__version__}, llvmlite "
            f"{llvmlite.__version__}, edmd2d {ed.__version__}",
            f"machine: {platform.machine()}, {cpu}, {libc}",
            f"blas: {blas()}; OPENBLAS_CORETYPE={os.environ.get('OPENBLAS_CORETYPE', '')!r}"]


def fingerprints() -> list[tuple[str, str]]:
    """(what, digest) for each step, in the order a divergence would propagate."""
    rows = []
    gas = ed.make_gas(1000, 0.5, seed=1)
    rows.append(("make_gas(1000, 0.5, seed=1)", state(gas)))
    rgas = ed.random_gas(1000, 0.4, seed=1)
    rows.append(("random_gas(1000, 0.4, seed=1)", state(rgas)))
    for collisions in (1_000, 100_000):
        sim = ed.make_gas(1000, 0.5, seed=1)
        sim.advance(collisions=collisions)
        rows.append((f"make_gas(...) after {collisions} collisions", state(sim)))
    for collisions in (1_000, 100_000):
        sim = ed.make_gas(1000, 0.5, seed=1, thermostat=(1.0, 1.0))
        sim.advance(collisions=collisions)
        rows.append((f"with thermostat (1, 1), after {collisions} collisions", state(sim)))
    result = ed.compress(ed.random_gas(256, 0.3, aspect=2 / math.sqrt(3), seed=3),
                         rate=1e-2, max_pressure=1e3)
    rows.append(("compress(random_gas(256, 0.3, seed=3), to Z = 1e3)",
                 state(result.simulation)))
    return rows


def main() -> None:
    for line in machine():
        print(line)
    for what, value in fingerprints():
        print(f"fingerprint {value}  {what}")


if __name__ == "__main__":
    main()
