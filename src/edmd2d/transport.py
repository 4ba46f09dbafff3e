"""Transport coefficients from equilibrium: the shear and bulk viscosities, the
thermal conductivity and the self-diffusion coefficient of an elastic gas in a
periodic box, from Einstein-Helfand moments, and the velocity autocorrelation
function with its long-time tail.

Each coefficient is the growth rate of the mean square of a moment, the time
integral of a flux (for the viscosity, the momentum flux ``A P_xy``; for heat, the
energy flux):

``<(G(t0 + tau) - G(t0))^2> ~ 2 A kT c tau`` (``kT^2`` in place of ``kT`` for heat)

at long ``tau``, the Einstein form of the Green-Kubo integral of the flux's
autocorrelation.  For hard disks the moments are exact sums (``_engine/helfand.py``):
each flight adds ``m v_a v_b`` or ``v_a e`` times its duration, each collision the
momentum ``d_a J_b`` or the energy ``d_a de`` it carries across the separation ``d`` of
the pair at contact.  Taking ``d`` at contact, the nearest image, rather than the
difference of unwrapped positions, is what defines the moments in a periodic box:
with unwrapped positions a pair meeting across the boundary would jump the moment
by a box length times the impulse, a random walk of its own that would add to the
coefficient.  The engine keeps the sums while a :class:`~edmd2d.transport.Transport` operation runs,
at no cost otherwise.

The self-diffusion coefficient comes from the mean squared displacement of the
unwrapped centres, ``<|r(t0 + tau) - r(t0)|^2> ~ 4 D tau``, and the velocity
autocorrelation ``<v(t0) . v(t0 + tau)> / 2`` (per axis) from the velocities at the
samples.  In two dimensions that autocorrelation decays as ``1 / tau`` at long times
(the long-time tail), so ``D`` grows with the time window and with the box: compare
values at the same ``N`` and window only (see ``docs/transport.md``).

Every estimate comes with an error from blocks: the samples are cut into blocks of
time origins, each block gives its own estimate, and the error is the standard
error of their mean.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from . import progress as _progress
from ._engine import helfand as _helfand
from ._jit import njit
from ._operations import Every, Operation, run
from ._validate import as_count, as_positive_float
from .measurements import kinetic_temperature

if TYPE_CHECKING:
    from .simulation import Simulation

__all__ = ["Transport", "TransportCoefficients", "transport"]

# Relative tolerance of "a whole number of samples" (window / dt, block / dt).
_WHOLE = 1e-9


@dataclass(frozen=True)
class TransportCoefficients:
    """Transport coefficients of an equilibrium run (:func:`~edmd2d.transport.transport`,
    :meth:`Transport.result`), each with the standard error of its mean over the
    blocks (``nan`` with fewer than two blocks).

    The coefficients are the slopes of the moments' mean squares against the time
    window ``tau``, fitted over ``fit`` (fractions of the longest window): that removes
    the offset the short-time motion leaves.  The curves (``*_curve``) are the running
    values ``<dG^2> / (2 A kT tau)`` at each window, which approach the coefficient as
    ``1 / tau``.  Units: those of the simulation (``k_B = 1``).

    Attributes
    ----------
    n : int
        The number of disks.
    area : float
        The box's area ``A``.
    density : float
        ``N / A``.
    packing_fraction : float
    temperature : float
        The kinetic temperature ``kT`` (constant in an elastic run).
    pressure : float
        The mean pressure over the run, exact from the moments.
    duration : float
        The simulated time sampled.
    dt : float
        The time between samples.
    blocks : int
        The number of complete blocks of time origins used.
    fit : tuple of float
        The windows the slopes were fitted over, as fractions of the longest.
    times : numpy.ndarray, shape (L,)
        The time windows ``tau = dt, 2 dt, ..., window``.
    shear_viscosity, shear_viscosity_error : float
        ``eta``: from the moments of ``P_xy`` and ``(P_xx - P_yy) / 2`` (both give
        ``eta`` in an isotropic fluid; their mean is used).
    shear_viscosity_curve, shear_viscosity_curve_error : numpy.ndarray, shape (L,)
    bulk_viscosity, bulk_viscosity_error : float
        ``zeta``: from the moment of ``(P_xx + P_yy) / 2`` less its mean.
    bulk_viscosity_curve, bulk_viscosity_curve_error : numpy.ndarray, shape (L,)
    thermal_conductivity, thermal_conductivity_error : float
        ``lambda``, from the moment of the energy flux (``kT^2`` in the denominator);
        ``nan`` for a mixture, where the energy flux also carries interdiffusion.
    thermal_conductivity_curve, thermal_conductivity_curve_error : numpy.ndarray
    diffusion, diffusion_error : numpy.ndarray, shape (S,)
        The self-diffusion coefficient ``D`` of each species (``S`` species, by
        :attr:`~edmd2d.Simulation.species`).
    diffusion_curve, diffusion_curve_error : numpy.ndarray, shape (L, S)
        ``MSD / (4 tau)``.
    vacf_times : numpy.ndarray, shape (L + 1,)
        ``0, dt, ..., window``.
    vacf, vacf_error : numpy.ndarray, shape (L + 1, S)
        The velocity autocorrelation ``<v(t0) . v(t0 + tau)> / 2`` (per axis) of each
        species; ``kT / m`` at ``tau = 0``.
    """

    n: int
    area: float
    density: float
    packing_fraction: float
    temperature: float
    pressure: float
    duration: float
    dt: float
    blocks: int
    fit: tuple[float, float]
    times: np.ndarray
    shear_viscosity: float
    shear_viscosity_error: float
    shear_viscosity_curve: np.ndarray
    shear_viscosity_curve_error: np.ndarray
    bulk_viscosity: float
    bulk_viscosity_error: float
    bulk_viscosity_curve: np.ndarray
    bulk_viscosity_curve_error: np.ndarray
    thermal_conductivity: float
    thermal_conductivity_error: float
    thermal_conductivity_curve: np.ndarray
    thermal_conductivity_curve_error: np.ndarray
    diffusion: np.ndarray
    diffusion_error: np.ndarray
    diffusion_curve: np.ndarray
    diffusion_curve_error: np.ndarray
    vacf_times: np.ndarray
    vacf: np.ndarray
    vacf_error: np.ndarray


def _whole(name: str, value: float, dt: float) -> int:
    """``value / dt`` as a whole number >= 1 (``name`` the argument for errors)."""
    k = round(value / dt)
    if k < 1 or abs(value / dt - k) > _WHOLE * max(k, 1):
        raise ValueError(f"{name}={value!r} must be a whole multiple of dt={dt!r}")
    return int(k)


def _check_equilibrium(sim: Simulation) -> None:
    """Refuse a system whose moments would not give transport coefficients: only
    elastic disks in a periodic box without walls, fields or thermostat conserve
    momentum and energy, and the moments are taken in the centre-of-mass frame."""
    state = sim._state
    why = None
    if tuple(sim.box.periodic) != (True, True):
        why = "a box periodic on both axes"
    elif sim.walls:
        why = "no wall segments"
    elif sim.families:
        why = "no physics families (got " + ", ".join(sorted(sim.families)) + ")"
    elif state.model is not None:
        why = "elastic disks without thermostat or heated walls (got " f"{state.model!r})"
    elif np.any(sim.gravity != 0.0):
        why = "no gravity"
    elif sim.growth is not None:
        why = "no growth"
    elif not np.all(np.isfinite(sim.masses)):
        why = "no immovable disks"
    if why is not None:
        raise ValueError(f"transport coefficients need an equilibrium system: {why}")
    m = sim.masses
    v = sim.velocities
    p = np.hypot(*sim.momentum())
    scale = math.sqrt(float(m.sum()) * float(np.dot(m, np.einsum("ij,ij->i", v, v))))
    if p > 1e-9 * scale:
        raise ValueError(
            f"transport coefficients are taken in the centre-of-mass frame, but the "
            f"total momentum is {sim.momentum().tolist()}: remove it first, e.g. "
            f"sim.set_velocities(v - (m[:, None] * v).sum(0) / m.sum())")


class Transport(Operation):
    """Sample the Einstein-Helfand moments, the unwrapped centres and the velocities
    every ``dt`` of a run, for :class:`~edmd2d.transport.TransportCoefficients` (see
    the module notes).

    The moments themselves are exact (the engine sums them over every flight and
    collision while the operation runs); ``dt`` only sets the time windows at which
    they are compared, and the samples of the displacements and velocities.  The
    time origins are cut into blocks of ``block`` each for the errors; a block counts
    once every window from each of its origins has been sampled.

    A Transport used in a second run goes on where it stopped, if that run starts at
    its last sample and no positions or velocities were set in between.

    Parameters
    ----------
    dt : float
        The time between samples, > 0.
    window : float
        The longest time window, a whole multiple of ``dt``.
    block : float
        The time origins per block, a whole multiple of ``dt``, at least ``window``
        (ten times as long or more keeps the blocks nearly independent).
    fit : (float, float), default (0.5, 1.0)
        The windows to fit the slopes over, as fractions of ``window`` (at least two
        windows, from ``dt`` on).
    blocks : int, optional
        Use at most this many blocks (default: every complete one).

    Examples
    --------
    >>> import edmd2d as ed
    >>> from edmd2d.transport import Transport
    >>> sim = ed.make_gas(400, 0.3, seed=1)
    >>> op = Transport(dt=0.1, window=1.0, block=5.0)
    >>> _ = sim.run(until=21.0, operations=[op])
    >>> c = op.result()
    >>> c.blocks, c.times.shape, round(c.temperature, 9)
    (4, (10,), 1.0)
    """

    def __init__(self, *, dt: float, window: float, block: float,
                 fit: tuple[float, float] = (0.5, 1.0), blocks: int | None = None) -> None:
        self.dt = as_positive_float("dt", dt)
        super().__init__(Every(dt=self.dt))
        self.lags = _whole("window", as_positive_float("window", window), self.dt)
        self.per_block = _whole("block", as_positive_float("block", block), self.dt)
        if self.per_block < self.lags:
            raise ValueError(f"block={block!r} must be at least window={window!r}")
        self.fit = _fit(fit)
        self._fitted = _fitted(self.fit, self.lags, window)
        self.max_blocks = None if blocks is None else as_count("blocks", blocks, minimum=1)
        self._sim: Simulation | None = None
        self._time = math.nan  # of the last sample
        self._edits = 0  # the state's count of edits at the last sample
        self._moments: list[np.ndarray] = []  # one row of 5 per sample
        self._base = np.zeros(5)  # added to the engine's moments (continuation)
        self._ring_r: np.ndarray | None = None
        self._ring_v: np.ndarray | None = None
        self._msd: list[np.ndarray] = []  # per block of origins, (L + 1, S)
        self._vv: list[np.ndarray] = []
        self._count: list[np.ndarray] = []  # origins per block and lag, (L + 1,)
        self._species: np.ndarray | None = None
        self._per_species: np.ndarray | None = None
        self._temperatures: list[float] = []  # kT at each sample
        self._meta: dict = {}

    @property
    def samples(self) -> int:
        """The samples taken so far (the first at the start)."""
        return len(self._moments)

    @property
    def moments(self) -> np.ndarray:
        """The Einstein-Helfand moments at each sample since the first, shape
        ``(samples, 5)``: the time integrals of the momentum flux ``(xx, yy, xy)``
        (``sum m v_a v_b`` over the flights plus ``sum d_a J_b`` over the collisions)
        and of the energy flux ``(x, y)`` (``sum v_a e`` plus ``sum d_a de``), each
        counted from the first sample (a new array)."""
        return np.array(self._moments).reshape(-1, 5)

    def begin(self, sim: Simulation) -> None:
        """Start the moments and take the first sample at the run's start, or go on
        from the last sample of an earlier run.

        Parameters
        ----------
        sim : Simulation

        Raises
        ------
        ValueError
            For a system without transport coefficients (walls, fields, a
            thermostat, inelastic disks, a moving centre of mass), or a second run
            that does not start at the last sample, or with another simulation.
        """
        _check_equilibrium(sim)
        state = sim._state
        if self._sim is not None:
            if sim is not self._sim:
                raise ValueError("this Transport samples another simulation")
            if state.edits != self._edits:
                raise ValueError("the positions or velocities were set since this "
                                 "Transport's last sample: start a new one")
            if abs(sim.time - self._time) > 1e-12 * max(1.0, abs(self._time)):
                raise ValueError(f"this Transport stopped at t={self._time!r}; a run "
                                 f"starting at t={sim.time!r} cannot go on with it")
        if state.helfand_sums is None:
            # The flights before now are taken off in advance (the engine adds each
            # disk's flight from its last move), so the trajectory is untouched.
            state.helfand_sums = np.zeros(_helfand.N_HELFAND)
            state.helfand_sums[:_helfand.H_CX] = -_helfand.pending(state.time, state.S,
                                                                   state.invm)
        if self._sim is not None:
            self._base = self._moments[-1] - state.helfand_moments()
            return
        self._sim = sim
        species = np.ascontiguousarray(sim.species, dtype=np.int64)
        self._species = species
        kinds = int(species.max()) + 1
        self._per_species = np.bincount(species, minlength=kinds).astype(float)
        mass, rad = sim.masses, sim.radii
        area = sim.box.width * sim.box.height
        self._meta = dict(
            n=sim.n, area=area, density=sim.n / area,
            packing_fraction=float(np.pi * np.sum(rad * rad) / area),
            # (Species labels alone make no mixture: equal disks have one heat flux.)
            mixture=bool(np.ptp(mass) > 0 or np.ptp(rad) > 0))
        self._base = -state.helfand_moments()
        lags = self.lags
        self._ring_r = np.empty((lags + 1, sim.n, 2))
        self._ring_v = np.empty((lags + 1, sim.n, 2))
        self._sample(sim)

    def __call__(self, sim: Simulation) -> None:
        """Take a sample.

        Parameters
        ----------
        sim : Simulation
        """
        self._sample(sim)

    def close(self) -> None:
        """Stop the engine's moments (the run is over)."""
        if self._sim is not None:
            self._sim._state.helfand_sums = None

    def _sample(self, sim: Simulation) -> None:
        assert self._ring_r is not None and self._ring_v is not None
        state = sim._state
        s = len(self._moments)
        moments = state.helfand_moments() + self._base
        lags = self.lags
        r = sim.unwrapped_positions
        v = sim.velocities
        slot = s % (lags + 1)
        self._ring_r[slot] = r
        self._ring_v[slot] = v
        # Every origin o = s - k (k = 0 .. lags) that has a sample adds its window k.
        assert self._species is not None and self._per_species is not None
        ks = np.arange(min(s, lags) + 1)
        sq_s, vv_s = _windows(s, lags, self._ring_r, self._ring_v, r, v, self._species,
                              len(self._per_species))
        blocks = (s - ks) // self.per_block
        for b in np.unique(blocks):
            while len(self._msd) <= b:
                self._msd.append(np.zeros((lags + 1, len(self._per_species))))
                self._vv.append(np.zeros((lags + 1, len(self._per_species))))
                self._count.append(np.zeros(lags + 1))
            sel = blocks == b
            self._msd[b][ks[sel]] += sq_s[sel]
            self._vv[b][ks[sel]] += vv_s[sel]
            self._count[b][ks[sel]] += 1.0
        # (Last: a sample counts, and a later run may go on from it, once it is whole.)
        self._temperatures.append(kinetic_temperature(sim))
        self._moments.append(moments)
        self._time = sim.time
        self._edits = state.edits

    def result(self) -> TransportCoefficients:
        """The coefficients over the complete blocks so far.

        Returns
        -------
        TransportCoefficients

        Raises
        ------
        ValueError
            Before a first block is complete (the run is shorter than ``block +
            window``).
        """
        lags, per = self.lags, self.per_block
        samples = len(self._moments)
        # A block b is complete once its last origin (b + 1) per - 1 has its longest
        # window: (b + 1) per - 1 + lags <= samples - 1.
        complete = max((samples - lags) // per, 0)
        if self.max_blocks is not None:
            complete = min(complete, self.max_blocks)
        if complete < 1:
            raise ValueError(
                f"no complete block yet: a block needs {per * self.dt:g} of time origins "
                f"and then the window {lags * self.dt:g} (sampled up to "
                f"{(samples - 1) * self.dt:g})")
        meta = self._meta
        dt = self.dt
        tau = dt * np.arange(1, lags + 1)
        G = np.array(self._moments)
        duration = (samples - 1) * dt
        # (Constant in an elastic run, to rounding; the mean of the samples.)
        area, kt = meta["area"], float(np.mean(self._temperatures))
        # The mean pressure: the trace of the momentum flux's integral over the run.
        pressure = float((G[-1, 0] + G[-1, 1] - G[0, 0] - G[0, 1]) / (2.0 * area * duration))
        lo, hi = self._fitted
        shear = np.empty((complete, lags))
        bulk = np.empty((complete, lags))
        heat = np.empty((complete, lags))
        for b in range(complete):
            origins = np.arange(b * per, (b + 1) * per)
            for k in range(1, lags + 1):
                dG = G[origins + k] - G[origins]
                off = 0.5 * (dG[:, 0] - dG[:, 1])
                shear[b, k - 1] = 0.5 * np.mean(dG[:, 2] ** 2 + off ** 2)
                trace = 0.5 * (dG[:, 0] + dG[:, 1]) - area * pressure * k * dt
                bulk[b, k - 1] = np.mean(trace ** 2)
                heat[b, k - 1] = 0.5 * np.mean(dG[:, 3] ** 2 + dG[:, 4] ** 2)
        # The mean pressure is that of the same run: over a window tau it takes out
        # tau / duration of the moment's variance, exactly for a random walk.
        bulk /= 1.0 - tau / duration
        per_species = self._per_species
        assert per_species is not None  # (set with the first sample)
        with np.errstate(invalid="ignore", divide="ignore"):  # (labels without disks: nan)
            msd = np.array([self._msd[b][1:] / self._count[b][1:, None]
                            for b in range(complete)]) / per_species[None, None, :]
            vv = np.array([self._vv[b] / self._count[b][:, None]
                           for b in range(complete)]) / (2.0 * per_species[None, None, :])

        def slope(m):  # (blocks, lags) -> (blocks,): fitted over windows lo .. hi
            x = tau[lo - 1:hi]
            y = m[:, lo - 1:hi]
            xc = x - x.mean()
            return (y - y.mean(axis=1, keepdims=True)) @ xc / (xc @ xc)

        def stats(values):
            mean = values.mean(axis=0)
            if len(values) < 2:
                return mean, np.full_like(mean, np.nan)
            return mean, values.std(axis=0, ddof=1) / math.sqrt(len(values))

        def coefficient(m, scale):
            value, error = stats(slope(m) / scale)
            curve, curve_error = stats(m / (scale * tau))
            return float(value), float(error), curve, curve_error

        eta = coefficient(shear, 2.0 * area * kt)
        zeta = coefficient(bulk, 2.0 * area * kt)
        lam = coefficient(heat, 2.0 * area * kt * kt)
        if meta["mixture"]:
            lam = (math.nan, math.nan, np.full(lags, np.nan), np.full(lags, np.nan))
        # D per species: the slope of the MSD, over 4.
        d_slope = np.stack([slope(msd[:, :, s]) for s in range(msd.shape[2])], axis=1) / 4.0
        d, d_err = stats(d_slope)
        d_curve, d_curve_err = stats(msd / (4.0 * tau[None, :, None]))
        vacf, vacf_err = stats(vv)
        return TransportCoefficients(
            n=meta["n"], area=area, density=meta["density"],
            packing_fraction=meta["packing_fraction"], temperature=kt,
            pressure=pressure, duration=duration, dt=dt, blocks=complete,
            fit=self.fit, times=tau,
            shear_viscosity=eta[0], shear_viscosity_error=eta[1],
            shear_viscosity_curve=eta[2], shear_viscosity_curve_error=eta[3],
            bulk_viscosity=zeta[0], bulk_viscosity_error=zeta[1],
            bulk_viscosity_curve=zeta[2], bulk_viscosity_curve_error=zeta[3],
            thermal_conductivity=lam[0], thermal_conductivity_error=lam[1],
            thermal_conductivity_curve=lam[2], thermal_conductivity_curve_error=lam[3],
            diffusion=d, diffusion_error=d_err, diffusion_curve=d_curve,
            diffusion_curve_error=d_curve_err,
            vacf_times=dt * np.arange(lags + 1), vacf=vacf, vacf_error=vacf_err)



@njit
def _windows(s, lags, ring_r, ring_v, r, v, species, kinds):
    """For sample ``s`` (centres ``r``, velocities ``v``) and each earlier sample ``s -
    k`` still in the rings (``k = 0 .. min(s, lags)``, ring slot ``(s - k) % (lags +
    1)``), the squared displacements and the products ``v(s - k) . v(s)`` summed over
    the disks of each species: two arrays ``(min(s, lags) + 1, kinds)``.  (One pass
    over the rings, reading each once: the cost of a sample is this memory traffic.)"""
    top = min(s, lags)
    sq = np.zeros((top + 1, kinds))
    vv = np.zeros((top + 1, kinds))
    for k in range(top + 1):
        slot = (s - k) % (lags + 1)
        for i in range(r.shape[0]):
            dx = r[i, 0] - ring_r[slot, i, 0]
            dy = r[i, 1] - ring_r[slot, i, 1]
            c = species[i]
            sq[k, c] += dx * dx + dy * dy
            vv[k, c] += ring_v[slot, i, 0] * v[i, 0] + ring_v[slot, i, 1] * v[i, 1]
    return sq, vv


def _fit(fit) -> tuple[float, float]:
    """``fit`` checked: two fractions ``0 <= lo < hi <= 1``."""
    try:
        lo, hi = (float(f) for f in fit)
    except (TypeError, ValueError):
        raise ValueError(f"fit={fit!r} must be two fractions (lo, hi) of the window") from None
    if not 0.0 <= lo < hi <= 1.0:
        raise ValueError(f"fit={fit!r} must be two fractions 0 <= lo < hi <= 1 of the window")
    return lo, hi


def _fitted(fit: tuple[float, float], lags: int, window: float) -> tuple[int, int]:
    """The first and last window (in samples, from 1) of the slopes' fit: at least
    two."""
    lo, hi = max(round(fit[0] * lags), 1), round(fit[1] * lags)
    if hi - lo < 1:
        raise ValueError(f"fit={fit!r} of window={window!r} ({lags} windows of dt) leaves "
                         f"fewer than two windows to fit a slope to: widen fit, or take "
                         f"a longer window or a shorter dt")
    return lo, hi


def transport(sim: Simulation, duration: float, *, dt: float, window: float,
              blocks: int = 10, fit: tuple[float, float] = (0.5, 1.0),
              progress: _progress.ProgressArg = False) -> TransportCoefficients:
    """Run ``sim`` for ``duration`` and measure its transport coefficients (see the
    module notes and :class:`~edmd2d.transport.Transport`).

    The time origins are cut into ``blocks`` blocks of ``(duration + dt - window) /
    blocks`` each, rounded down to whole samples.

    Parameters
    ----------
    sim : Simulation
        An elastic gas in a periodic box, at rest as a whole (advanced in place).
    duration : float
        The simulated time to run, a whole multiple of ``dt``.
    dt : float
        The time between samples, > 0.
    window : float
        The longest time window, a whole multiple of ``dt`` and at most
        ``(duration - window) / blocks`` (each block holds that many origins).
    blocks : int, default 10
        >= 1 (>= 2 for errors).
    fit : (float, float), default (0.5, 1.0)
        The windows the slopes are fitted over, as fractions of ``window``.
    progress : bool or tqdm, default False
        A progress bar of the simulated time (see :mod:`edmd2d.progress`).

    Returns
    -------
    TransportCoefficients

    Raises
    ------
    ValueError
        For bad arguments, a window longer than a block allows, or a system without
        transport coefficients.

    Examples
    --------
    >>> import edmd2d as ed
    >>> from edmd2d.transport import transport
    >>> c = transport(ed.make_gas(400, 0.3, seed=1), 21.0, dt=0.1, window=1.0, blocks=4)
    >>> c.blocks, c.shear_viscosity > 0, c.diffusion.shape
    (4, True, (1,))
    """
    duration = as_positive_float("duration", duration)
    dt = as_positive_float("dt", dt)
    window = as_positive_float("window", window)
    blocks = as_count("blocks", blocks, minimum=1)
    lags = _whole("window", window, dt)
    steps = _whole("duration", duration, dt)
    # (steps + 1 samples: origins 0 .. steps - lags have their longest window.)
    per = (steps + 1 - lags) // blocks
    if per < lags:
        raise ValueError(
            f"window={window!r} is too long for duration={duration!r} in {blocks} blocks: "
            f"each block's origins must span at least the window (at most "
            f"window = duration / (blocks + 1) = {duration / (blocks + 1):.6g})")
    op = Transport(dt=dt, window=window, block=per * dt, fit=fit, blocks=blocks)
    bar, owned = _progress.bar(progress, total=duration, unit="time", desc="transport")
    try:
        run(sim, until=sim.time + steps * dt, operations=[op],
            progress=bar if bar is not None else False)
    finally:
        if owned:
            bar.close()
    return op.result()
