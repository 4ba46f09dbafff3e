"""The command line: run, resume, info, configuration errors and help texts."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d import config
from edmd2d.cli import main

ROOT = pathlib.Path(__file__).resolve().parents[1]

CONFIG = """\
# a small gas
[gas]
n = 200
packing_fraction = 0.3
temperature = 1.0

[model]
seed = 4

[run]
equilibrate = 2.0
duration = 4.0
blocks = 4

[output]
gsd_every = 1.0
checkpoint_every = 2.5
"""


def write(tmp_path, text=CONFIG, name="gas.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def run(args):
    """``main`` on arguments that may be paths."""
    return main([str(a) for a in args])


def state(path):
    sim = ed.checkpoint.load(path)
    return sim.positions, sim.velocities, sim.counts, sim.time


def test_run_writes_the_table_and_the_files_and_measures_as_measure(tmp_path, capsys):
    pytest.importorskip("gsd")
    out = tmp_path / "out"
    assert run(["run", write(tmp_path), "--output", out, "--no-progress"]) == 0
    printed = capsys.readouterr()
    assert printed.err == ""
    rows = [line for line in printed.out.splitlines() if line.strip().startswith(("3 ", "4 ",
                                                                                  "5 ", "6 "))]
    assert len(rows) == 4 and "+-" in rows[-1]
    assert {p.name for p in out.iterdir()} == {"config.toml", "trajectory.gsd",
                                               "checkpoint.edmd2d", "results.json"}
    results = json.loads((out / "results.json").read_text())
    assert results["status"] == "complete" and results["seed"] == 4
    assert results["edmd2d"] == ed.__version__ and results["config"]["gas"]["n"] == 200
    assert len(results["table"]) == 4

    # The same gas, equilibrated, then measured in Python: the same numbers exactly.
    sim = ed.make_gas(200, 0.3, temperature=1.0, seed=4).advance(until=2.0)
    m = sim.measure(4.0, blocks=4)
    got = results["measurement"]
    assert got["compressibility_factor"] == {"value": m.compressibility_factor,
                                             "error": m.compressibility_factor_error}
    assert got["pressure"]["value"] == m.pressure and got["collisions"] == m.collisions
    assert got["wall_pressure"] == {"value": None, "error": None}  # (nan: periodic)
    assert np.array_equal(state(out / "checkpoint.edmd2d")[0], sim.positions)
    assert (out / "config.toml").read_text() == CONFIG


def test_resume_continues_bit_for_bit(tmp_path, capsys):
    pytest.importorskip("gsd")
    import gsd.hoomd

    config_path = write(tmp_path)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert run(["run", config_path, "-o", whole, "--no-progress"]) == 0
    assert run(["run", config_path, "-o", parts, "--no-progress", "--until", "3.7"]) == 0
    assert "resume" in capsys.readouterr().out
    assert json.loads((parts / "results.json").read_text())["status"] == "stopped"
    assert state(parts / "checkpoint.edmd2d")[3] == 3.7
    assert run(["resume", parts / "checkpoint.edmd2d", "--no-progress"]) == 0
    assert "(before the checkpoint)" in capsys.readouterr().out

    a, b = state(whole / "checkpoint.edmd2d"), state(parts / "checkpoint.edmd2d")
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
    assert a[2] == b[2] and a[3] == b[3] == 6.0
    ra = json.loads((whole / "results.json").read_text())
    rb = json.loads((parts / "results.json").read_text())
    assert ra["measurement"] == rb["measurement"]
    assert [r["compressibility_factor"] for r in ra["table"]] == \
        [r["compressibility_factor"] for r in rb["table"]]
    with gsd.hoomd.open(str(whole / "trajectory.gsd")) as ta, \
            gsd.hoomd.open(str(parts / "trajectory.gsd")) as tb:
        assert [float(f.log["edmd2d/time"][0]) for f in tb] == [0, 1, 2, 3, 4, 5, 6]
        for fa, fb in zip(ta, tb):
            assert np.array_equal(fa.particles.position, fb.particles.position)

    # A complete run has nothing to do; --until takes it on, in more blocks alike.
    assert run(["resume", whole / "checkpoint.edmd2d", "--no-progress"]) == 0
    assert "complete" in capsys.readouterr().out
    assert run(["resume", whole / "checkpoint.edmd2d", "--until", "8", "--no-progress"]) == 0
    longer = json.loads((whole / "results.json").read_text())["measurement"]
    sim = ed.make_gas(200, 0.3, seed=4).advance(until=2.0)
    window = ed.operations.Measure(ed.operations.Blocks(4.0, 4, count=6))
    sim.run(until=8.0, operations=[window])
    assert longer["blocks"] == 6
    assert longer["pressure"]["value"] == window.result().pressure
    # The window reported is the measurement to the run's new end.
    assert json.loads((whole / "results.json").read_text())["window"] == {
        "start": 2.0, "duration": 6.0, "blocks": 6, "blocks_measured": 6}
    run(["info", whole / "checkpoint.edmd2d"])
    assert "6 of 6 blocks of t=2..8" in capsys.readouterr().out


@pytest.mark.parametrize("model", ["", "[model]\nrestitution = 1.0\n",
                                   "[model.wall_temperatures]\nbottom = 2.0\n"])
def test_a_drawn_seed_is_written_into_the_copied_configuration(tmp_path, model):
    text = CONFIG.replace("[model]\nseed = 4\n", model)
    if "wall_temperatures" in model:
        text = text.replace("[gas]\n", "[gas]\nperiodic = false\n")
    assert run(["run", write(tmp_path, text), "-o", tmp_path / "a", "--no-progress"]) == 0
    first = json.loads((tmp_path / "a" / "results.json").read_text())
    copied = (tmp_path / "a" / "config.toml").read_text()
    assert f"seed = {first['seed']}" in copied
    # The copy runs the same system again.
    assert run(["run", tmp_path / "a" / "config.toml", "-o", tmp_path / "b",
                "--no-progress"]) == 0
    second = json.loads((tmp_path / "b" / "results.json").read_text())
    assert second["seed"] == first["seed"]
    assert second["measurement"] == first["measurement"]


def test_resume_until_before_the_end_stops_there(tmp_path, capsys):
    config_path = write(tmp_path)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert run(["run", config_path, "-o", whole, "--no-progress"]) == 0
    assert run(["run", config_path, "-o", parts, "--no-progress", "--until", "2.5"]) == 0
    # An earlier --until than the run's end stops there: the run is not complete, and
    # a plain resume goes on to the end, to the numbers of the run that never stopped.
    assert run(["resume", parts / "checkpoint.edmd2d", "--until", "4.5",
                "--no-progress"]) == 0
    stopped = json.loads((parts / "results.json").read_text())
    assert stopped["status"] == "stopped" and stopped["end"] == 6.0
    assert stopped["window"]["blocks_measured"] == 2
    capsys.readouterr()
    assert run(["resume", parts / "checkpoint.edmd2d", "--no-progress"]) == 0
    assert "complete" not in capsys.readouterr().err
    ra = json.loads((whole / "results.json").read_text())
    rb = json.loads((parts / "results.json").read_text())
    assert rb["status"] == "complete" and ra["measurement"] == rb["measurement"]
    # A configuration given where a checkpoint is expected says what to do instead.
    assert run(["resume", config_path]) == 2
    assert "is a configuration, not a checkpoint" in capsys.readouterr().err


def test_info_describes_gsd_files_and_checkpoints(tmp_path, capsys):
    pytest.importorskip("gsd")
    out = tmp_path / "out"
    assert run(["run", write(tmp_path), "-o", out, "--no-progress"]) == 0
    capsys.readouterr()
    assert run(["info", out / "checkpoint.edmd2d"]) == 0
    text = capsys.readouterr().out
    for expected in ("edmd2d checkpoint", "time      6", "disks     200", "periodic",
                     "0: 200 (radius 0.5, mass 1)", "seed 4", "4 of 4 blocks"):
        assert expected in text
    assert run(["info", out / "trajectory.gsd"]) == 0
    text = capsys.readouterr().out
    for expected in ("GSD file", "frames      7", "time        0 .. 6", "disks       200",
                     "A: 200", "walls       0 segments"):
        assert expected in text
    assert run(["info", out / "results.json"]) == 2
    assert "neither a GSD file nor an edmd2d checkpoint" in capsys.readouterr().err
    # A checkpoint cut short is called damaged, not something else.
    cut = tmp_path / "cut.edmd2d"
    cut.write_bytes((out / "checkpoint.edmd2d").read_bytes()[:2000])
    assert run(["info", cut]) == 2
    assert "truncated or corrupted" in capsys.readouterr().err
    # A new run into the directory without a trajectory leaves none of the old one.
    assert run(["run", write(tmp_path, CONFIG.replace("gsd_every = 1.0\n", "")), "-o", out,
                "--no-progress"]) == 0
    assert not (out / "trajectory.gsd").exists()
    plain = tmp_path / "plain.ckpt"
    ed.checkpoint.save(ed.make_gas(10, 0.2, seed=seed_of(1)), plain)
    assert run(["resume", plain]) == 2
    assert "not written by 'edmd2d run'" in capsys.readouterr().err


BAD = [
    # (replace, by, the key named, the line's text)
    ("packing_fraction = 0.3", "packing_fracton = 0.3", "gas.packing_fracton",
     "packing_fracton"),
    ("n = 200", 'n = "200"', "gas.n", "n = "),
    ("duration = 4.0", "duration = -4.0", "run.duration", "duration"),
    ("[output]", "[outputs]", "outputs", "[outputs]"),
    ("blocks = 4", "blocks = 4.5", "run.blocks", "blocks"),
    ("temperature = 1.0", "temperature = 0.0", "gas.temperature", "temperature"),
    ("seed = 4", "seed = 4\nthermostat = [0.0, 1.0]", "model.thermostat", "thermostat"),
    ("packing_fraction = 0.3", "packing_fraction = 0.95", "gas.packing_fraction",
     "packing_fraction"),
    ("seed = 4", "seed = 4\n[model.wall_temperatures]\nbotom = 2.0",
     "model.wall_temperatures.botom", "botom"),
]


@pytest.mark.parametrize("old, new, key, where", BAD)
def test_a_bad_configuration_names_the_key_and_its_line(tmp_path, capsys, old, new, key,
                                                        where):
    text = CONFIG.replace(old, new, 1)
    line = next(k for k, s in enumerate(text.splitlines(), 1) if s.startswith(where))
    path = write(tmp_path, text)
    assert run(["run", path, "-o", tmp_path / "out", "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert f"{path}, line {line}: {key}:" in err
    assert "Traceback" not in err and err.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_configuration_messages():
    with pytest.raises(config.ConfigError, match="did you mean 'packing_fraction'"):
        config.loads(CONFIG.replace("packing_fraction", "packing_fractoin"))
    with pytest.raises(config.ConfigError, match=r"<config>: gas: the table \[gas\] is required"):
        config.loads("# nothing\n[run]\nduration = 1.0\n")
    with pytest.raises(config.ConfigError, match="line 10: run.duration: is required"):
        config.loads(CONFIG.replace("duration = 4.0\n", ""))
    with pytest.raises(config.ConfigError, match="line 3: not valid TOML"):
        config.loads(CONFIG.replace("n = 200", "n = = 200"))
    mixture = CONFIG.replace("temperature = 1.0\n", """temperature = 1.0
