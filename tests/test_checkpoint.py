"""Checkpoints: a run continued from a file is the run that never stopped, bit for bit;
bad files are refused with a clear error; an interrupted write loses nothing."""

from __future__ import annotations

import importlib.util
import json
import os
import stat
import subprocess
import sys
import zipfile

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d import checkpoint


def everything(seed=None):
    """A run that uses every piece of state: gravity, restitution and rest on the
    floor, a heated wall, a thermostat (random stream), a peg, periodic wraps."""
    seed = seed_of(1) if seed is None else seed
    gas = ed.make_gas(300, 0.3, periodic=(True, False), seed=seed)
    mass = gas.masses.copy()
    mass[0] = np.inf
    vel = gas.velocities.copy()
    vel[0] = 0.0
    return ed.Simulation(gas.positions, vel, gas.radii, mass, box=gas.box,
                         gravity=(0.05, -0.3), restitution=0.85, wall_restitution=0.8,
                         wall_temperatures={"bottom": 2.0}, thermostat=(1.0, 0.05), seed=seed)


def state_digest(sim):
    return (sim.positions.tobytes(), sim.velocities.tobytes(),
            sim.unwrapped_positions.tobytes(), sim.counts, sim.dissipated_energy(),
            sim.thermostat_energy(), sim.wall_heat().tobytes(), sim.time)


def test_restart_continues_bit_identically(tmp_path):
    whole = everything().advance(until=30.0)
    part = everything().advance(until=12.5)
    path = tmp_path / "run.edmd2d"
    checkpoint.save(part, path)
    resumed = checkpoint.load(path).advance(until=30.0)
    assert state_digest(resumed) == state_digest(whole)
    # Saving does not touch the simulation.
    assert state_digest(part.advance(until=30.0)) == state_digest(whole)


def test_restart_in_a_new_process_is_bit_identical(tmp_path):
    """The file alone carries the run: a fresh interpreter continues it exactly."""
    path = tmp_path / "run.edmd2d"
    checkpoint.save(everything().advance(until=5.0), path)
    code = ("import sys, edmd2d as ed\n"
            "sim = ed.checkpoint.load(sys.argv[1]).advance(until=20.0)\n"
            "ed.checkpoint.save(sim, sys.argv[2])\n")
    out = tmp_path / "after.edmd2d"
    subprocess.run([sys.executable, "-c", code, str(path), str(out)], check=True)
    assert state_digest(checkpoint.load(out)) == state_digest(
        everything().advance(until=20.0))


def test_large_reordered_gas_restarts_exactly(tmp_path):
    """10^4 disks: the rows have been re-sorted in memory (Z-order) and the lookahead
    runs; the internal order is part of the state."""
    whole = ed.make_gas(10_000, 0.5, seed=seed_of(3)).advance(collisions=250_000)
    part = ed.make_gas(10_000, 0.5, seed=seed_of(3)).advance(collisions=120_000)
    checkpoint.save(part, tmp_path / "gas")
    resumed = checkpoint.load(tmp_path / "gas").advance(collisions=130_000)
    assert state_digest(resumed) == state_digest(whole)


