"""edmd2d: exact event-driven simulation of many hard disks in two dimensions.

>>> import edmd2d as ed
>>> box = ed.Box(10.0, 10.0, periodic=True)
>>> sim = ed.Simulation([[2.0, 5.0], [8.0, 5.0]], [[1.0, 0.0], [0.0, 0.0]], radii=0.5, box=box)
>>> sim.advance(until=10.0).counts.collisions
1
"""

# (_compile_notice says on standard error when the engine is being compiled)
from . import _compile_notice, checkpoint, models, operations, theory, transport  # noqa: F401
from ._version import __version__  # noqa: F401
from .analysis import (
    angular_velocity_distribution,
    hexatic_order,
    local_packing_fractions,
    maxwell_boltzmann_test,
    mean_squared_displacement,
    radial_distribution,
    speed_distribution,
    trajectory,
    voronoi_cell_areas,
)
from .builders import lattice_packing_limit, make_gas, random_gas, random_packing
from .compress import Compression, compress, packing_fraction
from .contacts import ContactNetwork, contact_network, contact_tolerance
from .geometry import Box, Oscillation, Translation, Wall
from .measurements import (
    Cooling,
    Measurement,
    cooling,
    kinetic_temperature,
    measure,
    rotational_temperature,
)
from .simulation import Counts, Simulation

__all__ = [
    "Box", "Wall", "Translation", "Oscillation", "Simulation", "Counts", "make_gas",
    "lattice_packing_limit",
    "measure", "Measurement", "kinetic_temperature", "rotational_temperature", "cooling",
    "Cooling", "models",
    "radial_distribution", "speed_distribution", "maxwell_boltzmann_test",
    "angular_velocity_distribution",
    "trajectory", "mean_squared_displacement", "hexatic_order",
    "theory", "checkpoint", "operations", "transport",
    "random_packing", "contact_network", "contact_tolerance", "ContactNetwork",
    "random_gas", "compress", "Compression", "packing_fraction",
    "voronoi_cell_areas", "local_packing_fractions",
]


def __getattr__(name: str):
    # ``edmd2d.viz`` is loaded on first use, so that ``import edmd2d`` never imports
    # matplotlib (an optional dependency).
    if name == "viz":
        import importlib

        return importlib.import_module(".viz", __name__)
    raise AttributeError(f"module 'edmd2d' has no attribute {name!r}")
