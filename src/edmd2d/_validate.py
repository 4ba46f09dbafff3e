"""One converter for every array argument of the public API.

Each public function passes user input through :func:`as_float_array` (or
:func:`per_disk`), which returns a C-contiguous float64 array of the expected shape or
raises ``TypeError``/``ValueError`` naming the argument, what was received, what was
expected and, where it helps, the offending indices.  Never ``assert`` on user input:
assertions vanish under ``python -O``.
"""

from __future__ import annotations

import contextlib
import functools
import numbers
from collections.abc import Iterator

import numpy as np

__all__ = ["as_float_array", "per_disk", "as_count", "as_positive_float", "indices_where",
           "as_generator", "about", "refusal", "argument_of"]

_MAX_LISTED = 10
_MAX_COUNT = int(np.iinfo(np.int64).max)


@contextlib.contextmanager
def about(name: str) -> Iterator[None]:
    """Mark the errors (``TypeError``, ``ValueError``) raised inside as being about the
    argument ``name``, so that a caller (the configuration loader) can point at its own
    key for that argument without reading the message.

    An outer ``about`` has the last word: a check of ``wall_temperatures`` is about
    that keyword, whatever its inner checks called the value.

    Parameters
    ----------
    name : str
        The argument (or keyword).

    Yields
    ------
    None

    Examples
    --------
    >>> from edmd2d.physics import about
    >>> try:
    ...     with about("label_level"):
    ...         raise ValueError("label_level must be >= 0, got -1")
    ... except ValueError as exc:
    ...     print(exc.edmd2d_argument)
    label_level
    """
    try:
        yield
    except (TypeError, ValueError) as exc:
        # (An attribute of edmd2d's own on the exception, which the CLI reads.)
        exc.edmd2d_argument = name  # type: ignore[union-attr]
        raise


def refusal(kind: type, argument: str, message: str) -> Exception:
    """An error ``kind(message)`` about ``argument`` (see :func:`about`), to raise."""
    exc = kind(message)
    exc.edmd2d_argument = argument
    return exc


def argument_of(exc: BaseException) -> str | None:
    """The argument an error is about (see :func:`about`), or ``None``."""
    return getattr(exc, "edmd2d_argument", None)


def _names_argument(check):
    """Errors of ``check(name, ...)`` are about ``name``."""

    @functools.wraps(check)
    def checked(name, *args, **kwargs):
        with about(name):
            return check(name, *args, **kwargs)

    return checked


def indices_where(mask: np.ndarray) -> str:
    """Describe the indices where ``mask`` is true, at most a few of them."""
    idx = np.flatnonzero(np.asarray(mask).reshape(len(mask), -1).any(axis=1))
    shown = ", ".join(str(int(i)) for i in idx[:_MAX_LISTED])
    more = f" and {len(idx) - _MAX_LISTED} more" if len(idx) > _MAX_LISTED else ""
    return f"[{shown}{more}]"


@_names_argument
def as_float_array(
    name: str,
    value,
    shape: tuple,
    *,
    allow_inf: bool = False,
) -> np.ndarray:
    """Convert ``value`` to a C-contiguous float64 array of ``shape``.

    ``shape`` may contain ``None`` for a free length.  NaN is always rejected; infinity
    only when ``allow_inf`` is false.
    """
    if value is None:
        raise TypeError(f"{name} is required, got None")
    try:
        kind = np.asarray(value).dtype.kind
    except (TypeError, ValueError):  # (ragged nesting: the conversion below says so)
        kind = "O"
    if isinstance(value, (str, bytes)) or kind in "USa":
        # (numpy would parse strings nested in lists; refused everywhere alike)
        shown = value if isinstance(value, (str, bytes)) else np.asarray(value)
        raise TypeError(f"{name} must be numeric, got strings: {shown!r}")
    # (checked before the conversion, which would warn that it drops imaginary parts)
    if kind == "c" or isinstance(value, complex):
        raise TypeError(f"{name} must be real, got complex values")
    if kind == "b" or isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be numbers, got booleans: {value!r}")
    try:
        arr = np.array(value, dtype=np.float64, order="C", copy=True)
    except (TypeError, ValueError) as exc:
        raise TypeError(
            f"{name} must be an array of real numbers with shape {_fmt(shape)}; "
            f"could not convert {type(value).__name__}: {exc}"
        ) from None
    if arr.ndim != len(shape) or any(s is not None and s != a for s, a in zip(shape, arr.shape)):
        raise ValueError(f"{name} must have shape {_fmt(shape)}, got shape {arr.shape}")
    bad = np.isnan(arr) if allow_inf else ~np.isfinite(arr)
    if bad.any():
        what = "NaN" if allow_inf else "NaN or infinite"
        if arr.ndim == 0:
            raise ValueError(f"{name} contains {what} values: got {float(arr)}, need a "
                             "finite number")
        raise ValueError(f"{name} contains {what} values at indices {indices_where(bad)}")
    return arr


@_names_argument
def per_disk(name: str, value, n: int, *, allow_inf: bool = False) -> np.ndarray:
    """A per-disk quantity: a scalar broadcast to ``(n,)`` or an array of shape ``(n,)``."""
    if value is None:
        raise TypeError(f"{name} is required, got None")
    if np.ndim(value) == 0:
        scalar = as_float_array(name, value, (), allow_inf=allow_inf)
        return np.full(n, float(scalar), dtype=np.float64)
    return as_float_array(name, value, (n,), allow_inf=allow_inf)


@_names_argument
def as_count(name: str, value, minimum: int = 0) -> int:
    """An integer >= ``minimum`` (a number of collisions, disks, frames...)."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)):
        if isinstance(value, (float, np.floating)) and float(value).is_integer():
            value = int(value)
        else:
            raise TypeError(f"{name} must be an integer, got {type(value).__name__} {value!r}")
    value = int(value)
    if value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {value}")
    if value > _MAX_COUNT:
        raise ValueError(f"{name} must be at most 2**63 - 1 (a 64-bit count), got {value}")
    return value


@_names_argument
def as_positive_float(name: str, value, *, allow_zero: bool = False) -> float:
    """A finite scalar > 0 (or >= 0 with ``allow_zero``)."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, np.floating, np.integer)):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__} {value!r}")
    value = float(value)
    if not np.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value}")
    if value < 0 or (value == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be {bound}, got {value}")
    return value


def _fmt(shape: tuple) -> str:
    parts = ["N" if s is None else str(s) for s in shape]
    return "(" + ", ".join(parts) + ("," if len(parts) == 1 else "") + ")"


@_names_argument
def as_generator(name: str, seed) -> np.random.Generator:
    """``numpy.random.default_rng(seed)``, whose errors name the argument."""
    try:
        return np.random.default_rng(seed)
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"{name} must be None, an int >= 0, a numpy.random.SeedSequence or "
                        f"a numpy.random.Generator, got {seed!r} ({exc})") from None
