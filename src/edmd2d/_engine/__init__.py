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


def _prefetch_codegen(context, builder, signature, args):
    from llvmlite import ir
    from numba.core import cgutils, types

    aryty, idxty = signature.args
    ary = context.make_array(aryty)(context, builder, args[0])
    zero = context.get_constant(types.intp, 0)
    row = context.cast(builder, args[1], idxty, types.intp)
    ptr = cgutils.get_item_pointer2(
        context, builder, data=ary.data, shape=cgutils.unpack_tuple(builder, ary.shape),
        strides=cgutils.unpack_tuple(builder, ary.strides), layout=aryty.layout,
        inds=[row] + [zero] * (aryty.ndim - 1), wraparound=False,
    )
    byte_ptr = ir.IntType(8).as_pointer()
    i32 = ir.IntType(32)
    fnty = ir.FunctionType(ir.VoidType(), [byte_ptr, i32, i32, i32])
    fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.prefetch.p0")
    # (address, read, keep in all cache levels, data cache)
    builder.call(fn, [builder.bitcast(ptr, byte_ptr), ir.Constant(i32, 0),
                      ir.Constant(i32, 3), ir.Constant(i32, 1)])
    return context.get_dummy_value()


def _make_prefetch():
    from numba.core import config, types
    from numba.extending import intrinsic

    if config.DISABLE_JIT:
        def prefetch(arr, i):  # plain Python: nothing to prefetch
            return None

        return prefetch

    @intrinsic
    def prefetch(typingctx, arr, i):
        """Ask the CPU to start loading row ``i`` of ``arr`` into the caches (a hint:
        no effect on results).  The event loop uses it for the disks of the next
        events, whose rows are otherwise cache misses at large N."""
        if isinstance(arr, types.Array) and isinstance(i, types.Integer):
            return types.void(arr, i), _prefetch_codegen
        return None

    return prefetch


prefetch = _make_prefetch()
