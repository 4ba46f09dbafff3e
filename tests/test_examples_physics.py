"""The physics examples run headless and write their figures (shrunk to seconds)."""

from __future__ import annotations

import importlib.util
import math
import pathlib

import matplotlib
import numpy as np
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
    ("jammed_packing", {"N": 200}),
    ("compression_eos", {"N": 100, "RATE": 1e-2}),
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


def test_heated_bed_settles_denser_and_cooler_upwards(tmp_path, capsys):
    """A bed of 200 disks (e = 0.9) on a floor at kT = 4, 4 close-packed rows deep,
    run to t = 350: after t = 50 its granular temperature is steady, the floor's heat
    balances the dissipation, and the bed thins out and cools upwards.

    The steady temperature fluctuates by ~8 % (rms) at this size; the means of the two
    halves of the window (150 time units each, ~50 correlation times) agree to 4 of
    their standard errors (~1 % each, from the scatter of 30-unit block means).  The
    bed's energy (~1200) fluctuates by ~35 while the floor supplies ~4e4 over the
    window, so heat and dissipation agree to 1 %.  The packing fraction falls from ~0.5
    at the floor with every bin of height up to where it is 0.01, and the layer at the
    floor (just heated, T ~ 2.5) is more than 1.5 times hotter than the coolest layer
    above it (T ~ 1.25)."""
    module = load("heated_bed")
    module.N, module.DURATION, module.ANIMATE = 200, 350.0, 3.0
    out = tmp_path / "heated_bed.gif"
    result = module.main(out)
    assert out.stat().st_size > 10_000 and out.with_suffix(".png").stat().st_size > 10_000
    (t1, e1), (t2, e2) = result["first"], result["second"]
    assert abs(t2 - t1) < 4.0 * math.hypot(e1, e2)
    assert max(e1, e2) < 0.25 * result["fluctuation"]  # (a sharp comparison)
    assert t1 < module.FLOOR_KT
    assert result["heat"] == pytest.approx(result["dissipation"], rel=0.01)
    packing, temperature = result["packing"], result["temperature"]
    assert packing[0] > 0.4
    bed = packing > 0.01
    assert np.all(np.diff(packing[bed]) < 0)
    assert temperature[0] > 1.5 * np.nanmin(temperature)
    text = capsys.readouterr().out
    assert "granular temperature" in text and "wrote" in text


def test_sedimentation_follows_the_barometric_law_with_its_virial_correction(tmp_path,
                                                                              capsys):
    """1000 disks, isolated after settling under a thermostat, over 6000 time units.

    The fitted decay length is within 3 % of kT/mg: at the floor density 0.02 the
    second virial coefficient lengthens it by ~1.8 %, and the fit follows the virial
    profile to 4 block standard errors (0.2-0.5 %, from 8 blocks of 750 time units,
    far longer than the ~100 over which heights decorrelate).  The mean height matches
    L (1 + B2 n0 / 2) to the same 4 errors plus 0.2 % for the next order in B2 n0."""
    module = load("sedimentation")
    module.N, module.DURATION = 1000, 8000.0
    out = tmp_path / "sedimentation.png"
    result = module.main(out)
    assert out.stat().st_size > 10_000
    assert result["ratio"] == pytest.approx(1.0, abs=0.03)
    assert abs(result["ratio"] - result["virial_ratio"]) < 4.0 * result["ratio_err"]
    assert abs(result["mean_height"] - result["expected_mean"]) < (
        4.0 * result["mean_err"] + 0.002)
    text = capsys.readouterr().out
    assert "decay length" in text and "wrote" in text


def test_melting_example_runs_a_small_sweep_and_resumes(tmp_path, capsys):
    """The melting example end to end on a tiny system (serial sweep): its table, its
    figure, and a second call that reuses every finished point."""
    module = load("hard_disk_melting")
    module.NS, module.ETAS = (256,), (0.70, 0.712)
    module.EQUILIBRATE, module.MEASURE, module.BLOCKS = 400.0, 1000.0, 5
    out = tmp_path / "melt.png"
    rows = module.main(out, tmp_path / "sweep", scheduler="serial")
    assert out.stat().st_size > 10_000
    assert [r["packing_fraction"] for r in rows] == [0.70, 0.712]
    for r in rows:
        assert r["pressure"] == pytest.approx(r["Z"] * 4 * r["packing_fraction"] / math.pi)
        assert 0.0 < r["pressure_error"] < 0.5 and 0.0 <= r["psi6"] <= 1.0
        assert r["collisions_per_disk"] >= 1400
        # the drifts: second half of the measured windows less the first half
        record = module.ed.checkpoint.read_metadata(r["state"])
        for key, drift in (("z", r["drift"]), ("psi6", r["psi6_drift"])):
            measured = np.array(record[key][len(record[key]) - 5:])
            assert drift == pytest.approx(measured[2:].mean() - measured[:2].mean())
    again = module.main(out, tmp_path / "sweep", scheduler="serial")
    assert again == rows  # (read back from the sweep, not run again)
    assert "wrote" in capsys.readouterr().out
    # --plot draws the same rows from the finished sweep without running anything
    drawn = module.plot(tmp_path / "plot.png", [tmp_path / "sweep"])
    assert drawn == rows and (tmp_path / "plot.png").stat().st_size > 10_000
    lines = (tmp_path / "plot.csv").read_text().splitlines()
    assert lines[0].startswith("n,packing_fraction,pressure") and len(lines) == 3
    assert float(lines[1].split(",")[2]) == pytest.approx(rows[0]["pressure"], abs=1e-5)


