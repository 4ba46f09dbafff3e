"""Contact networks: lattices at contact, rattlers, periodic images, walls, overlaps."""

from __future__ import annotations

import doctest
import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import min_image, seed_of, segment_distance
from edmd2d import _gaps, contacts
from edmd2d.compress import DEFAULT_MAX_PRESSURE

SQRT3 = math.sqrt(3.0)

# Wide tolerances (a neighbour count, not contacts) and hand-built configurations with
# no backbone warn by design; the tests that use them on purpose say so.
WIDE_TOL = pytest.mark.filterwarnings("ignore:contact_network. tol=.*does not separate")
NO_BACKBONE = pytest.mark.filterwarnings("ignore:contact_network. every disk is a rattler")


def square_lattice(nx, ny, spacing=1.0):
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    return np.column_stack([(i.ravel() + 0.5) * spacing, (j.ravel() + 0.5) * spacing])


def triangular_lattice(nx, ny, spacing=1.0):
    """``nx * ny`` sites (``ny`` even) of a triangular lattice and the periodic box that
    fits it exactly."""
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    x = (i + 0.5 * (j % 2) + 0.25) * spacing
    y = (j + 0.5) * spacing * SQRT3 / 2
    return np.column_stack([x.ravel(), y.ravel()]), ed.Box(nx * spacing, ny * spacing * SQRT3 / 2)


def brute_force_pairs(pos, rad, box, tol):
    """Every pair within tol of contact through its nearest image (small systems)."""
    d = min_image(pos[None, :, :] - pos[:, None, :], box)
    dist = np.hypot(d[..., 0], d[..., 1])
    s = rad[:, None] + rad[None, :]
    return {(int(i), int(j)) for i, j in np.argwhere(np.triu(dist - s <= tol * s, k=1))}


def sequential_rattlers(pairs, base, n, need=3):
    """Rattlers removed one at a time, the slowest obvious way."""
    alive = set(range(n))
    while True:
        z = {i: int(base[i]) for i in alive}
        for i, j in pairs:
            if i in alive and j in alive:
                z[i] += 1
                z[j] += 1
        weak = [i for i in sorted(alive) if z[i] < need]
        if not weak:
            break
        alive.discard(weak[0])
    mask = np.ones(n, bool)
    mask[list(alive)] = False
    return mask


# --------------------------------------------------------------------------- lattices
def test_square_lattice_has_four_contacts_each():
    net = ed.contact_network(square_lattice(8, 8), ed.Box(8.0, 8.0), radii=0.5)
    assert net.contact_numbers.tolist() == [4] * 64
    assert net.n_contacts == 128 and len(net.pairs) == 128
    assert net.n_rattlers == 0 and not net.rattlers.any()
    assert net.mean_contact_number == 4.0 and net.excess_contact_number == 0.0
    assert net.isostatic_contact_number == 4.0
    # 2 (N - 1) + 1 = 127 in a periodic box: one contact more than isostatic.
    assert net.n_isostatic == 127 and net.excess_contacts == 1 and not net.is_isostatic
    assert net.max_overlap == 0.0 and len(net.box_contacts) == 0
    assert (net.pairs[:, 0] < net.pairs[:, 1]).all()
    # The diagonal neighbours, sqrt(2) - 1 diameters away, are no contacts even at 0.4
    # (which lies among them, and says so).
    with pytest.warns(UserWarning, match=r"tol=0.4 does not separate .* 256 relative gaps"):
        wide = ed.contact_network(square_lattice(8, 8), ed.Box(8.0, 8.0), radii=0.5, tol=0.4)
    assert wide.n_contacts == 128


def test_triangular_lattice_has_six_contacts_each():
    pos, box = triangular_lattice(8, 8)
    net = ed.contact_network(pos, box, radii=0.5)
    assert net.contact_numbers.tolist() == [6] * 64
    assert net.n_contacts == 192 and net.mean_contact_number == pytest.approx(6.0)
    assert net.excess_contacts == 192 - 127
    assert net.max_relative_overlap < 1e-15  # sqrt(3)/2 rounds to within an ulp
    np.testing.assert_allclose(net.gaps, 0.0, atol=1e-15)


