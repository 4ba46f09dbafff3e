"""The command line shared by the gallery's examples.

Each example keeps its settings as module constants (``N``, ``DURATION``, ``SEED``...);
this parser takes the output path and lets the common ones be changed from the shell,
for a quicker or smaller run::

    python examples/gas_in_a_box.py --n 100 --duration 4 /tmp/small.gif
"""

from __future__ import annotations

import argparse
from pathlib import Path

# (option, constant, type, help)
_OPTIONS = (
    ("--n", "N", int, "number of disks"),
    ("--duration", "DURATION", float, "simulated time"),
    ("--seed", "SEED", int, "random seed"),
)


def run(module_globals: dict, default_name: str) -> None:
    """Parse the command line of the example whose globals are ``module_globals``,
    set the constants it names, and call its ``main(out)``."""
    doc = module_globals["__doc__"]
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    default = Path(module_globals["__file__"]).parent / "output" / default_name
    parser.add_argument("out", nargs="?", type=Path, default=default,
                        help=f"the file to write (its suffix picks the format; default "
                             f"{default})")
    for option, constant, kind, text in _OPTIONS:
        if constant in module_globals:
            parser.add_argument(option, type=kind, default=None,
                                help=f"{text} (default {module_globals[constant]})")
    args = parser.parse_args()
    for option, constant, _, _ in _OPTIONS:
        value = getattr(args, option[2:], None)
        if constant in module_globals and value is not None:
            if value <= 0:
                parser.error(f"{option} must be positive, got {value}")
            module_globals[constant] = value
    module_globals["main"](args.out)
