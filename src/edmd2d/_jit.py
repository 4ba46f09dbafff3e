"""Numba settings in one place.

Every compiled kernel of edmd2d is decorated with :func:`njit` from this module, so that
caching and compiler options are chosen once.  Set the environment variable
``EDMD2D_NUMBA_CACHE=0`` to turn the on-disk cache off (for instance on a read-only
install or when debugging the compiler); ``NUMBA_DISABLE_JIT=1`` (numba's own switch)
runs the kernels as plain Python.

Hot kernels that allocate nothing are decorated with :func:`kernel` instead: the same
settings with numba's reference counting (NRT) switched off.  With it on, every call
between compiled functions increments and decrements the reference count of each array
argument with an atomic (``lock``-prefixed) instruction, and the event loop passes
about twenty arrays per prediction (the cost measured is in docs/performance-notes.md).
A function without NRT must not create arrays (``np.empty``, slices returned to the
caller and the like); such functions keep :func:`njit`.

Inlining: numba's ``inline="always"`` inlines at the level of numba's own IR, and every
such site reruns whole-function passes (SSA, liveness, type inference) over the caller.
Small scalar helpers (contact times, cell neighbours) are therefore plain :func:`njit`
functions, which LLVM inlines into the event loop by itself, at a fraction of the
compile time and the same speed.  ``inline="always"`` is kept for helpers
that take many arrays (where a call would pass each array as a struct) and for the
single prediction site of the loop.

``fastmath`` is deliberately off: the collision kernels rely on IEEE semantics (signed
comparisons of nearly cancelling quantities, ``inf`` for "never"), and the elastic
response must conserve energy and momentum to rounding.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
from pathlib import Path

from numba import njit as _numba_njit
from numba.core import config as _numba_config

__all__ = ["CACHE", "CACHE_DIR", "kernel", "njit"]

CACHE: bool = os.environ.get("EDMD2D_NUMBA_CACHE", "1").strip().lower() not in {
    "0",
    "false",
    "no",
    "off",
}


def _engine_digest() -> str:
    """A digest of the source of every module that holds compiled code."""
    here = Path(__file__).resolve().parent
    digest = hashlib.sha256()
    for path in sorted([here / "_jit.py", *(here / "_engine").glob("*.py")]):
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


# numba keys a cached function on the source of its own file only: after an edit of a
# module it calls (a contact time, a response, the queue), the event loop's cached
# machine code would be loaded unchanged.  edmd2d's functions are therefore cached in
# a directory named by a digest of all the engine's sources (under NUMBA_CACHE_DIR if
# set, else beside the package), so that any edit compiles afresh.
CACHE_DIR: str | None = None
if CACHE:
    _base = os.environ.get("NUMBA_CACHE_DIR") or str(Path(__file__).resolve().parent
                                                      / "__pycache__")
    CACHE_DIR = os.path.join(_base, f"edmd2d-engine-{_engine_digest()}")


@contextlib.contextmanager
def _engine_cache_dir():
    """Numba reads its cache directory when a function is decorated: point it at
    :data:`CACHE_DIR` for edmd2d's functions only."""
    if CACHE_DIR is None:
        yield
        return
    before = _numba_config.CACHE_DIR
    _numba_config.CACHE_DIR = CACHE_DIR
    try:
        yield
    finally:
        _numba_config.CACHE_DIR = before


def njit(*args, **kwargs):
    """``numba.njit`` with edmd2d's defaults (cache on unless disabled, no fastmath,
    cached under :data:`CACHE_DIR`)."""
    kwargs.setdefault("cache", CACHE)
    kwargs.setdefault("fastmath", False)
    kwargs.setdefault("error_model", "numpy")
    if args and callable(args[0]):
        with _engine_cache_dir():
            return _numba_njit(*args, **kwargs)
    decorate = _numba_njit(*args, **kwargs)

    def decorator(func):
        with _engine_cache_dir():
            return decorate(func)

    return decorator


def kernel(func):
    """:func:`njit` without reference counting, for hot kernels that allocate nothing.

    Compiled callers pass arrays to such a kernel as plain pointers: no atomic
    increment and decrement per array and call (see the module notes).
    """
    return njit(_nrt=False)(func)
