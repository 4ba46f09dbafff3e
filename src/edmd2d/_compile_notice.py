"""One line on standard error when edmd2d's compiled code is about to be compiled.

The first use of a kind of system compiles its event loop with numba, which takes
seconds (the times measured are in docs/guide/performance.md); without a word a script
would seem to hang.  numba announces every real compilation with a ``numba:compile``
event: a dispatcher that finds its machine code in memory or in the on-disk cache
(:mod:`edmd2d._jit`) loads it without one.  The listener below says, once per process,
at the first such event for a function of edmd2d, that the engine is being compiled.

The notice is logged at ``INFO`` to the ``edmd2d`` logger.  While logging is not
configured at all (no handler on the way to the root logger) it is written to standard
error instead, where an unconfigured program would otherwise never see it; standard
output stays the script's own.  To silence it, give the logger a handler of its own,
``logging.getLogger("edmd2d").addHandler(logging.NullHandler())``, or configure logging
above ``INFO``.
"""

from __future__ import annotations

import logging
import sys

from numba.core import event as _event

from . import _jit

__all__ = ["LOGGER", "message"]

LOGGER = logging.getLogger("edmd2d")


def message(cache: bool) -> str:
    """The notice, for numba's on-disk cache on (``cache``) or off."""
    later = ("once: later runs load it from numba's disk cache and start at once" if cache
             else "in every new process: numba's disk cache is off, EDMD2D_NUMBA_CACHE=0")
    return ("edmd2d: compiling the engine for this kind of system (typically 10-30 s, "
            f"{later})")


class _Notice(_event.Listener):
    """Says :func:`message` at the first compilation of an edmd2d function."""

    def __init__(self) -> None:
        self.said = False

    def on_start(self, event) -> None:
        if self.said:
            return
        dispatcher = event.data.get("dispatcher") if isinstance(event.data, dict) else None
        module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
        if not (module == "edmd2d" or module.startswith("edmd2d.")):
            return  # (another library's function)
        # (Kept registered: numba iterates over its list of listeners while it calls
        # this one, so removing it here could skip the next.)
        self.said = True
        text = message(_jit.CACHE)
        if LOGGER.hasHandlers():
            LOGGER.info(text)
        else:
            try:
                print(text, file=sys.stderr, flush=True)
            except (OSError, ValueError, AttributeError):  # (stderr closed or None)
                pass

    def on_end(self, event) -> None:
        pass


NOTICE = _Notice()
_event.register("numba:compile", NOTICE)
