"""The type of :class:`edmd2d.Simulation` as the modules below it see it.

``Simulation`` uses the measurements and the run driver, so those modules cannot
import ``simulation``; they recognise a simulation by this base class instead, which
``Simulation`` is the one subclass of.
"""

from __future__ import annotations


class SimulationBase:
    """What a function that takes an ``edmd2d.Simulation`` checks its argument against."""

    __slots__ = ()


def require_simulation(sim, caller: str) -> None:
    """Raise ``TypeError`` naming ``caller`` unless ``sim`` is an ``edmd2d.Simulation``."""
    if not isinstance(sim, SimulationBase):
        raise TypeError(f"{caller} needs an edmd2d.Simulation, got {type(sim).__name__}")
