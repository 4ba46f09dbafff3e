"""Einstein-Helfand moments: the exact time integrals of the fluxes of momentum and
energy of an elastic gas in a periodic box, from which the transport coefficients
follow (``edmd2d.transport``).

Between events every disk flies freely, so the momentum flux ``sum m v_a v_b`` and
the kinetic energy flux ``sum v_a e`` (``e = m v^2 / 2``) of its flight are constant;
their time integrals are sums over flights, which the engine adds as it moves each
disk (:func:`flight`; the flights since each disk's last move: :func:`pending`).  A
collision transfers momentum and energy across the line of centres at once: the
momentum part is the collision virial the engine keeps anyway (``acc[A_VIRIAL_XX]``,
``A_VIRIAL_YY``, ``A_VIRIAL_XY``), the energy part ``d (e_i' - e_i)``, with ``d``
the separation of the pair as it collides (``i``'s centre less that of the image of
``j`` it meets), is added here (:func:`heat`).  Taking ``d`` at the collision, not
the difference of unwrapped positions, is what makes the moments well defined in a
periodic box: a pair that meets across the boundary is as near as any other.

``sums`` (``layout.Helfand``) holds, in this order, the flight integrals of
``sum m v_x^2``, ``sum m v_y^2``, ``sum m v_x v_y``, ``sum v_x e`` and
``sum v_y e``, and the collisional energy transfers ``sum d_x de`` and
``sum d_y de``.
"""

from __future__ import annotations

import numpy as np

from .._jit import njit
from .layout import VX, VY, T, X, Y, unpack_shift

# sums entries
H_XX = 0
H_YY = 1
H_XY = 2
H_QX = 3
H_QY = 4
H_CX = 5
H_CY = 6
N_HELFAND = 7


@njit
def flight(i, t, S, invm, helfand):
    """Add disk ``i``'s free flight from its local time to ``t`` to the flight
    integrals, as the engine moves it."""
    tau = t - S[i, T]
    if tau == 0.0:
        return
    vx = S[i, VX]
    vy = S[i, VY]
    mt = tau / invm[i]
    et = 0.5 * mt * (vx * vx + vy * vy)
    sums = helfand.sums
    sums[H_XX] += mt * vx * vx
    sums[H_YY] += mt * vy * vy
    sums[H_XY] += mt * vx * vy
    sums[H_QX] += et * vx
    sums[H_QY] += et * vy


@njit
def energy(i, S, invm):
    """Disk ``i``'s kinetic energy."""
    return 0.5 * (S[i, VX] * S[i, VX] + S[i, VY] * S[i, VY]) / invm[i]


@njit
def heat(i, j, aux, e_before, S, invm, gf, helfand):
    """Add the energy that the collision of ``i`` with the image ``aux`` of ``j``
    (both at the collision's time, ``i``'s kinetic energy ``e_before`` before it)
    carried across their separation: ``d (e_i' - e_i)``."""
    sx, sy = unpack_shift(aux)
    de = energy(i, S, invm) - e_before
    helfand.sums[H_CX] += (S[i, X] - (S[j, X] + sx * gf[0])) * de
    helfand.sums[H_CY] += (S[i, Y] - (S[j, Y] + sy * gf[1])) * de


def pending(t, S, invm):
    """The flights of every disk from its local time to ``t`` in the flight
    integrals, summed (what the engine adds as it next moves each disk; for readouts
    between events): an array of the five flight entries of ``sums``."""
    tau = t - S[:, T]
    v = S[:, VX:VY + 1]
    mt = tau / invm
    et = 0.5 * mt * np.einsum("ij,ij->i", v, v)
    return np.array([mt @ (v[:, 0] * v[:, 0]), mt @ (v[:, 1] * v[:, 1]),
                     mt @ (v[:, 0] * v[:, 1]), et @ v[:, 0], et @ v[:, 1]])
