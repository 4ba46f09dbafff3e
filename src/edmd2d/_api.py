"""The public surface of the package, as the documentation and its tests see it."""

from __future__ import annotations

import importlib
import inspect
import pkgutil


def public_modules(package: str = "edmd2d") -> list[str]:
    """Every module of ``package`` whose dotted name has no part starting with ``_``."""
    root = importlib.import_module(package)
    names = [package]
    for info in pkgutil.walk_packages(root.__path__, prefix=package + "."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return sorted(names)


def public_names(module) -> list[str]:
    """The module's ``__all__``, or else its own public functions and classes."""
    if hasattr(module, "__all__"):
        return list(module.__all__)
    return [name for name, obj in vars(module).items()
            if not name.startswith("_") and (inspect.isfunction(obj) or inspect.isclass(obj))
            and obj.__module__ == module.__name__]
