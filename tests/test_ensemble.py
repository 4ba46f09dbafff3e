"""Ensembles of runs (edmd2d.ensemble, ``edmd2d sweep``): seeds, tables, failures,
resuming, refusing another sweep's directory, the same numbers serial and on Dask."""

from __future__ import annotations

import csv
import importlib.util
import json
import pathlib
import sys

import numpy as np
import pytest

from conftest import seed_of
from edmd2d import checkpoint, config, ensemble
from edmd2d import operations as op
from edmd2d.cli import main

ROOT = pathlib.Path(__file__).resolve().parents[1]

needs_dask = pytest.mark.skipif(
    importlib.util.find_spec("distributed") is None,
    reason="dask.distributed is not installed (pip install 'edmd2d[ensemble]'): the "
           "sweeps on a Dask cluster are not tested")

# A small equation-of-state sweep: 4 tasks of 64 disks, well under a second serially.
EOS = {"n": [64], "packing_fraction": [0.2, 0.3], "equilibrate": [1.0], "duration": [2.0],
       "blocks": [4]}


def table(output) -> list[dict]:
    with open(pathlib.Path(output) / ensemble.CSV_FILE, newline="") as f:
        return list(csv.DictReader(f))


def text(output) -> str:
    return (pathlib.Path(output) / ensemble.CSV_FILE).read_text()


def square_task(parameters, seed, workdir):
    """Squares ``x``, draws a number from its seed and counts its calls in workdir;
    ``x = 13`` raises, and the first call with ``stop`` set stops like a Ctrl-C."""
    calls = workdir / "calls"
    count = int(calls.read_text()) + 1 if calls.exists() else 1
    calls.write_text(str(count))
    if parameters["x"] == 13:
        raise RuntimeError("thirteen is unlucky")
    if parameters.get("stop") and count == 1:
        raise KeyboardInterrupt
    return {"square": parameters["x"] ** 2, "draw": float(np.random.default_rng(seed).random()),
            "calls": count}


def test_grid_expands_a_dict_of_lists_as_a_product():
    assert ensemble.grid({"a": [1, 2], "b": ["x", "y"]}) == [
        {"a": 1, "b": "x"}, {"a": 1, "b": "y"}, {"a": 2, "b": "x"}, {"a": 2, "b": "y"}]
    assert ensemble.grid([{"a": np.float64(0.5), "b": (1, 2)}]) == [{"a": 0.5, "b": [1, 2]}]
    with pytest.raises(ValueError, match="empty"):
        ensemble.grid({"a": []})
    with pytest.raises(TypeError, match="list of values"):
        ensemble.grid({"a": 1.0})
    with pytest.raises(TypeError, match="JSON"):
        ensemble.grid([{"a": object()}])


def test_seeds_are_spawned_in_task_order_and_recorded(tmp_path):
    result = ensemble.sweep(square_task, {"x": [1, 2, 3]}, replicas=2, seed=7,
                            output=tmp_path, scheduler="serial")
    children = np.random.SeedSequence(7).spawn(6)
    draws = [float(np.random.default_rng(c).random()) for c in children]
    assert [t["values"]["draw"] for t in result.tasks] == draws
    rows = table(tmp_path)
    assert [r["task"] for r in rows] == ["p000-r00", "p000-r01", "p001-r00", "p001-r01",
                                         "p002-r00", "p002-r01"]
    assert [r["seed_spawn_key"] for r in rows] == ["0", "1", "2", "3", "4", "5"]
    assert {r["seed_entropy"] for r in rows} == {"7"}
    assert [float(r["draw"]) for r in rows] == draws  # (the text reads back exactly)
    again = result.seed("p001-r01")
    assert float(np.random.default_rng(again).random()) == draws[3]
    data = json.loads((tmp_path / ensemble.JSON_FILE).read_text())
    assert data["entropy"] == 7 and data["parameters"] == [{"x": 1}, {"x": 2}, {"x": 3}]
    assert data["versions"]["edmd2d"] and data["total"] == data["finished"] == 6
    assert all((tmp_path / "tasks" / r["task"] / "calls").exists() for r in rows)

    # No seed: one is drawn, recorded, and taken up again when resuming.
    drawn = ensemble.sweep(square_task, {"x": [1]}, output=tmp_path / "drawn",
                           scheduler="serial")
    assert drawn.entropy > 2**64
    assert ensemble.sweep(square_task, {"x": [1]}, output=tmp_path / "drawn",
                          scheduler="serial").tasks == drawn.tasks