def test_contacts_scale_with_the_disks():
    pos, box = triangular_lattice(6, 6, spacing=2.5)
    net = ed.contact_network(pos, box, radii=1.25)
    assert net.n_contacts == 108


@WIDE_TOL
@NO_BACKBONE  # (tol=0 in a random packing)
def test_pairs_agree_with_brute_force():
    rng = np.random.default_rng(seed_of(3))
    pos, rad, box = ed.random_packing(150, 0.45, radii=rng.uniform(0.3, 0.6, 150),
                                      periodic=(True, False), seed=seed_of(4))
    for tol in (0.0, 0.02, 0.1):
        net = ed.contact_network(pos, box, radii=rad, tol=tol)
        assert {tuple(p) for p in net.pairs.tolist()} == brute_force_pairs(pos, rad, box, tol)


def test_image_search_agrees_with_the_minimum_image():
    # The search through explicit images (for small boxes) against the tree's minimum
    # image, in a box large enough for both.
    pos, rad, box = ed.random_packing(400, 0.4, seed=seed_of(5))
    cut = 1.3
    from scipy import spatial

    fast = spatial.cKDTree(pos, boxsize=box.size).query_pairs(cut, output_type="ndarray")
    slow, vec = _gaps._image_pairs(pos, box, cut)
    assert {tuple(p) for p in fast.tolist()} == {tuple(p) for p in slow.tolist()}
    d = min_image(pos[slow[:, 1]] - pos[slow[:, 0]], box)
    np.testing.assert_allclose(vec, d, rtol=1e-12, atol=1e-12)


# --------------------------------------------------------------------------- rattlers
def test_a_shrunk_disk_is_a_rattler():
    pos, box = triangular_lattice(8, 8)
    rad = np.full(64, 0.5)
    rad[27] = 0.4
    net = ed.contact_network(pos, box, radii=rad)
    assert net.rattlers.tolist() == [k == 27 for k in range(64)]
    assert net.contact_numbers[27] == 0
    assert sorted(net.contact_numbers.tolist()).count(5) == 6  # its neighbours
    assert net.n_contacts == 192 - 6
    assert net.mean_contact_number == pytest.approx(2 * 186 / 63)
    assert net.n_isostatic == 2 * 63 - 2 + 1


def test_a_vacancy_leaves_no_rattler():
    pos, box = triangular_lattice(8, 8)
    net = ed.contact_network(np.delete(pos, 27, axis=0), box, radii=0.5)
    assert net.n_rattlers == 0 and net.n_contacts == 186


def test_rattlers_are_removed_iteratively():
    # A strip of triangles: every disk but the four at the ends has 4 contacts, yet the
    # strip unravels from its ends, one pair of disks after the other.
    k = 12
    a = np.column_stack([np.arange(k), np.zeros(k)])
    b = np.column_stack([np.arange(k - 1) + 0.5, np.full(k - 1, SQRT3 / 2)])
    pos = np.concatenate([a, b]) + 5.0
    with pytest.warns(UserWarning, match=r"every disk is a rattler at tol=1e-07 \(43 contacts"):
        net = ed.contact_network(pos, ed.Box(30.0, 30.0), radii=0.5)
    assert (net.contact_numbers >= 3).sum() == 2 * k - 1 - 2
    assert net.rattlers.all() and net.n_contacts == 0
    assert math.isnan(net.mean_contact_number) and not net.is_isostatic
    # Walls at both ends hold it: x = 5 - 0.5 and x = 5 + k - 1 + 0.5 touch the end disks.
    held = ed.contact_network(pos - [4.5, 0.0], ed.Box(float(k), 30.0, periodic=(False, True)),
                              radii=0.5)
    assert held.n_rattlers == 0
    assert sorted(map(tuple, held.box_contacts.tolist())) == [(0, 0), (k - 1, 1)]


