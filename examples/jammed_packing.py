"""A jammed packing: 10^4 disks of a 50:50 mixture compressed until they jam.

Physics: 10 000 disks, half of diameter 1 and half of diameter 1.4 (the classic
bidisperse mixture, which does not crystallise), start at random at packing fraction
0.4 in a periodic box and grow (the Lubachevsky-Stillinger compression, at the rate
``RATE``: the mean diameter grows at that fraction of the thermal speed) with the
temperature held at kT = 1, until the reduced pressure ``Z = PA / NkT`` passes 1e9.
The disks are then jammed: touching disks are about 1e-9 diameters apart, and the
packing fraction is near the 0.84 found for this mixture by energy minimisation
(O'Hern, Silbert, Liu and Nagel, Phys. Rev. E 68, 011306 (2003)).

The contacts (gaps below ``100 / Z``, :func:`edmd2d.contact_network`) make a rigid
network: every disk but the rattlers (fewer than three contacts, peeled off one
after the other) has on average close to the isostatic ``2d = 4`` contacts.

Writes a figure (``.png``): the packing with each disk coloured by its number of
contacts (rattlers grey) and the contact network drawn in, beside the compression's
``Z`` against packing fraction; prints the jamming packing fraction, the contact
numbers and the isostatic count::

    python examples/jammed_packing.py [examples/output/jammed_packing.png] [--n 1000]
"""

from __future__ import annotations

import time

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection, LineCollection  # noqa: E402

import edmd2d as ed  # noqa: E402

N, SEED, RATE, START, MAX_PRESSURE = 10_000, 1, 1e-2, 0.4, 1e9


def jam():
    """The compression and the contact network of its final packing."""
    radii = np.where(np.arange(N) % 2, 0.5, 0.7)
    gas = ed.random_gas(N, START, radii=radii, seed=SEED)
    clock = time.perf_counter()
    result = ed.compress(gas, rate=RATE, max_pressure=MAX_PRESSURE, progress=True)
    seconds = time.perf_counter() - clock
    net = ed.contact_network(result.simulation, tol=100.0 / result.reduced_pressure)
    return result, net, seconds


def main(out):
    result, net, seconds = jam()
    sim = result.simulation
    pos, rad = sim.positions, sim.radii
    z = net.contact_numbers.astype(float)
    fig, (ax, ax_z) = plt.subplots(1, 2, figsize=(12, 6),
                                   gridspec_kw={"width_ratios": [1.2, 1]})
    cmap = plt.get_cmap("viridis", 6)
    colors = cmap((np.clip(z, 3, 8) - 3) / 5)
    colors[net.rattlers] = (0.8, 0.8, 0.8, 1.0)
    disks = EllipseCollection(2 * rad, 2 * rad, 0, units="xy", offsets=pos,
                              offset_transform=ax.transData, facecolors=colors,
                              edgecolors="none")
    ax.add_collection(disks)
    i, j = net.pairs[:, 0], net.pairs[:, 1]
    d = pos[j] - pos[i]
    size = np.array(sim.box.size)
    d -= size * np.round(d / size)  # (a bond through the periodic boundary)
    segments = np.stack([pos[i], pos[i] + d], axis=1)
    ax.add_collection(LineCollection(segments, colors="k", linewidths=0.3))
    ax.set_xlim(0, sim.box.width)
    ax.set_ylim(0, sim.box.height)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(f"{N} disks jammed at packing fraction {result.packing_fraction:.4f}")
    mappable = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(2.5, 8.5))
    fig.colorbar(mappable, ax=ax, shrink=0.7, label="contacts (rattlers grey)")
    ax_z.semilogy(result.packing_fractions, result.reduced_pressures, "k", lw=0.8)
    ax_z.set_xlabel("packing fraction")
    ax_z.set_ylabel("Z = PA / NkT")
    ax_z.set_title(f"compression at rate {RATE:g}")
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(f"jammed at packing fraction {result.packing_fraction:.5f} (Z = "
          f"{result.reduced_pressure:.3g}) after {int(result.collisions[-1])} collisions "
          f"in {seconds:.1f} s")
    print(f"contacts: {net.n_contacts} among {N - net.n_rattlers} non-rattlers "
          f"({net.n_rattlers} rattlers); mean contact number "
          f"{net.mean_contact_number:.3f} (isostatic 4: {net.n_isostatic} contacts); "
          f"largest overlap {net.max_relative_overlap:.1e} of a contact distance")
    print(f"wrote {out}")
    return result, net


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "jammed_packing.png")