def test_a_failing_task_is_reported_and_the_others_finish(tmp_path):
    result = ensemble.sweep(square_task, [{"x": 2}, {"x": 13}, {"x": 4}], seed=seed_of(1),
                            output=tmp_path, scheduler="serial")
    assert not result.complete and [t["task"] for t in result.failed] == ["p001-r00"]
    rows = table(tmp_path)
    assert [r["status"] for r in rows] == ["ok", "failed", "ok"]
    assert rows[1]["x"] == "13" and rows[1]["error_type"] == "RuntimeError"
    assert rows[1]["error"] == "thirteen is unlucky" and rows[1]["square"] == ""
    assert [r["square"] for r in rows] == ["4", "", "16"]
    failed = json.loads((tmp_path / ensemble.JSON_FILE).read_text())["tasks"][1]
    assert failed["parameters"] == {"x": 13}
    assert "Traceback" in failed["error"]["traceback"]
    assert "square_task" in failed["error"]["traceback"]

    # Resumed, the failed task runs again (and fails again); the others are kept.
    again = ensemble.sweep(square_task, [{"x": 2}, {"x": 13}, {"x": 4}], seed=seed_of(1),
                           output=tmp_path, scheduler="serial")
    assert [t["values"]["calls"] for t in again.tasks if t["values"]] == [1, 1]
    assert (tmp_path / "tasks" / "p001-r00" / "calls").read_text() == "2"


def test_an_interrupted_sweep_resumes_without_running_finished_tasks(tmp_path):
    points = [{"x": 1}, {"x": 2, "stop": True}, {"x": 3}]
    with pytest.raises(KeyboardInterrupt):
        ensemble.sweep(square_task, points, seed=seed_of(3), output=tmp_path / "a",
                       scheduler="serial")
    assert [r["task"] for r in table(tmp_path / "a")] == ["p000-r00"]  # (kept on Ctrl-C)
    result = ensemble.sweep(square_task, points, seed=seed_of(3), output=tmp_path / "a",
                            scheduler="serial")
    assert result.complete
    assert [t["values"]["calls"] for t in result.tasks] == [1, 2, 1]
    # The same numbers as a sweep that was not interrupted.
    whole = ensemble.sweep(square_task, [{"x": 1}, {"x": 2, "stop": False}, {"x": 3}],
                           seed=seed_of(3), output=tmp_path / "b", scheduler="serial")
    assert [t["values"]["draw"] for t in result.tasks] == \
           [t["values"]["draw"] for t in whole.tasks]


def test_eos_task_continues_from_its_checkpoint_bit_for_bit(tmp_path, monkeypatch):
    whole = ensemble.sweep(ensemble.eos_task, EOS, replicas=2, seed=seed_of(5),
                           output=tmp_path / "whole", scheduler="serial")
    assert whole.complete
    # A Ctrl-C right after the checkpoint at the end of the second block of the first
    # task ...
    written = []
    save = op.Checkpoint.__call__

    def interrupted(self, sim):
        save(self, sim)
        written.append(sim.time)
        if len(written) == 2:
            raise KeyboardInterrupt

    monkeypatch.setattr(op.Checkpoint, "__call__", interrupted)
    with pytest.raises(KeyboardInterrupt):
        ensemble.sweep(ensemble.eos_task, EOS, replicas=2, seed=seed_of(5),
                       output=tmp_path / "cut", scheduler="serial")
    monkeypatch.setattr(op.Checkpoint, "__call__", save)
    assert table(tmp_path / "cut") == []
    # ... and the task resumes from its checkpoint, to the same table.
    loaded = []
    load = checkpoint.load
    monkeypatch.setattr(checkpoint, "load", lambda path: loaded.append(path) or load(path))
    resumed = ensemble.sweep(ensemble.eos_task, EOS, replicas=2, seed=seed_of(5),
                             output=tmp_path / "cut", scheduler="serial")
    assert [pathlib.Path(p).parent.name for p in loaded] == ["p000-r00"]
    assert resumed.tasks[0]["values"] == whole.tasks[0]["values"]
    assert text(tmp_path / "cut") == text(tmp_path / "whole")
    rows = table(tmp_path / "whole")
    assert list(rows[0])[:8] == ["task", "point", "n", "packing_fraction", "equilibrate",
                                 "duration", "blocks", "replica"]
    for name in ("Z", "pressure", "temperature", "collision_rate"):
        assert float(rows[0][name + "_error"]) >= 0.0
    assert 1.0 < float(rows[0]["Z"]) < float(rows[3]["Z"]) < 3.0
    assert 0.0 <= float(rows[0]["psi6"]) <= 1.0