@WIDE_TOL
def test_peeling_matches_one_at_a_time_removal():
    for seed in range(4):
        rng = np.random.default_rng(seed)
        pos, rad, box = ed.random_packing(300, 0.5, radii=rng.uniform(0.4, 0.6, 300),
                                          periodic=bool(seed % 2), seed=seed)
        # A loose tolerance makes a contact graph near its rigidity threshold: a
        # backbone remains, and most rattlers only become rattlers as others go.
        net = ed.contact_network(pos, box, radii=rad, tol=0.45)
        walls = np.bincount(net.box_contacts[:, 0], minlength=300)
        expected = sequential_rattlers(net.pairs.tolist(), walls, 300)
        np.testing.assert_array_equal(net.rattlers, expected)
        assert (net.contact_numbers < 3).sum() < net.n_rattlers < 300


# --------------------------------------------------------------------------- periodic
@NO_BACKBONE
def test_contacts_across_the_periodic_edges():
    box = ed.Box(10.0, 8.0)
    pos = np.array([[0.2, 4.0], [9.2, 4.0],      # across x = 0
                    [5.0, 0.3], [5.0, 7.3],      # across y = 0
                    [0.1, 7.9], [9.6, 0.4]])     # across the corner, diagonal
    rad = np.array([0.5, 0.5, 0.5, 0.5, 0.5, 0.5 * math.hypot(0.5, 0.5) * 2 - 0.5])
    net = ed.contact_network(pos, box, radii=rad)
    assert net.pairs.tolist() == [[0, 1], [2, 3], [4, 5]]
    np.testing.assert_allclose(net.gaps, 0.0, atol=1e-14)
    walled = ed.contact_network(pos, ed.Box(10.0, 8.0, periodic=False), radii=rad)
    assert len(walled.pairs) == 0


@NO_BACKBONE
def test_a_box_two_diameters_wide_holds_two_contacts_per_pair():
    pos = np.array([[0.5, 2.0], [1.5, 2.0]])
    net = ed.contact_network(pos, ed.Box(2.0, 5.0, periodic=(True, False)), radii=0.5)
    assert net.pairs.tolist() == [[0, 1], [0, 1]]  # left and right of each other
    assert net.contact_numbers.tolist() == [2, 2]
    # A disk touching its own image constrains nothing and is no contact.
    alone = ed.contact_network([[0.5, 2.0]], ed.Box(1.0, 5.0, periodic=(True, False)),
                               radii=0.5)
    assert len(alone.pairs) == 0


# --------------------------------------------------------------------------- walls
def test_box_wall_contacts():
    pos = square_lattice(4, 4)
    net = ed.contact_network(pos, ed.Box(4.0, 4.0, periodic=False), radii=0.5)
    assert len(net.box_contacts) == 16
    sides = np.bincount(net.box_contacts[:, 1], minlength=4).tolist()
    assert sides == [4, 4, 4, 4] and ed.contacts.BOX_SIDES[2] == "bottom"
    assert sorted(net.contact_numbers.tolist()) == [4] * 16  # corners 2 + 2, edges 1 + 3
    assert net.n_contacts == 24 and net.n_wall_contacts == 16
    assert net.n_isostatic == 2 * 16 + 1 and net.excess_contacts == 24 + 16 - 33
    assert net.mean_contact_number == pytest.approx((2 * 24 + 16) / 16)
    channel = ed.contact_network(pos, ed.Box(4.0, 4.0, periodic=(True, False)), radii=0.5)
    assert sorted(set(channel.box_contacts[:, 1].tolist())) == [2, 3]
    assert channel.n_contacts == 28 and channel.n_isostatic == 2 * 16 - 1 + 1


def test_a_disk_held_by_three_walls_is_isostatic_by_count():
    net = ed.contact_network([[0.5, 0.5]], ed.Box(1.0, 3.0, periodic=False), radii=0.5)
    assert net.n_wall_contacts == 3 and net.n_isostatic == 3 and net.is_isostatic


