"""The physics examples run headless and write their figures (shrunk to seconds)."""

from __future__ import annotations

import importlib.util
import pathlib

import matplotlib
import pytest

matplotlib.use("Agg")

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name, small", [
    ("equation_of_state", {"N": 200, "ETAS": (0.2, 0.5), "COLLISIONS": 20_000}),
    ("maxwell_boltzmann", {"N": 200}),
    ("rdf_dense_fluid", {"N": 300, "FRAMES": 5}),
])
def test_example_writes_its_figure(name, small, tmp_path, capsys):
    module = load(name)
    for key, value in small.items():
        setattr(module, key, value)
    out = tmp_path / "sub" / f"{name}.png"
    module.main(out)
    assert out.stat().st_size > 10_000
    assert "wrote" in capsys.readouterr().out


def test_eos_table_runs(capsys):
    module = load("eos_table")
    module.table(200, 20_000, etas=(0.3,))
    text = capsys.readouterr().out
    assert "Z measured" in text and "collision rate" in text


def test_granular_cooling_example_writes_its_animation(tmp_path, capsys):
    module = load("granular_cooling")
    module.N, module.DURATION = 400, 20.0
    out = tmp_path / "granular_cooling.gif"
    module.main(out)
    assert out.stat().st_size > 10_000 and out.with_suffix(".png").stat().st_size > 10_000
    text = capsys.readouterr().out
    assert "collisions/disk" in text and "wrote" in text


@pytest.mark.parametrize("script", sorted(p.name for p in EXAMPLES.glob("[!_]*.py")))
def test_every_example_explains_its_command_line(script):
    import subprocess
    import sys

    res = subprocess.run([sys.executable, str(EXAMPLES / script), "--help"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.startswith("usage:")


def test_an_example_runs_smaller_and_shorter_from_the_command_line(tmp_path):
    import subprocess
    import sys

    out = tmp_path / "small.gif"
    res = subprocess.run([sys.executable, str(EXAMPLES / "gas_in_a_box.py"), "--n", "60",
                          "--duration", "6", str(out)], capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stderr
    assert out.stat().st_size > 1000 and "wrote" in res.stdout
    bad = subprocess.run([sys.executable, str(EXAMPLES / "gas_in_a_box.py"), "--n", "0"],
                         capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and "--n must be positive" in bad.stderr