def test_eos_task_with_a_random_start_a_mixture_and_collisions(tmp_path):
    species = [{"radius": 0.5, "fraction": 0.5}, {"radius": 0.35, "mass": 0.5,
                                                   "fraction": 0.5}]
    values = ensemble.eos_task({"n": 60, "packing_fraction": 0.3, "start": "random",
                                "species": species, "equilibrate_collisions": 5.0,
                                "duration": 1.0, "blocks": 2, "periodic": False,
                                "checkpoint_every": 0.4}, 11, tmp_path)
    assert values["Z"] > 1.0 and values["collisions"] > 0
    meta = checkpoint.read_metadata(tmp_path / "checkpoint.edmd2d")
    assert meta["window_start"] > 0.0 and len(meta["measure"]["edges"]) == 3
    with pytest.raises(ValueError, match="another run"):
        ensemble.eos_task({"n": 60, "packing_fraction": 0.3, "duration": 1.0}, 11, tmp_path)
    with pytest.raises(config.ConfigError, match="packing_fracton"):
        ensemble.eos_task({"n": 60, "packing_fracton": 0.3, "duration": 1.0}, 11,
                          tmp_path / "x")


def test_another_sweeps_directory_is_refused(tmp_path):
    ensemble.sweep(square_task, {"x": [1, 2]}, seed=1, output=tmp_path, scheduler="serial")
    before = text(tmp_path)
    for change, words in [
        ({"parameters": {"x": [1, 3]}}, "parameter set 1 is {'x': 2} there, {'x': 3} here"),
        ({"parameters": {"x": [1]}}, "2 parameter sets, not 1"),
        ({"replicas": 2}, "1 replicas, not 2"),
        ({"seed": 2}, "seed entropy 1"),
        ({"function": ensemble.eos_task}, "of the function"),
    ]:
        kwargs = {"function": square_task, "parameters": {"x": [1, 2]}, "seed": 1, **change}
        with pytest.raises(ValueError, match="holds another sweep") as info:
            ensemble.sweep(kwargs.pop("function"), kwargs.pop("parameters"),
                           output=tmp_path, scheduler="serial", **kwargs)
        assert words in str(info.value)
    assert text(tmp_path) == before
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "results.json").write_text('{"status": "complete"}')
    with pytest.raises(ValueError, match="not written by edmd2d.ensemble.sweep"):
        ensemble.sweep(square_task, {"x": [1]}, output=tmp_path / "run", scheduler="serial")


