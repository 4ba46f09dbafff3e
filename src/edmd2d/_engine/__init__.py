"""The compiled core: plain ``@njit`` functions over flat numpy arrays, no classes.

Nothing here validates input or raises: the Python layer (``simulation.py``) checks
arguments before calling in, and kernels report problems through status codes.
"""
