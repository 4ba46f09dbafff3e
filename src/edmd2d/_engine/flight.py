"""Flight: where a disk is, and how fast it moves, a time ``dt`` after its state.

Between events every movable disk flies freely: on a straight line at constant
velocity, or, under a uniform acceleration ``g`` (gravity), on the parabola
``p + v dt + g dt^2 / 2`` with velocity ``v + g dt``.  Immovable disks (``invm = 0``)
feel no gravity: they keep their constant velocity.  Each disk's state is stored at its
own local time ``S[i, T]`` ("delayed states"), so its position (and, under gravity, its
velocity) at any later time comes from these functions, and only the disks of an event
are moved to its time (:func:`drift`).  Every place of the engine and of the Python
layer that moves a disk along its flight goes through this module.

The ``flight`` argument chooses the flight: ``None`` for straight lines (the default,
which compiles to the plain formulas), or ``(gx, gy, invm)``: the acceleration and the
inverse masses (0 for an immovable disk).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from .layout import VX, VY, T, X, Y


@njit(inline="always")
def acceleration(i, flight):
    """The acceleration of disk ``i``: ``g`` if it is movable, else 0."""
    if flight is None:
        return 0.0, 0.0
    gx, gy, invm = flight
    if invm[i] > 0.0:
        return gx, gy
    return 0.0, 0.0


@njit
def position_at(i, t, S, flight):
    """The centre of disk ``i`` at time ``t`` (not wrapped into the box)."""
    dt = t - S[i, T]
    if flight is None:
        return S[i, X] + dt * S[i, VX], S[i, Y] + dt * S[i, VY]
    gx, gy = acceleration(i, flight)
    return (S[i, X] + dt * (S[i, VX] + 0.5 * gx * dt),
            S[i, Y] + dt * (S[i, VY] + 0.5 * gy * dt))


@njit
def velocity_at(i, t, S, flight):
    """The velocity of disk ``i`` at time ``t``."""
    if flight is None:
        return S[i, VX], S[i, VY]
    dt = t - S[i, T]
    gx, gy = acceleration(i, flight)
    return S[i, VX] + gx * dt, S[i, VY] + gy * dt


@njit
def drift(i, t, S, flight):
    """Move disk ``i``'s stored state along its flight to time ``t``."""
    dt = t - S[i, T]
    if flight is None:
        S[i, X] += dt * S[i, VX]
        S[i, Y] += dt * S[i, VY]
    else:
        gx, gy = acceleration(i, flight)
        S[i, X] += dt * (S[i, VX] + 0.5 * gx * dt)
        S[i, Y] += dt * (S[i, VY] + 0.5 * gy * dt)
        S[i, VX] += gx * dt
        S[i, VY] += gy * dt
    S[i, T] = t


@njit
def synchronized_positions(t, S, gi, gf, out, flight):
    """Positions of all disks at time ``t`` (>= every local time), wrapped into the box
    on its periodic axes."""
    for i in range(S.shape[0]):
        x, y = position_at(i, t, S, flight)
        if gi[2] != 0:
            x -= gf[0] * math.floor(x / gf[0])
        if gi[3] != 0:
            y -= gf[1] * math.floor(y / gf[1])
        out[i, 0] = x
        out[i, 1] = y


def _accelerations(S, gravity, invm):
    """Per-disk accelerations, shape (N, 2) (numpy): ``gravity`` for movable disks."""
    return np.where((invm > 0.0)[:, None], np.asarray(gravity, np.float64), 0.0)


def positions_at(t, S, gravity=None, invm=None):
    """Unwrapped centres of all disks at time ``t``, shape (N, 2) (numpy, a new array);
    under ``gravity`` (a 2-vector; ``invm`` the inverse masses) on their parabolas."""
    dt = (t - S[:, T])[:, None]
    if gravity is None:
        return S[:, X:Y + 1] + dt * S[:, VX:VY + 1]
    return S[:, X:Y + 1] + dt * (S[:, VX:VY + 1] + 0.5 * _accelerations(S, gravity, invm) * dt)


def velocities_at(t, S, gravity=None, invm=None):
    """Velocities of all disks at time ``t``, shape (N, 2) (numpy, a new array)."""
    if gravity is None:
        return S[:, VX:VY + 1].copy()
    dt = (t - S[:, T])[:, None]
    return S[:, VX:VY + 1] + _accelerations(S, gravity, invm) * dt


def drift_all(t, S, gravity=None, invm=None):
    """Move every stored state to time ``t`` (all local clocks then equal ``t``)."""
    if gravity is None:
        S[:, X:Y + 1] += (t - S[:, T])[:, None] * S[:, VX:VY + 1]
    else:
        pos = positions_at(t, S, gravity, invm)
        S[:, VX:VY + 1] = velocities_at(t, S, gravity, invm)
        S[:, X:Y + 1] = pos
    S[:, T] = t