def test_serial_sweeps_need_no_dask(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # (import distributed fails)
    result = ensemble.sweep(square_task, {"x": [1]}, output=tmp_path, scheduler="serial")
    assert result.complete
    with pytest.raises(ImportError, match=r"edmd2d\[ensemble\]"):
        ensemble.sweep(square_task, {"x": [1]}, output=tmp_path / "dask",
                       scheduler="tcp://nowhere:1")


def test_the_progress_bar_counts_tasks(tmp_path, capsys):
    ensemble.sweep(square_task, {"x": [1, 2, 3]}, output=tmp_path, scheduler="serial",
                   progress=True)
    err = capsys.readouterr().err
    assert "sweep" in err and "3/3" in err and "task" in err
    ensemble.sweep(square_task, {"x": [1, 2, 3]}, output=tmp_path, scheduler="serial")
    assert capsys.readouterr().err == ""


@needs_dask
def test_a_local_cluster_gives_the_table_of_a_serial_sweep(tmp_path):
    serial = ensemble.sweep(ensemble.eos_task, EOS, replicas=2, seed=seed_of(9),
                            output=tmp_path / "serial", scheduler="serial")
    dask = ensemble.sweep(ensemble.eos_task, EOS, replicas=2, seed=seed_of(9),
                          output=tmp_path / "dask", workers=2)
    assert text(tmp_path / "dask") == text(tmp_path / "serial")
    assert [t["values"] for t in dask.tasks] == [t["values"] for t in serial.tasks]
    assert len({t["pid"] for t in dask.tasks} - {t["pid"] for t in serial.tasks}) >= 1
    data = json.loads((tmp_path / "dask" / ensemble.JSON_FILE).read_text())
    assert data["versions"]["distributed"]


@needs_dask
def test_a_cluster_by_address_reports_failures_and_resumes(tmp_path):
    import distributed

    points = {**EOS, "packing_fraction": [0.2, 0.95]}  # (0.95: no lattice holds it)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
        result = ensemble.sweep(ensemble.eos_task, points, seed=seed_of(4), output=tmp_path,
                                scheduler=cluster.scheduler_address)
        rows = table(tmp_path)
        assert [r["status"] for r in rows] == ["ok", "failed"]
        assert rows[1]["packing_fraction"] == "0.95" and rows[1]["error_type"] == "ConfigError"
        assert "cannot be reached" in rows[1]["error"] and "Traceback" in \
            result.failed[0]["error"]["traceback"]
        # A client given is used and left open; the finished task is not run again.
        with distributed.Client(cluster) as client:
            again = ensemble.sweep(ensemble.eos_task, points, seed=seed_of(4), output=tmp_path,
                                   scheduler=client, retry_failed=False)
            assert client.status == "running"
    assert again.tasks == result.tasks
    with pytest.raises(ValueError, match="workers="):
        ensemble.sweep(ensemble.eos_task, points, output=tmp_path, scheduler="serial",
                       workers=2)


# ------------------------------------------------------------------ the command line
def small_example(tmp_path) -> pathlib.Path:
    source = (ROOT / "examples" / "eos_sweep.toml").read_text()
    small = (source.replace("n = 256", "n = 64").replace("duration = 20.0", "duration = 2.0")
             .replace("[0.2, 0.3, 0.4, 0.5]", "[0.2, 0.4]")
             .replace("equilibrate_collisions = 50.0", "equilibrate_collisions = 10.0"))
    assert small.count("\n") == source.count("\n") and small != source
    path = tmp_path / "eos_sweep.toml"
    path.write_text(small)
    return path


def test_the_example_configuration_is_valid():
    cfg = config.load_sweep(ROOT / "examples" / "eos_sweep.toml")
    assert [p["packing_fraction"] for p in cfg.data["sweep"]["parameters"]] == \
           [0.2, 0.3, 0.4, 0.5]
    assert cfg.data["sweep"]["replicas"] == 2 and cfg.data["sweep"]["seed"] is not None


def test_the_command_line_sweeps_the_example_and_resumes(tmp_path, capsys):
    path = small_example(tmp_path)
    out = tmp_path / "out"
    args = ["sweep", str(path), "--scheduler", "serial", "--no-progress", "-o", str(out)]
    assert main(args) == 0
    printed = capsys.readouterr()
    assert "4 of 4 tasks finished, 0 failed" in printed.out and printed.err == ""
    assert "p001-r01" in printed.out and "packing_fraction" in printed.out
    rows = table(out)
    assert [r["packing_fraction"] for r in rows] == ["0.2", "0.2", "0.4", "0.4"]
    assert {r["status"] for r in rows} == {"ok"} and {r["seed_entropy"] for r in rows} == \
           {"20240601"}
    data = json.loads((out / "results.json").read_text())
    assert data["metadata"]["config"] == path.read_text()
    before = text(out)
    assert main(args) == 0 and text(out) == before
    # Another grid into the same directory is refused, with exit code 2.
    path.write_text(path.read_text().replace("[0.2, 0.4]", "[0.2, 0.45]"))
    assert main(args) == 2
    assert "holds another sweep" in capsys.readouterr().err


def test_the_command_line_refuses_a_misspelt_key_with_its_line(tmp_path, capsys):
    path = small_example(tmp_path)
    lines = path.read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("packing_fraction"))
    lines[k] = lines[k].replace("packing_fraction", "packing_fracton")
    path.write_text("\n".join(lines) + "\n")
    assert main(["sweep", str(path), "--scheduler", "serial"]) == 2
    err = capsys.readouterr().err
    assert f"line {k + 1}: sweep.grid.packing_fracton: unknown key (did you mean " \
           "'packing_fraction'?)" in err
    path.write_text("[sweep]\nreplica = 2\n[gas]\nn = 10\npacking_fraction = 0.2\n"
                    "[run]\nduration = 1.0\n")
    assert main(["sweep", str(path), "--scheduler", "serial"]) == 2
    assert "line 2: sweep.replica: unknown key (did you mean 'replicas'?)" in \
        capsys.readouterr().err
    path.write_text("[gas]\nn = 10\npacking_fraction = 0.2\n[run]\nduration = 1.0\n"
                    "[model]\nseed = 1\n")
    assert main(["sweep", str(path), "--scheduler", "serial"]) == 2
    assert "line 6: model: unknown table" in capsys.readouterr().err