@NO_BACKBONE
def test_wall_segment_contacts():
    box = ed.Box(10.0, 10.0)
    walls = [ed.Wall((5.0, 2.0), (5.0, 8.0)), ed.Wall((0.2, 1.0), (0.2, 3.0))]
    pos = np.array([[4.5, 5.0],              # side of walls[0]
                    [5.0, 8.0 + 0.5],        # its end point
                    [5.0 + 0.5 / math.sqrt(2), 1.5],   # not quite the end (1.5 < 2)
                    [9.7, 2.0],              # walls[1] through the periodic image
                    [2.0, 9.0]])
    net = ed.contact_network(pos, box, radii=0.5, walls=walls)
    assert net.wall_contacts.tolist() == [[0, 0], [1, 0], [3, 1]]
    np.testing.assert_allclose(net.wall_gaps, 0.0, atol=1e-14)
    assert net.contact_numbers.tolist() == [1, 1, 0, 1, 0]
    # the image-free distance of disk 3 is far: only the image touches
    assert segment_distance(pos[3], walls[1]) > 9.0


def test_a_simulation_is_read_with_its_walls():
    pos = square_lattice(4, 4)
    box = ed.Box(4.0, 4.0, periodic=False)
    sim = ed.Simulation(pos, np.zeros_like(pos), 0.5, box=box,
                        walls=[ed.Wall((2.0, 0.0), (2.0, 0.5))])
    net = ed.contact_network(sim)
    assert net.wall_contacts.tolist() == [[1, 0], [2, 0]]  # the stub's end touches two
    assert len(net.box_contacts) == 16 and net.n_contacts == 24
    with pytest.raises(TypeError, match="radii must not be given with a Simulation"):
        ed.contact_network(sim, radii=0.5)
    with pytest.raises(TypeError, match="box must not be given with a Simulation"):
        ed.contact_network(sim, box)


# --------------------------------------------------------------------------- overlaps
@NO_BACKBONE
def test_overlaps_are_reported():
    pos = np.array([[2.0, 2.0], [2.999, 2.0], [6.0, 0.4]])
    net = ed.contact_network(pos, ed.Box(8.0, 8.0, periodic=(True, False)), radii=0.5)
    assert net.pairs.tolist() == [[0, 1]]
    assert net.gaps[0] == pytest.approx(-1e-3)
    assert net.box_contacts.tolist() == [[2, 2]] and net.box_gaps[0] == pytest.approx(-0.1)
    assert net.max_overlap == pytest.approx(0.1)
    assert net.max_relative_overlap == pytest.approx(0.1)  # relative to the diameter
    # Overlaps are contacts at any tolerance, zero included.
    assert ed.contact_network(pos[:2], ed.Box(8.0, 8.0), radii=0.5, tol=0.0).max_overlap \
        == pytest.approx(1e-3)


def test_result_is_frozen():
    net = ed.contact_network(square_lattice(4, 4), ed.Box(4.0, 4.0), radii=0.5)
    with pytest.raises(AttributeError):
        net.tol = 0.5
    with pytest.raises(ValueError, match="read-only"):
        net.rattlers[0] = True
    assert "ContactNetwork(disks=16" in repr(net)


# --------------------------------------------------------------------------- tolerance
def test_automatic_tolerance_separates_contacts_from_near_contacts():
    # A triangular lattice whose contact gaps spread over decades (as in a compressed
    # packing), with every tenth disk shrunk into a rattler with gaps of 1e-4 and more.
    rng = np.random.default_rng(seed_of(7))
    pos, box = triangular_lattice(20, 20)
    rad = 0.5 - 10.0 ** rng.uniform(-14, -11, 400)
    rad[::10] = 0.5 - 10.0 ** rng.uniform(-4, -2, 40)
    tol = ed.contact_tolerance(pos, box, radii=rad)
    assert 1e-11 < tol < 1e-4
    net = ed.contact_network(pos, box, radii=rad, tol="auto")
    assert net.tol == tol
    assert net.rattlers.tolist() == [k % 10 == 0 for k in range(400)]
    full = ed.contact_network(pos, box, radii=0.5).pairs
    assert net.n_contacts == int((full % 10 != 0).all(axis=1).sum())