def test_an_interrupted_write_keeps_the_previous_checkpoint(tmp_path, monkeypatch):
    path = tmp_path / "run.edmd2d"
    sim = ed.make_gas(100, 0.3, seed=seed_of(1))
    checkpoint.save(sim, path)
    before = path.read_bytes()

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    from edmd2d import _atomic

    monkeypatch.setattr(_atomic.os, "replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        checkpoint.save(sim.advance(until=5.0), path)
    assert path.read_bytes() == before
    assert os.listdir(tmp_path) == ["run.edmd2d"]  # (no temporary file left)


def test_truncated_and_corrupted_files_are_refused(tmp_path):
    path = tmp_path / "run.edmd2d"
    checkpoint.save(ed.make_gas(100, 0.3, seed=seed_of(1)), path)
    data = path.read_bytes()
    (tmp_path / "cut").write_bytes(data[: len(data) // 2])
    with pytest.raises(ValueError, match="truncated or corrupted"):
        checkpoint.load(tmp_path / "cut")
    flipped = bytearray(data)
    flipped[len(data) // 3] ^= 0xFF  # (inside an array member: its CRC fails)
    (tmp_path / "flipped").write_bytes(bytes(flipped))
    with pytest.raises(ValueError, match="corrupted"):
        checkpoint.load(tmp_path / "flipped")


def test_files_that_are_not_checkpoints_are_refused(tmp_path):
    (tmp_path / "text").write_text("hello")
    with pytest.raises(ValueError, match="truncated or corrupted"):
        checkpoint.load(tmp_path / "text")
    np.savez(tmp_path / "arrays.npz", x=np.zeros(3))
    with pytest.raises(ValueError, match="is not an edmd2d checkpoint"):
        checkpoint.load(tmp_path / "arrays.npz")
    with zipfile.ZipFile(tmp_path / "other.zip", "w") as z:
        z.writestr("header.json", json.dumps({"format": "something else"}))
    with pytest.raises(ValueError, match="is not an edmd2d checkpoint"):
        checkpoint.load(tmp_path / "other.zip")


def _with_header(tmp_path, name, edit):
    """A checkpoint of a small gas whose header ``edit`` changed, written to ``name``."""
    path = tmp_path / "run.edmd2d"
    checkpoint.save(ed.make_gas(50, 0.3, seed=seed_of(1)), path)
    with zipfile.ZipFile(path) as z:
        members = {member: z.read(member) for member in z.namelist()}
    header = json.loads(members["header.json"])
    edit(header)
    members["header.json"] = json.dumps(header).encode()
    with zipfile.ZipFile(tmp_path / name, "w") as z:
        for member, data in members.items():
            z.writestr(member, data)
    return tmp_path / name


def test_another_format_version_is_refused(tmp_path):
    future = _with_header(tmp_path, "future",
                          lambda header: header.update(version=checkpoint.VERSION + 1))
    with pytest.raises(ValueError, match=f"format version {checkpoint.VERSION + 1}"):
        checkpoint.load(future)


def test_a_checkpoint_of_format_version_1_is_refused(tmp_path):
    # Version 1 held the attributes of the Simulation itself; version 2 the engine's
    # state: the old files are refused with a message that names their version.
    def to_version_1(header):
        header["version"] = 1
        header["state"] = {"_" + key: value for key, value in header["state"].items()}

    old = _with_header(tmp_path, "old", to_version_1)
    assert checkpoint.VERSION == 2
    with pytest.raises(ValueError, match="format version 1 .*reads version 2"):
        checkpoint.load(old)


def test_parts_of_two_checkpoints_do_not_make_one(tmp_path):
    checkpoint.save(ed.make_gas(50, 0.3, seed=seed_of(1)), tmp_path / "a")
    checkpoint.save(ed.make_gas(80, 0.3, seed=seed_of(1)), tmp_path / "b")
    with zipfile.ZipFile(tmp_path / "a") as za, zipfile.ZipFile(tmp_path / "b") as zb:
        members = {name: za.read(name) for name in za.namelist()}
        members["E.npy"] = zb.read("E.npy")
    with zipfile.ZipFile(tmp_path / "mixed", "w") as z:
        for name, data in members.items():
            z.writestr(name, data)
    with pytest.raises(ValueError, match="inconsistent state"):
        checkpoint.load(tmp_path / "mixed")


def test_save_refuses_what_is_not_a_simulation(tmp_path):
    with pytest.raises(TypeError, match="needs an edmd2d.Simulation"):
        checkpoint.save("gas", tmp_path / "x")
    assert not os.listdir(tmp_path)


def test_segments_and_their_tallies_restart_exactly(tmp_path):
    box = ed.Box(12.0, 12.0, periodic=False)
    walls = ed.Wall.polygon([(1.0, 1.0), (11.0, 1.5), (10.0, 11.0), (1.5, 10.0)])
    rng = np.random.default_rng(seed_of(2))
    xs, ys = np.meshgrid(np.linspace(3.0, 9.0, 6), np.linspace(3.0, 9.0, 6))
    pos = np.c_[xs.ravel(), ys.ravel()]
    sim = ed.Simulation(pos, rng.normal(size=(36, 2)), 0.4, box=box, walls=walls,
                        wall_temperatures={2: 1.5}, seed=seed_of(4))
    part = ed.checkpoint.load(_saved(sim.advance(until=5.0), tmp_path))
    whole = sim.advance(until=15.0)
    part.advance(until=15.0)
    assert state_digest(part) == state_digest(whole)
    assert part._accumulators()["segment_contacts"].tolist() == (
        whole._accumulators()["segment_contacts"].tolist())


def _saved(sim, tmp_path):
    path = tmp_path / "saved"
    checkpoint.save(sim, path)
    return path


def test_files_are_written_with_the_mode_the_umask_gives(tmp_path):
    """Checkpoints (through a temporary file renamed over the target) and GSD files
    (which the gsd library creates with mode 0640) get 0666 less the umask, as a file
    opened by the user's own program would."""
    sim = ed.make_gas(20, 0.3, seed=seed_of(1))
    old = os.umask(0o027)
    try:
        for mask, mode in ((0o022, 0o644), (0o077, 0o600), (0o002, 0o664)):
            os.umask(mask)
            ed.checkpoint.save(sim, tmp_path / "state.edmd2d")
            assert stat.S_IMODE(os.stat(tmp_path / "state.edmd2d").st_mode) == mode
            if importlib.util.find_spec("gsd") is not None:
                from edmd2d.io import gsd

                gsd.record(sim, tmp_path / "run.gsd", [sim.time])
                assert stat.S_IMODE(os.stat(tmp_path / "run.gsd").st_mode) == mode
    finally:
        os.umask(old)
    assert list(tmp_path.glob(".*")) == []  # (no temporary file left behind)


def test_a_state_saved_before_gravity_could_change_loads_with_no_work_of_gravity():
    from edmd2d._engine import layout
    from edmd2d._state import EngineState

    sim = ed.make_gas(30, 0.2, periodic=False, gravity=(0.0, -1.0), seed=2).advance(until=1.0)
    state = sim._state.__getstate__()
    state["acc"] = state["acc"][:layout.A_GRAVITY]  # (the accumulators of older files)
    loaded = EngineState.__new__(EngineState)
    loaded.__setstate__(state)
    assert len(loaded.acc) == layout.N_ACC and loaded.acc[layout.A_GRAVITY] == 0.0
    assert np.array_equal(loaded.acc[:layout.A_GRAVITY], sim._state.acc[:layout.A_GRAVITY])