[[gas.species]]
radius = 0.5
count = 120
[[gas.species]]
radius = 0.7
mass = 2
cont = 80
""")
    with pytest.raises(config.ConfigError, match=r"line 12: gas.species\[1\].cont: unknown"):
        config.loads(mixture)
    with pytest.raises(config.ConfigError, match="line 3: gas.n: is 200, but the species"):
        config.loads(mixture.replace("cont = 80", "count = 70"))


def test_a_configuration_builds_the_gas_of_make_gas(tmp_path):
    sim, removed = config.build(config.loads(CONFIG.replace("[model]", """[model]
thermostat = [1.5, 0.2]""")), seed=seed_of(4))
    gas = ed.make_gas(200, 0.3, seed=seed_of(4), thermostat=(1.5, 0.2))
    assert removed == 0
    assert np.array_equal(sim.positions, gas.positions)
    assert np.array_equal(sim.velocities, gas.velocities)
    # (the thermostat's random numbers go on from the same state)
    assert sim._model.rng.bit_generator.state == gas._model.rng.bit_generator.state


def test_a_mixture_with_walls(tmp_path):
    text = CONFIG.replace("temperature = 1.0\n", """temperature = 1.0
periodic = [true, false]
[[gas.species]]
radius = 0.5
fraction = 0.75
[[gas.species]]
radius = 0.5
mass = 3.0
fraction = 0.25
[[walls]]
start = [3.0, 0.0]
end = [3.0, 6.0]
""").replace("[model]", "[model]\nrestitution = [[1.0, 0.9], [0.9, 0.8]]\n"
                        "wall_temperatures = {bottom = 2.0}")
    sim, removed = config.build(config.loads(text), seed=seed_of(2))
    assert removed > 0 and len(sim) == 200 - removed and len(sim.walls) == 1
    heavy = sim.species == 1
    assert np.array_equal(sim.masses, np.where(heavy, 3.0, 1.0))
    assert 0 < heavy.sum() <= 50 and sim.wall_temperatures == {"bottom": 2.0}
    assert sim.restitution.tolist() == [[1.0, 0.9], [0.9, 0.8]]
    # Velocities drawn for each disk's mass: the heavy ones slower.
    speed2 = (sim.velocities ** 2).sum(axis=1)
    assert speed2[heavy].mean() < speed2[~heavy].mean()


def test_walls_leave_out_the_disks_make_gas_leaves_out():
    # One rule for both: a wall across the box and one 0.05 from the periodic edge
    # x = 0, which crosses the disks near x = width through their images.
    text = CONFIG + """
