"""Numba settings in one place.

Every compiled kernel of edmd2d is decorated with :func:`njit` from this module, so that
caching and compiler options are chosen once.  Set the environment variable
``EDMD2D_NUMBA_CACHE=0`` to turn the on-disk cache off (for instance on a read-only
install or when debugging the compiler); ``NUMBA_DISABLE_JIT=1`` (numba's own switch)
runs the kernels as plain Python.

``fastmath`` is deliberately off: the collision kernels rely on IEEE semantics (signed
comparisons of nearly cancelling quantities, ``inf`` for "never"), and the elastic
response must conserve energy and momentum to rounding.
"""

from __future__ import annotations

import os

from numba import njit as _numba_njit

__all__ = ["CACHE", "njit"]

CACHE: bool = os.environ.get("EDMD2D_NUMBA_CACHE", "1").strip().lower() not in {
    "0",
    "false",
    "no",
    "off",
}


def njit(*args, **kwargs):
    """``numba.njit`` with edmd2d's defaults (cache on unless disabled, no fastmath)."""
    kwargs.setdefault("cache", CACHE)
    kwargs.setdefault("fastmath", False)
    kwargs.setdefault("error_model", "numpy")
    return _numba_njit(*args, **kwargs)