def test_sweep_configuration_messages():
    base = "[gas]\nn = 10\n[run]\nduration = 1.0\n"
    cases = [
        ("[sweep.grid]\npacking_fraction = 0.3\n", "line 2: sweep.grid.packing_fraction: "
                                                    "expected a list of values"),
        ("[sweep.grid]\npacking_fraction = [0.3, 1.2]\n", "each value: must be < 1"),
        ("[sweep.grid]\nspecies = [1]\n", "a mixture is given in [[gas.species]]"),
        ("[[sweep.points]]\npacking_fraction = 0.3\nblocks = 0\n",
         "line 3: sweep.points[0].blocks: must be >= 1"),
        ("[sweep]\nreplicas = 0\n", "sweep.replicas: must be >= 1"),
        ("", "gas.packing_fraction: is required"),
    ]
    for extra, words in cases:
        with pytest.raises(config.ConfigError) as info:
            config.loads_sweep(extra + base)
        assert words in str(info.value)
    cfg = config.loads_sweep("[sweep.grid]\npacking_fraction = [0.2, 0.3]\n"
                             "[[sweep.points]]\nblocks = 2\n[[sweep.points]]\nblocks = 4\n"
                             + base)
    assert [(p["blocks"], p["packing_fraction"]) for p in cfg.data["sweep"]["parameters"]] \
        == [(2, 0.2), (2, 0.3), (4, 0.2), (4, 0.3)]


def test_sweep_help(capsys):
    assert main(["sweep", "--help"]) == 0
    out = capsys.readouterr().out
    for word in ("CONFIG.toml", "--scheduler", "--workers", "--no-progress", "[sweep.grid]",
                 "replicas", "equilibrate_collisions", "edmd2d[ensemble]"):
        assert word in out
    assert main(["sweep", "x.toml", "--workers", "0"]) == 2
    assert "must be >= 1" in capsys.readouterr().err


def test_eos_task_refuses_a_checkpoint_of_another_version(tmp_path):
    parameters = {"n": 40, "packing_fraction": 0.2, "duration": 0.5, "blocks": 1}
    ensemble.eos_task(parameters, 3, tmp_path)
    path = tmp_path / "checkpoint.edmd2d"
    meta = checkpoint.read_metadata(path)
    checkpoint.save(checkpoint.load(path), path, metadata={**meta, "version": 1})
    with pytest.raises(ValueError, match="format version 1"):
        ensemble.eos_task(parameters, 3, tmp_path)
