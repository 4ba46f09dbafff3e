"""The numbers the README quotes for its measuring and compression examples, as ranges
over seeds (about 20 s a seed on one core).

A trajectory is chaotic, so the last bits of a run depend on the versions of NumPy,
numba and the C library (docs/guide/reproducibility.md): a number quoted for one seed
is reproduced only where those are the same, while the range over seeds is what any
machine reproduces.  Usage::

    python examples/readme_ranges.py            # seeds 1-8
    python examples/readme_ranges.py --seeds 1-16
"""

from __future__ import annotations

import argparse

import numpy as np

import edmd2d as ed


def one_seed(seed: int) -> dict:
    """The README's measuring block (4096 disks at 0.5) and its compression block (400
    equal disks to 0.65 at rate 1e-3; 256 disks of the 50:50 mixture of diameter ratio
    1.4 jammed at rate 1e-2) for one seed."""
    sim = ed.make_gas(4096, 0.5, seed=seed)
    sim.advance(collisions=100 * 4096)
    m = sim.measure(duration=50.0)
    fluid = ed.compress(ed.random_gas(400, 0.3, seed=seed), 0.65, rate=1e-3)
    radii = np.where(np.arange(256) % 2, 0.5, 0.7)
    jam = ed.compress(ed.random_gas(256, 0.4, radii=radii, seed=seed), rate=1e-2)
    net = ed.contact_network(jam.simulation, tol=100 / jam.reduced_pressure)
    return {"Z": m.compressibility_factor, "Z error": m.compressibility_factor_error,
            "Z at 0.65": float(fluid.reduced_pressures[-20:].mean()),
            "jammed at": jam.packing_fraction, "contacts": net.mean_contact_number}


def main(seeds: range) -> dict:
    rows = []
    for seed in seeds:
        row = one_seed(seed)
        rows.append(row)
        print(f"seed {seed}: " + ", ".join(f"{k} {v:.4f}" for k, v in row.items()), flush=True)
    ranges = {key: (min(r[key] for r in rows), max(r[key] for r in rows)) for key in rows[0]}
    print(f"seeds {seeds.start}-{seeds.stop - 1}: "
          + ", ".join(f"{k} {lo:.4f}-{hi:.4f}" for k, (lo, hi) in ranges.items()))
    return ranges


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="1-8", help="first-last (default 1-8)")
    first, last = (int(x) for x in parser.parse_args().seeds.split("-"))
    main(range(first, last + 1))