[[walls]]
start = [5.0, 0.0]
end = [5.0, 20.0]
[[walls]]
start = [0.05, 2.0]
end = [0.05, 20.0]
"""
    sim, removed = config.build(config.loads(text), seed=seed_of(3))
    walls = [ed.Wall((5.0, 0.0), (5.0, 20.0)), ed.Wall((0.05, 2.0), (0.05, 20.0))]
    with pytest.warns(UserWarning, match=f"crossed {removed} of the 200 lattice disks"):
        gas = ed.make_gas(200, 0.3, seed=seed_of(3), walls=walls)
    assert removed > 0 and len(sim) == len(gas) == 200 - removed
    np.testing.assert_array_equal(sim.positions, gas.positions)
    assert sim.walls == gas.walls
    free = ed.make_gas(200, 0.3, seed=seed_of(3))
    kept = {tuple(p) for p in sim.positions.tolist()}
    x, y = free.positions.T
    across = free.positions[(x > free.box.width - 0.5) & (y > 2.0) & (y < 20.0)]
    assert len(across) and not any(tuple(p) in kept for p in across.tolist())


GATE = CONFIG.replace("temperature = 1.0\n", """temperature = 1.0
periodic = [true, false]
""").replace("[model]\n", """[model]
gravity = [0.0, -1.0]
restitution = 0.9
""").replace("[output]\ngsd_every = 1.0\ncheckpoint_every = 2.5\n", "") + """
[[walls]]
polygon = [[1.0, 1.0], [3.0, 1.0], [2.0, 3.0]]
open = true
[[walls]]
start = [0.0, 8.0]
end = [20.0, 8.0]
opens_at = 3.0
"""


def test_walls_that_start_open_or_open_during_the_run(tmp_path):
    """A triangle that starts open (its three sides), and a segment across the box that
    opens at t = 3: closed before, open after, also across a resume."""
    sim, _ = config.build(config.loads(GATE), seed=seed_of(5))
    assert sim.open_walls.tolist() == [True, True, True, False]
    out = tmp_path / "out"
    assert run(["run", write(tmp_path, GATE), "-o", out, "--until", "2.5",
                "--no-progress"]) == 0
    before = ed.checkpoint.load(out / "checkpoint.edmd2d")
    assert before.time == 2.5 and before.open_walls.tolist() == [True, True, True, False]
    assert run(["resume", out / "checkpoint.edmd2d", "--no-progress"]) == 0
    after = ed.checkpoint.load(out / "checkpoint.edmd2d")
    assert after.time == 6.0 and after.open_walls.tolist() == [True, True, True, True]


@pytest.mark.parametrize("wall, word", [
    ("start = [0.0, 8.0]\nend = [20.0, 8.0]\nopen = true\nopens_at = 3.0",
     r"walls\[0\].opens_at: a wall that starts open"),
    ("start = [0.0, 8.0]\nend = [20.0, 8.0]\nopens_at = -1.0",
     r"walls\[0\].opens_at: must be >= 0"),
    ("start = [0.0, 8.0]\nend = [20.0, 8.0]\nopen = 1", r"walls\[0\].open"),
])
def test_bad_wall_openings_are_refused_by_name(wall, word):
    with pytest.raises(config.ConfigError, match=word):
        config.loads(CONFIG + "\n[[walls]]\n" + wall + "\n")


def test_the_progress_bar_is_shown_unless_asked_not_to(tmp_path, capsys):
    text = CONFIG.replace("[output]\ngsd_every = 1.0\ncheckpoint_every = 2.5\n", "")
    assert run(["run", write(tmp_path, text), "-o", tmp_path / "out"]) == 0
    err = capsys.readouterr().err
    assert "edmd2d" in err and "100%" in err and "coll/s" in err


@pytest.mark.parametrize("command, words", [
    ([], ["run", "resume", "info"]),
    (["run"], ["CONFIG.toml", "--output", "--no-progress", "packing_fraction", "[output]"]),
    (["resume"], ["CHECKPOINT", "--until", "bit for bit"]),
    (["info"], ["GSD", "checkpoint"]),
])
def test_help_texts(capsys, command, words):
    assert main(command + ["--help"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("usage: edmd2d")
    for word in words:
        assert word in text


def test_bad_command_lines_exit_with_2(tmp_path, capsys):
    assert main([]) == 2
    assert main(["run"]) == 2
    assert "CONFIG.toml" in capsys.readouterr().err
    assert main(["run", str(tmp_path / "missing.toml")]) == 2
    assert "missing.toml: no such file" in capsys.readouterr().err
    assert main(["info", str(tmp_path)]) == 2
    assert "directory" in capsys.readouterr().err


def test_the_installed_command_runs(tmp_path):
    pytest.importorskip("gsd")
    env = dict(os.environ)
    package = pathlib.Path(ed.__file__).resolve().parents[1]
    env["PYTHONPATH"] = os.pathsep.join([str(package), env.get("PYTHONPATH", "")])
    text = CONFIG.replace("duration = 4.0", "duration = 1.0").replace("blocks = 4", "blocks = 2")
    done = subprocess.run(
        [sys.executable, "-m", "edmd2d.cli", "run", str(write(tmp_path, text)), "-o",
         str(tmp_path / "out"), "--no-progress"],
        env=env, check=False, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "done at t=3" in done.stdout
    bad = subprocess.run([sys.executable, "-m", "edmd2d", "info", str(tmp_path / "nothing")],
                         env=env, check=False, capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and bad.stderr.startswith("edmd2d: error:")
    assert "Traceback" not in bad.stderr


def test_the_example_configuration_is_valid():
    cfg = config.load(ROOT / "examples" / "gas.toml")
    assert cfg.data["run"]["duration"] > 0 and cfg.data["model"]["seed"] is not None


def test_an_interrupted_run_leaves_a_checkpoint_to_resume(tmp_path, capsys, monkeypatch):
    from edmd2d import cli

    config_path = write(tmp_path, CONFIG.replace("gsd_every = 1.0\n", ""))
    assert run(["run", config_path, "-o", tmp_path / "whole", "--no-progress"]) == 0
    row = cli._Runner._row

    def interrupted(self, sim, measure):
        row(self, sim, measure)
        if measure.blocks == 2:
            raise KeyboardInterrupt

    monkeypatch.setattr(cli._Runner, "_row", interrupted)
    parts = tmp_path / "parts"
    assert run(["run", config_path, "-o", parts, "--no-progress"]) == 130
    assert "interrupted at t=4; continue with: edmd2d resume" in capsys.readouterr().err
    assert json.loads((parts / "results.json").read_text())["status"] == "interrupted"
    monkeypatch.setattr(cli._Runner, "_row", row)
    assert run(["resume", parts / "checkpoint.edmd2d", "--no-progress"]) == 0
    a, b = state(tmp_path / "whole" / "checkpoint.edmd2d"), state(parts / "checkpoint.edmd2d")
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]) and a[2] == b[2]
    assert (json.loads((tmp_path / "whole" / "results.json").read_text())["measurement"]
            == json.loads((parts / "results.json").read_text())["measurement"])


COLLAPSING = """
[gas]
n = 100
packing_fraction = 0.15
periodic = false
aspect = 0.5
[model]
restitution = 0.9
wall_restitution = 0.9
gravity = [0.0, -1.0]
resting = false
seed = 1
[run]
equilibrate = 5.0
duration = 100.0
blocks = 10
[output]
gsd_every = 10.0
"""


def test_a_failed_run_keeps_what_it_measured_and_resume_says_why(tmp_path, capsys):
    """Inelastic disks poured under gravity, not allowed to come to rest, settle until
    two lie on each other (an inelastic collapse no tc ends): the run exits 1, but
    results.json holds the blocks measured before, marked failed with the error, and
    the checkpoint the state before the failure; resuming it says why it stopped and
    what to change, and runs nothing."""
    path = write(tmp_path, COLLAPSING)
    assert main(["run", str(path), "--no-progress"]) == 1
    err = capsys.readouterr().err
    assert "the simulation failed: inelastic collapse" in err
    out = tmp_path / "gas-run"
    results = json.loads((out / "results.json").read_text())
    assert results["status"] == "failed" and "inelastic collapse" in results["error"]
    assert 5.0 < results["time"] < 105.0
    assert results["window"]["blocks_measured"] >= 1 and results["measurement"] is not None
    state = ed.checkpoint.load(out / "checkpoint.edmd2d")
    assert state.time == results["time"]
    assert main(["resume", str(out / "checkpoint.edmd2d"), "--no-progress"]) == 1
    err = capsys.readouterr().err
    assert "this run failed at t=" in err and "[model] tc" in err
    assert ed.checkpoint.load(out / "checkpoint.edmd2d").time == state.time  # (untouched)


SHAKEN = CONFIG.replace("temperature = 1.0\n", """temperature = 1.0
periodic = [true, false]
""").replace("[model]\n", """[model]
gravity = [0.0, -1.0]
""") + """
[[walls]]
start = [0.0, 1.0]
end = [20.0, 1.0]
amplitude = 0.4
omega = 6.0
[[walls]]
start = [0.0, 19.0]
end = [20.0, 19.0]
velocity = [0.0, -0.5]
distance = 2.0
begin = 1.0
"""


def test_walls_that_move_run_and_resume_bit_for_bit(tmp_path):
    """A shaken floor and a piston from a configuration file; a run stopped half way
    and resumed from its checkpoint ends exactly where the whole run ends."""
    sim, _ = config.build(config.loads(SHAKEN), seed=seed_of(6))
    motions = sim.families["moving_walls"].motions()
    assert motions[0] == ed.Oscillation(0.4, 6.0)
    assert motions[1] == ed.Translation((0.0, -0.5), 2.0, 1.0)
    whole, half = tmp_path / "whole", tmp_path / "half"
    path = write(tmp_path, SHAKEN)
    assert run(["run", path, "-o", whole, "--no-progress"]) == 0
    assert run(["run", path, "-o", half, "--until", "2.5", "--no-progress"]) == 0
    assert run(["resume", half / "checkpoint.edmd2d", "--no-progress"]) == 0
    a = ed.checkpoint.load(whole / "checkpoint.edmd2d")
    b = ed.checkpoint.load(half / "checkpoint.edmd2d")
    assert a.time == b.time
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.wall_work(), b.wall_work())
    assert a.wall_work()[0] != 0.0 and a.wall_positions[1, 0, 1] == 17.0


@pytest.mark.parametrize("wall, word", [
    ("velocity = [0.0, 1.0]", r"walls\[0\].velocity: velocity needs distance too"),
    ("amplitude = 0.5\nomega = 1.0\ndistance = 2.0",
     r"walls\[0\].amplitude: a wall moves by velocity and distance"),
    ("amplitude = -0.5\nomega = 1.0", r"walls\[0\].amplitude: must be > 0"),
])
def test_bad_wall_motions_are_refused_by_name(wall, word):
    with pytest.raises(config.ConfigError, match=word):
        config.loads(CONFIG + "\n[[walls]]\nstart = [0.0, 8.0]\nend = [20.0, 8.0]\n" + wall
                     + "\n")
