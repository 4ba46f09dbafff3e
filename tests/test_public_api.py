"""The public surface, names and signatures, against a committed snapshot.

Every name in ``__all__`` of every public module, with the signature of each function,
class and method, is listed in ``tests/public_api.txt``.  A change to the public surface
must be deliberate: make it, list it in ``CHANGELOG.md``, and write the snapshot anew
with ``python tests/test_public_api.py``.
"""

from __future__ import annotations

import importlib
import inspect
import sys
from pathlib import Path

SNAPSHOT = Path(__file__).with_name("public_api.txt")


def _signature(obj) -> str:
    """The parameters, their kinds and defaults; annotations are left out (how Python
    shows them differs between versions, and they are not what a caller passes)."""
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return "(...)"
    plain = [p.replace(annotation=inspect.Parameter.empty) for p in sig.parameters.values()]
    return str(sig.replace(parameters=plain, return_annotation=inspect.Signature.empty))


def surface() -> list[str]:
    """One line per public name: ``module.name kind signature``, and the public methods
    and properties of each class."""
    from edmd2d._api import public_modules, public_names

    lines = []
    for module_name in public_modules():
        module = importlib.import_module(module_name)
        for name in public_names(module):
            obj = getattr(module, name)
            where = f"{module_name}.{name}"
            if inspect.isclass(obj):
                lines.append(f"{where} class{_signature(obj)}")
                for attr, member in sorted(vars(obj).items()):
                    if attr.startswith("_") and attr != "__init__":
                        continue
                    if isinstance(member, property):
                        lines.append(f"{where}.{attr} property")
                    elif isinstance(member, (classmethod, staticmethod)):
                        lines.append(f"{where}.{attr} {type(member).__name__}"
                                     f"{_signature(member.__func__)}")
                    elif inspect.isfunction(member) and attr != "__init__":
                        lines.append(f"{where}.{attr} method{_signature(member)}")
            elif inspect.isfunction(obj):
                lines.append(f"{where} function{_signature(obj)}")
            elif inspect.ismodule(obj):
                lines.append(f"{where} module")
            else:
                lines.append(f"{where} {type(obj).__name__}")
    return lines


def test_the_public_surface_is_the_snapshot():
    now = surface()
    saved = SNAPSHOT.read_text().splitlines()
    gone = sorted(set(saved) - set(now))
    new = sorted(set(now) - set(saved))
    assert not gone and not new, (
        "the public surface changed; if that is meant, list it in CHANGELOG.md and run "
        "`python tests/test_public_api.py` to write the snapshot anew.\n"
        + "".join(f"- {line}\n" for line in gone) + "".join(f"+ {line}\n" for line in new))


if __name__ == "__main__":
    SNAPSHOT.write_text("\n".join(surface()) + "\n")
    sys.exit(0)