@pytest.fixture(scope="module")
def jammed_mixtures():
    """The 50:50 mixture of diameter ratio 1.4 (128 disks) jammed by compress with its
    default stop, Z >= 1e9, at two seeds."""
    radii = np.where(np.arange(128) % 2, 0.5, 0.7)
    return [ed.compress(ed.random_gas(128, 0.4, radii=radii, seed=seed_of(k)), rate=1e-2)
            for k in (20, 21)]


def test_the_default_tolerance_finds_the_contacts_of_a_default_compression(jammed_mixtures):
    import warnings

    for jam in jammed_mixtures:
        assert jam.reached == "jammed" and jam.reduced_pressure >= DEFAULT_MAX_PRESSURE
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # a clear separation: no warning
            net = ed.contact_network(jam.simulation)
        assert net.tol == contacts.DEFAULT_TOL == 1e-7
        # Non-rattlers near the isostatic 4 (3.83-3.95 at 128 disks over ten seeds,
        # with 5-20 % rattlers), and the contacts of the rule 100 / Z of its own Z.
        assert 3.75 < net.mean_contact_number < 4.05
        assert net.n_rattlers < 0.3 * len(net.rattlers)
        ref = ed.contact_network(jam.simulation, tol=100.0 / jam.reduced_pressure)
        np.testing.assert_array_equal(net.rattlers, ref.rattlers)
        assert net.n_contacts == ref.n_contacts
        # Isostatic to within a few contacts (rattlers' partners missing).
        assert -0.05 * net.n_isostatic < net.excess_contacts <= 2


def test_a_tolerance_among_the_gaps_warns_naming_it(jammed_mixtures):
    sim = jammed_mixtures[0].simulation
    # 1 / Z: the contacts' gaps spread on both sides, and most disks look free.
    with pytest.warns(UserWarning, match=r"tol=1e-09 does not separate contacts from gaps"):
        net = ed.contact_network(sim, tol=1e-9)
    assert net.n_rattlers > 0.9 * len(sim)
    # A packing compressed to Z = 1e7 only: its contacts lie about the default.
    radii = np.where(np.arange(64) % 2, 0.5, 0.7)
    loose = ed.compress(ed.random_gas(64, 0.4, radii=radii, seed=seed_of(22)), rate=1e-2,
                        max_pressure=1e7)
    with pytest.warns(UserWarning, match=r"tol=1e-07"):
        ed.contact_network(loose.simulation)
    # With tol = 100 / Z it is a packing again.
    net = ed.contact_network(loose.simulation, tol=100.0 / loose.reduced_pressure)
    assert 3.5 < net.mean_contact_number < 4.2


def test_automatic_tolerance_refuses_an_uncompressed_packing():
    pos, rad, box = ed.random_packing(500, 0.45, seed=seed_of(3))
    with pytest.raises(ValueError, match="no clear separation"):
        ed.contact_tolerance(pos, box, radii=rad)
    with pytest.raises(ValueError, match="no clear separation"):
        ed.contact_network(pos, box, radii=rad, tol="auto")
    with pytest.raises(ValueError, match="min_separation must be > 1"):
        ed.contact_tolerance(pos, box, radii=rad, min_separation=1.0)


