"""numba's cache must follow every engine source, not only the file of each function."""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path

import pytest

import edmd2d
from edmd2d import _jit
from edmd2d._engine import loop, response


def _digest_of(package: Path) -> str:
    spec = importlib.util.spec_from_file_location("_jit_copy", package / "_jit.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module._engine_digest()


def test_an_edit_of_any_engine_module_changes_the_cache_directory(tmp_path):
    # The event loop calls the responses in another file: numba alone would keep the
    # loop's cached code after an edit there.
    package = tmp_path / "edmd2d"
    shutil.copytree(Path(edmd2d.__file__).parent, package,
                    ignore=shutil.ignore_patterns("__pycache__"))
    before = _digest_of(package)
    assert before == _digest_of(package) == _jit._engine_digest()
    target = package / "_engine" / "response.py"
    target.write_text(target.read_text() + "\n# an edit\n")
    assert _digest_of(package) != before


@pytest.mark.skipif(not _jit.CACHE, reason="numba's cache is switched off")
def test_engine_functions_are_cached_under_the_digest_directory():
    for dispatcher in (loop.run, response.collide_pair):
        assert dispatcher._cache._cache_path.startswith(_jit.CACHE_DIR)
    assert _jit._engine_digest() in _jit.CACHE_DIR
