"""Dot products and weighted sums whose bits do not depend on the machine.

NumPy hands ``a @ b`` and ``np.dot`` to its BLAS library (OpenBLAS in the wheels),
which picks a kernel for the processor it runs on (or the one ``OPENBLAS_CORETYPE``
names): the SkylakeX, Haswell and older kernels add the products in different orders
and round the sums differently in the last bits.  A trajectory is chaotic, so one such
bit in a centre-of-mass velocity or a temperature rescale grows into a different run
(measured: the same seed compressed to a crystal of global ``|psi_6|`` 0.93 with the
SkylakeX kernel and 0.80 with the Haswell one).  Every sum on the path of a trajectory
goes through these functions instead: an elementwise product (each rounded once, as
IEEE arithmetic prescribes) summed by NumPy's pairwise summation, whose order depends
on the array's length alone.  Their cost is of the order of a copy of the arrays.
"""

from __future__ import annotations

import numpy as np

__all__ = ["dot", "weighted_sum"]


def dot(a, b):
    """``sum(a * b)`` over the last axis: for two vectors a number, for an ``(n, k)``
    array against a ``(k,)`` vector the ``n`` row products."""
    return np.sum(np.multiply(a, b), axis=-1)


def weighted_sum(w: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``sum_i w_i x_i`` of weights ``w`` (shape ``(n,)``) and rows ``x`` (shape
    ``(n, k)``), shape ``(k,)``: the machine-independent ``w @ x``."""
    return np.sum(np.ascontiguousarray((w[:, None] * x).T), axis=-1)
