"""The compiled core: plain ``@njit`` functions over flat numpy arrays, no classes.

Nothing here validates input or raises: the Python layer (``simulation.py``) checks
arguments before calling in, and kernels report problems through status codes.
"""

import numpy as np


def aligned_rows(n: int, width: int, dtype, align: int = 64) -> np.ndarray:
    """An uninitialised C-contiguous ``(n, width)`` array starting on an ``align``-byte
    boundary, so that rows of ``align`` bytes (or a divisor of it) never straddle two
    cache lines."""
    itemsize = np.dtype(dtype).itemsize
    buf = np.empty(n * width + align // itemsize, dtype)
    skip = (-buf.ctypes.data % align) // itemsize
    return buf[skip:skip + n * width].reshape(n, width)
