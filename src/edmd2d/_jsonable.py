"""Dicts of numbers and arrays as JSON values, exactly (a checkpoint's metadata)."""

from __future__ import annotations

import json

import numpy as np


def encode(edge: dict) -> dict:
    """A dict of numbers and arrays (a measurement boundary,
    :func:`edmd2d.measurements._edge`) in JSON-able values:
    arrays as ``{"dtype", "shape", "data"}``; floats as they are (JSON keeps a float64
    exactly through its shortest repr)."""

    def enc(value):
        if isinstance(value, dict):
            return {k: enc(v) for k, v in value.items()}
        if isinstance(value, np.ndarray):
            return {"dtype": value.dtype.str, "shape": list(value.shape),
                    "data": value.ravel().tolist()}
        if isinstance(value, np.generic):
            return value.item()
        return value

    out = enc(edge)
    json.dumps(out)  # (fails here, not in the middle of writing a file)
    return out


def decode(edge: dict) -> dict:
    """The dict that :func:`encode` was given, arrays rebuilt bit for bit."""
    def dec(value):
        if isinstance(value, dict):
            if set(value) == {"dtype", "shape", "data"}:
                return np.array(value["data"], dtype=value["dtype"]).reshape(value["shape"])
            return {k: dec(v) for k, v in value.items()}
        return value

    return dec(edge)
