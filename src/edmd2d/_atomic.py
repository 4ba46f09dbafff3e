"""Files written whole or not at all, with the permissions the user's umask gives.

Checkpoints, result tables and trimmed trajectories are written to a temporary file
beside the target, flushed to disk and renamed over it, so that a reader, or a run
that resumes after a crash, never sees half a file.  ``tempfile.mkstemp`` creates the
temporary file with mode 0600 whatever the umask; the file is given the mode a plain
``open`` would have given it (0666 less the umask) before it takes the target's place.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

__all__ = ["replacing", "replacing_path", "write_text", "umask_mode"]


def umask_mode() -> int:
    """The mode ``open`` gives a new file: 0666 less the process's umask."""
    mask = os.umask(0)  # (the only way to read the umask is to set it)
    os.umask(mask)
    return 0o666 & ~mask


@contextlib.contextmanager
def replacing_path(path):
    """The name of a temporary file beside ``path``, for a writer that opens files by
    name; when the block ends without an error the file replaces ``path`` (with the
    umask's mode), otherwise it is removed."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        yield tmp
        os.chmod(tmp, umask_mode())
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


@contextlib.contextmanager
def replacing(path, mode: str = "wb", encoding: str | None = None):
    """A file object (``mode`` ``"wb"`` or ``"w"``) whose contents, flushed to disk,
    replace ``path`` when the block ends without an error."""
    with replacing_path(path) as tmp, open(tmp, mode, encoding=encoding) as f:
        yield f
        f.flush()
        os.fsync(f.fileno())


def write_text(path, text: str) -> None:
    """Replace ``path`` by ``text`` (UTF-8) at once."""
    with replacing(path, "w", encoding="utf-8") as f:
        f.write(text)
