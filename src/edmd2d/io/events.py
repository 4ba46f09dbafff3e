"""The event stream in a file: :class:`EventWriter` appends every batch that
:meth:`edmd2d.Simulation.stream_events` delivers to a CSV file (one line an event:
``time,kind,disk,partner,impulse``, the time and impulse to the last bit).

Examples
--------
>>> import os, tempfile
>>> import edmd2d as ed
>>> from edmd2d.io.events import EventWriter, read
>>> path = os.path.join(tempfile.mkdtemp(), "events.csv")
>>> sim = ed.make_gas(100, 0.3, seed=1)
>>> with EventWriter(path) as out:
...     sim.stream_events(out)
...     _ = sim.advance(collisions=50)
...     sim.stream_events(None)
>>> events = read(path)
>>> int((events["kind"] == "disk").sum())
50
"""

from __future__ import annotations

import os

import numpy as np

from ..simulation import EVENT_DTYPE

__all__ = ["EventWriter", "read"]

_HEADER = "time,kind,disk,partner,impulse\n"


class EventWriter:
    """A callable for :meth:`~edmd2d.Simulation.stream_events` that writes each batch
    to a CSV file and flushes it, so that a run stopped half-way leaves every event
    delivered so far on disk.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    mode : {"w", "a"}, default "w"
        ``"w"`` creates (or truncates) the file and writes the header line
        ``time,kind,disk,partner,impulse``; ``"a"`` appends to an existing event file.

    Raises
    ------
    ValueError
        For another ``mode``.
    """

    def __init__(self, path: str | os.PathLike[str], mode: str = "w") -> None:
        if mode not in ("w", "a"):
            raise ValueError(f"mode must be 'w' or 'a', got {mode!r}")
        self._file = open(path, mode, encoding="ascii")
        if mode == "w":
            self._file.write(_HEADER)

    def __call__(self, batch) -> None:
        """Append a batch of events (a structured array of ``EVENT_DTYPE``) as rows."""
        lines = [f"{float(e['time'])!r},{e['kind']},{int(e['disk'])},{int(e['partner'])},"
                 f"{float(e['impulse'])!r}\n" for e in batch]
        self._file.writelines(lines)
        self._file.flush()

    def close(self) -> None:
        """Close the file (also on leaving a ``with`` block)."""
        self._file.close()

    def __enter__(self) -> EventWriter:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def read(path: str | os.PathLike[str]) -> np.ndarray:
    """The events of a file written by :class:`EventWriter`.

    Parameters
    ----------
    path : str or os.PathLike
        The event file.

    Returns
    -------
    ndarray
        One element per event, in the file's order, with the fields of
        :data:`edmd2d.simulation.EVENT_DTYPE` (``time``, ``kind``, ``disk``,
        ``partner``, ``impulse``).

    Raises
    ------
    ValueError
        For a file that does not start with the event file's header line.
    """
    with open(path, encoding="ascii") as f:
        header = f.readline()
        if header != _HEADER:
            raise ValueError(f"{path} is not an edmd2d event file (header {header!r})")
        rows = [line.rstrip("\n").split(",") for line in f if line.strip()]
    out = np.empty(len(rows), dtype=EVENT_DTYPE)
    for k, (t, kind, disk, partner, impulse) in enumerate(rows):
        out[k] = (float(t), kind, int(disk), int(partner), float(impulse))
    return out
