"""Flight: where a disk is, and how fast it moves, a time ``dt`` after its state.

Between events every movable disk flies freely: on a straight line at constant
velocity, or, under a uniform acceleration ``g`` (gravity), on the parabola
``p + v dt + g dt^2 / 2`` with velocity ``v + g dt``.  Immovable disks (``invm = 0``)
feel no gravity: they keep their constant velocity.  Each disk's state is stored at its
own local time ``S[i, T]`` ("delayed states"), so its position (and, under gravity, its
velocity) at any later time comes from these functions, and only the disks of an event
are moved to its time (:func:`drift`).  Every place of the engine and of the Python
layer that moves a disk along its flight goes through this module.

The ``gravity`` argument chooses the flight: ``None`` for straight lines (the default,
which compiles to the plain formulas), or a ``layout.Gravity``: the acceleration
``(gx, gy)``, the inverse masses ``invm`` (0 for an immovable disk) and each disk's
``support`` (``layout.S_SUPPORT``): the box walls it slides on, one bit per side, and
whether it is at rest.  A disk held on a box wall (by an inelastic model,
:mod:`.response`, :mod:`.resting`) slides along it: the component of ``g`` normal to
that wall is held by the wall.  A disk at rest (:mod:`.resting`) does not move.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from .layout import RESTING, VX, VY, T, X, Y


@njit
def acceleration(i, gravity):
    """The acceleration of disk ``i``: ``g`` if it is movable, less the components
    that the walls it slides on hold; 0 for an immovable disk or one at rest
    (:mod:`.resting`)."""
    if gravity is None:
        return 0.0, 0.0
    if gravity.invm[i] == 0.0:
        return 0.0, 0.0
    rest = gravity.support[i]
    if rest == 0:
        return gravity.gx, gravity.gy
    if rest & RESTING:
        return 0.0, 0.0
    return sliding_acceleration(rest, gravity)


@njit
def sliding_acceleration(held, gravity):
    """The acceleration of a flying disk that slides on the box walls ``held`` (bits
    ``1 << side``): gravity less the components those walls hold."""
    return (0.0 if held & 3 else gravity.gx), (0.0 if held & 12 else gravity.gy)


@njit
def position_at(i, t, S, gravity):
    """The centre of disk ``i`` at time ``t`` (not wrapped into the box)."""
    dt = t - S[i, T]
    if gravity is None:
        return S[i, X] + dt * S[i, VX], S[i, Y] + dt * S[i, VY]
    gx, gy = acceleration(i, gravity)
    return (S[i, X] + dt * (S[i, VX] + 0.5 * gx * dt),
            S[i, Y] + dt * (S[i, VY] + 0.5 * gy * dt))


@njit
def velocity_at(i, t, S, gravity):
    """The velocity of disk ``i`` at time ``t``."""
    if gravity is None:
        return S[i, VX], S[i, VY]
    dt = t - S[i, T]
    gx, gy = acceleration(i, gravity)
    return S[i, VX] + gx * dt, S[i, VY] + gy * dt


@njit
def drift(i, t, S, gravity):
    """Move disk ``i``'s stored state along its flight to time ``t``."""
    dt = t - S[i, T]
    if gravity is None:
        S[i, X] += dt * S[i, VX]
        S[i, Y] += dt * S[i, VY]
    else:
        gx, gy = acceleration(i, gravity)
        S[i, X] += dt * (S[i, VX] + 0.5 * gx * dt)
        S[i, Y] += dt * (S[i, VY] + 0.5 * gy * dt)
        S[i, VX] += gx * dt
        S[i, VY] += gy * dt
    S[i, T] = t


@njit
def synchronized_positions(t, S, gi, gf, out, gravity):
    """Positions of all disks at time ``t`` (>= every local time), wrapped into the box
    on its periodic axes."""
    for i in range(S.shape[0]):
        x, y = position_at(i, t, S, gravity)
        if gi[2] != 0:
            x -= gf[0] * math.floor(x / gf[0])
        if gi[3] != 0:
            y -= gf[1] * math.floor(y / gf[1])
        out[i, 0] = x
        out[i, 1] = y


def accelerations(gravity):
    """Per-disk accelerations, shape (N, 2) (numpy; see :func:`acceleration`)."""
    acc = np.zeros((len(gravity.invm), 2))
    movable = (gravity.invm > 0.0) & (gravity.support & RESTING == 0)
    acc[movable & (gravity.support & 3 == 0), 0] = gravity.gx
    acc[movable & (gravity.support & 12 == 0), 1] = gravity.gy
    return acc


def positions_at(t, S, gravity=None):
    """Unwrapped centres of all disks at time ``t``, shape (N, 2) (numpy, a new array);
    under gravity on their parabolas."""
    dt = (t - S[:, T])[:, None]
    if gravity is None:
        return S[:, X:Y + 1] + dt * S[:, VX:VY + 1]
    return S[:, X:Y + 1] + dt * (S[:, VX:VY + 1] + 0.5 * accelerations(gravity) * dt)


def velocities_at(t, S, gravity=None):
    """Velocities of all disks at time ``t``, shape (N, 2) (numpy, a new array)."""
    if gravity is None:
        return S[:, VX:VY + 1].copy()
    return S[:, VX:VY + 1] + accelerations(gravity) * (t - S[:, T])[:, None]


def drift_all(t, S, gravity=None):
    """Move every stored state to time ``t`` (all local clocks then equal ``t``)."""
    if gravity is None:
        S[:, X:Y + 1] += (t - S[:, T])[:, None] * S[:, VX:VY + 1]
    else:
        pos = positions_at(t, S, gravity)
        S[:, VX:VY + 1] = velocities_at(t, S, gravity)
        S[:, X:Y + 1] = pos
    S[:, T] = t