def test_melting_runs_at_one_point_combine_with_their_scatter():
    """One run stays as it is; runs that agree keep the weighted mean's error; runs
    that disagree by more than their errors widen it by sqrt(chi^2 / dof); the halves
    of each run follow from its mean and drift."""
    module = load("hard_disk_melting")
    scale = 4 * 0.72 / math.pi

    def run(eta, p, err, start="liquid", drift=0.0):
        s = 4 * eta / math.pi
        return {"n": 4096, "packing_fraction": eta, "pressure": p, "pressure_error": err,
                "Z": p / s, "drift": drift, "drift_error": 2 * err / s, "blocks": 10,
                "psi6": 0.5, "start": start, "task": "t"}

    (one, agree, apart), = module.combine([
        run(0.70, 9.1, 0.01), run(0.71, 9.10, 0.01), run(0.71, 9.11, 0.01, "crystal"),
        run(0.72, 9.10, 0.01, drift=0.02 / scale),
        run(0.72, 9.16, 0.01, "crystal", drift=0.02 / scale)]).values()
    assert (one["eta"], one["pressure"], one["error"], one["runs"]) == (0.70, 9.1, 0.01, 1)
    assert agree["pressure"] == pytest.approx(9.105)
    assert agree["error"] == pytest.approx(0.01 / 2 ** 0.5)
    chi2 = 2 * (0.03 / 0.01) ** 2  # both runs 0.03 from the mean, one degree of freedom
    assert apart["pressure"] == pytest.approx(9.13)
    assert apart["error"] == pytest.approx(0.01 / 2 ** 0.5 * chi2 ** 0.5)
    (first, e1), (second, e2) = apart["halves"]
    assert (first, second) == pytest.approx((9.12, 9.14))  # 9.13 -+ 0.02 / 2
    # each half's error is 0.01 sqrt 2, so chi^2 = 2 (0.03 / 0.0141)^2 = 9 scales by 3
    assert (e1, e2) == pytest.approx((0.03, 0.03))
    # 9 windows, 4 then 5: Z = (4 A + 5 B) / 9 with B - A = drift, and eA^2 / eB^2 = 5 / 4
    (odd,), = module.combine([{**run(0.7, 9.1, 0.01, drift=0.09), "blocks": 9}]).values()
    (a, ea), (b, eb) = odd["halves"]
    assert (4 * a + 5 * b) / 9 == pytest.approx(9.1)
    assert b - a == pytest.approx(0.09 * 4 * 0.7 / math.pi)
    assert (ea / eb) ** 2 == pytest.approx(5 / 4)
    assert math.hypot(ea, eb) == pytest.approx(2 * 0.01)


def test_loop_height_is_not_inflated_by_noise():
    """On a loop of known height 0.08 with flat extremes (as at 64^2), measured with
    errors 0.015 per point (each half 0.015 sqrt 2), the highest point less the
    lowest one after it is too large by about 2.4 errors on average; the height from
    split halves is not.  Over 300 noisy curves its mean lies within 4 standard
    errors of that mean (0.006) of the truth while the raw difference lies 0.02 or
    more above it; its error bar is larger than its spread, by less than 35 %."""
    module = load("hard_disk_melting")
    eta = np.round(np.arange(0.694, 0.7201, 0.002), 3)
    true = np.where(eta <= 0.704, 9.18, np.where(eta <= 0.716, 9.10, 9.25))
    true[eta == 0.694] = 9.10

    def points(first, second, error):
        return [{"eta": e, "pressure": (a + b) / 2, "error": error / 2 ** 0.5,
                 "halves": ((a, error), (b, error)), "runs": 1, "psi6": 0.5}
                for e, a, b in zip(eta, first, second)]

    exact = module.loop_height(points(true, true, 1e-9), samples=20)
    assert exact["height"] == pytest.approx(0.08) and exact["raw"] == pytest.approx(0.08)
    assert (exact["eta_max"], exact["eta_min"], exact["bounded"]) == (0.696, 0.706, False)
    rng = np.random.default_rng(7)
    sigma = 0.015 * 2 ** 0.5
    heights, raw, errors = [], [], []
    for _ in range(300):
        a, b = (true + sigma * rng.standard_normal(len(eta)) for _ in range(2))
        loop = module.loop_height(points(a, b, sigma), samples=200,
                                  seed=int(rng.integers(1 << 30)))
        heights.append(loop["height"])
        raw.append(loop["raw"])
        errors.append(loop["error"])
    spread = np.std(heights, ddof=1)
    assert abs(np.mean(heights) - 0.08) < 4 * spread / np.sqrt(300)
    assert np.mean(raw) - 0.08 > 0.02
    assert spread < np.mean(errors) < 1.35 * spread  # conservative (see loop_height)


def test_published_loop_heights_follow_the_curves():
    """The heights drawn from the published curves: they shrink with N, and the 128^2
    curve of Li et al. ends at its lowest point (so its height is a lower bound)."""
    module = load("hard_disk_melting")
    heights = module.published_heights()
    ns = [n for n, *_ in heights]
    assert ns == sorted(ns)
    assert all(a[1] > b[1] for a, b in zip(heights, heights[1:]))
    assert [n for n, _, bounded, _ in heights if bounded] == [128 ** 2]
    assert heights[-1][1] == pytest.approx(9.18800 - 9.18218)  # 1024^2: 0.702 to 0.714
