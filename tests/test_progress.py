"""Progress bars: shown only when asked, and a run with one is the run without."""

from __future__ import annotations

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of


def test_advance_with_a_bar_is_the_same_run(capsys):
    plain = ed.make_gas(2000, 0.4, seed=seed_of(3))
    shown = ed.make_gas(2000, 0.4, seed=seed_of(3))
    plain.advance(until=8.0)
    shown.advance(until=8.0, progress=True)
    assert np.array_equal(plain.positions, shown.positions)
    assert plain.counts == shown.counts
    err = capsys.readouterr().err
    assert "advance" in err and "100%" in err and "coll/s" in err
    plain.advance(collisions=50_000)
    shown.advance(collisions=50_000, progress=True)
    assert np.array_equal(plain.velocities, shown.velocities)
    assert "50.0k/50.0k" in capsys.readouterr().err


def test_no_bar_unless_asked(capsys):
    sim = ed.make_gas(200, 0.4, seed=seed_of(3))
    sim.advance(until=2.0)
    sim.measure(duration=2.0)
    assert capsys.readouterr().err == ""


def test_measure_shows_one_bar_over_its_window(capsys):
    a = ed.make_gas(500, 0.4, seed=seed_of(4)).measure(duration=5.0)
    b = ed.make_gas(500, 0.4, seed=seed_of(4)).measure(duration=5.0, progress=True)
    assert a.pressure == b.pressure
    err = capsys.readouterr().err
    assert err.count("measure") >= 1 and "advance" not in err


def test_a_bad_progress_value_is_refused():
    with pytest.raises(TypeError, match="progress must be True, False or a tqdm bar"):
        ed.make_gas(50, 0.3, seed=seed_of(1)).advance(until=1.0, progress="yes")
