"""Free flight: where a disk is, and how fast it moves, a time ``dt`` after its state.

Between events every movable disk flies on a straight line at constant velocity.  Each
disk's position is stored at its own local time ``S[i, T]`` ("delayed states"), so the
position at any later time comes from these functions, and only the disks of an event
are moved to its time (:func:`drift`).  Every place of the engine and of the Python
layer that moves a disk along its flight goes through this module.
"""

from __future__ import annotations

import math

from .._jit import njit
from .layout import VX, VY, T, X, Y


@njit
def position_at(i, t, S):
    """The centre of disk ``i`` at time ``t`` (not wrapped into the box)."""
    dt = t - S[i, T]
    return S[i, X] + dt * S[i, VX], S[i, Y] + dt * S[i, VY]


@njit
def drift(i, t, S):
    """Move disk ``i``'s stored state along its flight to time ``t``."""
    dt = t - S[i, T]
    S[i, X] += dt * S[i, VX]
    S[i, Y] += dt * S[i, VY]
    S[i, T] = t


@njit
def synchronized_positions(t, S, gi, gf, out):
    """Positions of all disks at time ``t`` (>= every local time), wrapped into the box
    on its periodic axes."""
    for i in range(S.shape[0]):
        x, y = position_at(i, t, S)
        if gi[2] != 0:
            x -= gf[0] * math.floor(x / gf[0])
        if gi[3] != 0:
            y -= gf[1] * math.floor(y / gf[1])
        out[i, 0] = x
        out[i, 1] = y


def positions_at(t, S):
    """Unwrapped centres of all disks at time ``t``, shape (N, 2) (numpy, a new array)."""
    return S[:, X:Y + 1] + (t - S[:, T])[:, None] * S[:, VX:VY + 1]


def drift_all(t, S):
    """Move every stored state to time ``t`` (all local clocks then equal ``t``)."""
    S[:, X:Y + 1] += (t - S[:, T])[:, None] * S[:, VX:VY + 1]
    S[:, T] = t
