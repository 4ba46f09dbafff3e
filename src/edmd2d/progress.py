"""Progress bars for long runs, animation saves and measurements (``tqdm``).

Library calls show no bar unless asked (``progress=True``); the bar goes to standard
error, redrawn in place on a terminal and printed as lines elsewhere (tqdm's own
behaviour).  A call may also be handed an existing ``tqdm`` bar, which it advances:
:func:`edmd2d.measurements.measure` passes one bar through its blocks this way.
"""

from __future__ import annotations

from typing import Any, TypeAlias

__all__ = ["bar"]

# What a ``progress`` argument takes: True, False, None or a tqdm bar (tqdm has no type
# information: a bar is any object with ``update``).
ProgressArg: TypeAlias = "bool | None | Any"


def bar(progress: ProgressArg, *, total: float | None, unit: str, desc: str,
        unit_scale: bool = True) -> tuple[Any, bool]:
    """The bar a call with ``progress`` should update.

    Parameters
    ----------
    progress : bool, None or tqdm bar
        What the caller was given: ``False`` or ``None`` for no bar, ``True`` for a
        new one, or a bar (anything with ``update``) to advance.
    total : float or None
        The total of a new bar (``None``: unknown).
    unit : str
        The unit of a new bar (``"frame"``, ``"t"``, ...).
    desc : str
        The label of a new bar.
    unit_scale : bool, default True
        Show the counts of a new bar with SI prefixes (``12.3k``) and decimals; off
        for counts of whole things (tasks).

    Returns
    -------
    bar : tqdm bar or None
        ``None`` for no bar, a new tqdm bar over ``total`` ``unit`` for ``True``, or
        ``progress`` itself.
    owned : bool
        Whether the bar was created here, so that the caller must close it.

    Raises
    ------
    TypeError
        For any other ``progress``.
    """
    if progress is None or progress is False:
        return None, False
    if progress is True:
        from tqdm.auto import tqdm

        return tqdm(total=total, unit=unit, desc=desc, dynamic_ncols=True,
                    unit_scale=unit_scale, leave=True), True
    if hasattr(progress, "update"):
        return progress, False
    raise TypeError(f"progress must be True, False or a tqdm bar, got {progress!r}")
