"""The notice that the engine is being compiled: on standard error, once, only when true.

The processes below compile one small kernel (``grid.build_lists``, about 2 s) rather
than the event loop, so that they stay cheap; the notice follows numba's compile
events, which are the same for every compiled function of edmd2d.
"""

from __future__ import annotations

import logging
import os
import pathlib
import subprocess
import sys

import pytest
from numba.core import event as numba_event

import edmd2d as ed
from edmd2d import _compile_notice
from edmd2d._engine import grid

SCRIPT = """
import numpy as np
import edmd2d
from edmd2d._engine import grid
cell = np.array([0, 1, 0], dtype=np.int64)
head, nxt, prv = (np.empty(k, np.int64) for k in (2, 3, 3))
grid.build_lists(cell, head, nxt, prv)
print("first", head.tolist())
grid.build_lists(cell, head, nxt, prv)
print("second")
"""

pytestmark = pytest.mark.skipif(
    os.environ.get("NUMBA_DISABLE_JIT", "0") not in {"", "0"},
    reason="nothing is compiled with NUMBA_DISABLE_JIT")


def _run(env_extra: dict) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    package = pathlib.Path(ed.__file__).resolve().parents[1]
    env["PYTHONPATH"] = os.pathsep.join([str(package), env.get("PYTHONPATH", "")])
    env.update(env_extra)
    return subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True,
                          text=True, check=True, timeout=300)


def test_a_compile_with_the_cache_off_is_announced_once_on_stderr():
    done = _run({"EDMD2D_NUMBA_CACHE": "0"})
    assert done.stdout == "first [0, 1]\nsecond\n"  # (the script's output only)
    assert done.stderr == _compile_notice.message(False) + "\n"
    assert "EDMD2D_NUMBA_CACHE=0" in done.stderr


def test_a_load_from_the_disk_cache_is_not_announced(tmp_path):
    env = {"EDMD2D_NUMBA_CACHE": "1", "NUMBA_CACHE_DIR": str(tmp_path)}
    fill = _run(env)
    assert fill.stderr == _compile_notice.message(True) + "\n"
    assert any(tmp_path.rglob("*.nbi"))  # (the cache was written there)
    load = _run(env)
    assert load.stdout == "first [0, 1]\nsecond\n"
    assert load.stderr == ""


def _compile_event(dispatcher):
    return numba_event.Event("numba:compile", numba_event.EventStatus.START,
                             data={"dispatcher": dispatcher, "args": (),
                                   "return_type": None})


def test_the_notice_goes_to_the_logger_once_logging_is_configured(caplog, capsys):
    notice = _compile_notice._Notice()
    with caplog.at_level(logging.INFO, logger="edmd2d"):  # (a handler: configured)
        notice.notify(_compile_event(grid.build_lists))
        notice.notify(_compile_event(grid.build_lists))
    assert [r.getMessage() for r in caplog.records] == [
        _compile_notice.message(ed._jit.CACHE)]
    assert caplog.records[0].name == "edmd2d"
    assert capsys.readouterr().err == ""


def test_other_libraries_compiles_are_not_announced(capsys):
    import numba

    @numba.njit
    def other(x):
        return x + 1

    notice = _compile_notice._Notice()
    notice.notify(_compile_event(other))
    assert not notice.said
    assert capsys.readouterr().err == ""