# --------------------------------------------------------------------------- errors
@pytest.mark.parametrize(
    "args, kwargs, error, pattern",
    [
        (([[1.0, 1.0]], ed.Box(4, 4)), {"radii": 0.5, "tol": -1e-9}, ValueError,
         "tol must be >= 0, got -1e-09"),
        (([[1.0, 1.0]], ed.Box(4, 4)), {"radii": 0.5, "tol": 1.0}, ValueError, "tol must be < 1"),
        (([[1.0, 1.0]], ed.Box(4, 4)), {"radii": 0.5, "tol": "tight"}, ValueError,
         'tol must be a number in \\[0, 1\\) or "auto"'),
        (([[1.0, 1.0]], ed.Box(4, 4)), {"radii": 0.5, "tol": np.nan}, ValueError,
         "tol must be finite"),
        (([[1.0, 1.0, 0.0]], ed.Box(4, 4)), {"radii": 0.5}, ValueError,
         r"positions must have shape \(N, 2\), got shape \(1, 3\)"),
        ((np.zeros((0, 2)), ed.Box(4, 4)), {"radii": 0.5}, ValueError, "at least one disk"),
        (([[1.0, 1.0], [2.0, 2.0]], ed.Box(4, 4)), {"radii": [0.5, 0.5, 0.5]}, ValueError,
         r"radii must have shape \(2,\), got shape \(3,\)"),
        (([[1.0, 1.0], [2.0, 2.0]], ed.Box(4, 4)), {"radii": [0.5, -0.5]}, ValueError,
         r"radii must be > 0; disks \[1\] are not"),
        (([[1.0, 1.0]], ed.Box(4, 4)), {}, TypeError, "radii is required"),
        (([[1.0, 1.0]],), {"radii": 0.5}, TypeError, "box is required"),
        (([[1.0, 1.0]], (4, 4)), {"radii": 0.5}, TypeError, "box must be an edmd2d.Box"),
        (([[1.0, 1.0]], ed.Box(4, 4)), {"radii": 0.5, "walls": [(0, 0)]}, TypeError,
         r"walls\[0\] must be an edmd2d.Wall"),
        (([[5.0, 1.0]], ed.Box(4, 4, periodic=False)), {"radii": 0.5}, ValueError,
         "outside the walled x axis"),
        ((["a", "b"], ed.Box(4, 4)), {"radii": 0.5}, TypeError, "positions must be numeric"),
    ],
)
def test_bad_arguments(args, kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        ed.contact_network(*args, **kwargs)


# --------------------------------------------------------------------------- scale
@WIDE_TOL
def test_a_large_packing_is_quick():
    import time

    pos, rad, box = ed.random_packing(50_000, 0.5, seed=seed_of(1))
    start = time.perf_counter()
    net = ed.contact_network(pos, box, radii=rad, tol=0.05)
    assert time.perf_counter() - start < 5.0  # (about 0.1 s; generous on a shared machine)
    assert net.n_disks == 50_000 and len(net.pairs) > 0


# --------------------------------------------------------------------------- freud
@WIDE_TOL
def test_neighbour_counts_agree_with_freud():
    freud = pytest.importorskip("freud", reason="freud-analysis is not installed: the "
                                "cross-check with freud.locality is skipped")
    pos, rad, box = ed.random_packing(2000, 0.5, seed=seed_of(9))
    tol = 0.1
    net = ed.contact_network(pos, box, radii=rad, tol=tol)
    fbox = freud.box.Box(Lx=box.width, Ly=box.height, is2D=True)
    pts = np.column_stack([pos - box.size / 2, np.zeros(len(pos))])
    query = freud.locality.AABBQuery(fbox, pts)
    nlist = query.query(pts, {"r_max": 1.0 * (1 + tol), "exclude_ii": True}).toNeighborList()
    np.testing.assert_array_equal(nlist.neighbor_counts, net.contact_numbers)


def test_doctests():
    assert doctest.testmod(contacts, raise_on_error=False).failed == 0


def test_an_open_wall_segment_is_in_no_contact():
    box = ed.Box(10.0, 10.0, periodic=False)
    walls = [ed.Wall((0.0, 2.0), (10.0, 2.0)), ed.Wall((0.0, 6.0), (10.0, 6.0))]
    pos = [[3.0, 2.5], [6.0, 6.5]]  # each touching one shelf from above
    with pytest.warns(UserWarning, match="rattler"):  # (two lone disks: no backbone)
        closed = contacts.contact_network(ed.Simulation(pos, [[0, 0]] * 2, 0.5, box=box,
                                                        walls=walls), tol=1e-9)
    assert closed.wall_contacts.tolist() == [[0, 0], [1, 1]]
    sim = ed.Simulation(pos, [[0, 0]] * 2, 0.5, box=box, walls=walls, open_walls=[1])
    with pytest.warns(UserWarning, match="rattler"):
        assert contacts.contact_network(sim, tol=1e-9).wall_contacts.tolist() == [[0, 0]]
