"""Time and memory of every analysis function on one large system.

The analysis functions must run at any N the engine runs, in memory linear in N.  Each
function is run in a fresh process on the same gas (packing 0.5, built and melted by
``N`` collisions, then handed over as arrays in a temporary file), and the growth of
the process's peak resident set size over the state before the call is reported::

    python benchmarks/analysis_scale.py 1000000
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

_CHILD = r"""
import json, resource, sys, time
import numpy as np
import edmd2d as ed
data = np.load(sys.argv[1])
box = ed.Box(float(data["w"]), float(data["h"]))
pos, vel, rad = data["pos"], data["vel"], data["rad"]
name = sys.argv[2]
frames = np.stack([pos, pos + 0.01 * vel, pos + 0.02 * vel])
calls = {
    "radial_distribution": lambda: ed.radial_distribution(pos, box),
    "speed_distribution": lambda: ed.speed_distribution(vel),
    "maxwell_boltzmann_test": lambda: ed.maxwell_boltzmann_test(vel),
    "hexatic_order(voronoi)": lambda: ed.hexatic_order(pos, box),
    "hexatic_order(cutoff)": lambda: ed.hexatic_order(pos, box, neighbors=1.4 * 2 * rad.max()),
    "mean_squared_displacement": lambda: ed.mean_squared_displacement(frames),
}
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
calls[name]()
seconds = time.perf_counter() - t0
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
print(json.dumps({"seconds": seconds, "peak_growth_bytes": peak * 1024}))
"""

NAMES = ("radial_distribution", "speed_distribution", "maxwell_boltzmann_test",
         "hexatic_order(voronoi)", "hexatic_order(cutoff)", "mean_squared_displacement")


def main(n: int) -> None:
    import numpy as np

    import edmd2d as ed

    sim = ed.make_gas(n, 0.5, seed=1)
    sim.advance(collisions=n)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "gas.npz")
        np.savez(path, pos=sim.positions, vel=sim.velocities, rad=sim.radii,
                 w=sim.box.width, h=sim.box.height)
        print(f"N = {n}: function, seconds, peak memory growth (bytes per disk)")
        for name in NAMES:
            out = subprocess.run([sys.executable, "-c", _CHILD, path, name], check=True,
                                 capture_output=True, text=True).stdout
            res = json.loads(out.strip().splitlines()[-1])
            print(f"{name:>28}  {res['seconds']:8.2f} s  "
                  f"{res['peak_growth_bytes'] / n:8.0f} B/disk", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
