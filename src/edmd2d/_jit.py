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

import os

from numba import njit as _numba_njit

__all__ = ["CACHE", "kernel", "njit"]

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


def kernel(func):
    """:func:`njit` without reference counting, for hot kernels that allocate nothing.

    Compiled callers pass arrays to such a kernel as plain pointers: no atomic
    increment and decrement per array and call (see the module notes).
    """
    return njit(_nrt=False)(func)
