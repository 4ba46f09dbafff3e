"""The package's modules import one another downward only.

Each module sits in a layer (below); it may import modules of its own layer or of the
layers below, never above, the imports between modules of one layer form no circle,
and every import of the package's own modules is at the top of its file (an import
inside a function would hide a circle from Python until that function first runs).
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import edmd2d

ROOT = Path(edmd2d.__file__).parent

# Lower layers first.  A new module gets a layer here; a module that needs one above
# its own is a sign that something is in the wrong place.
LAYERS = [
    # foundations: no simulation in sight
    {"_version", "_jit", "_validate", "_sums", "_atomic", "_api", "_jsonable", "_facade",
     "_measurement",
     "progress", "_compile_notice", "theory", "geometry", "_engine", "_gaps", "_balance",
     "_impacts"},
    # what the simulation is built from, and what reads a simulation through its
    # public state only
    {"models", "physics", "_placement", "_operations", "reference", "_checks",
     "_state"},
    {"measurements"},
    {"simulation"},
    {"analysis", "compress", "checkpoint", "io", "transport"},
    {"contacts"},
    {"builders"},
    {"operations", "viz", "config", "_runs"},
    {"ensemble"},
    {"cli", "__main__", "__init__"},
]


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts)


def _layer_of(name: str) -> int:
    top = name.split(".")[0]
    for k, layer in enumerate(LAYERS):
        if top in layer:
            return k
    raise AssertionError(f"module edmd2d.{name} has no layer in tests/test_layering.py")


def _resolve(module: str, node: ast.ImportFrom | ast.Import) -> list[str]:
    """The package's modules an import statement in ``module`` refers to."""
    out = []
    if isinstance(node, ast.Import):
        for alias in node.names:
            if alias.name == "edmd2d" or alias.name.startswith("edmd2d."):
                out.append(alias.name.removeprefix("edmd2d").lstrip("."))
        return [m for m in out if m]
    if node.level == 0:
        if not (node.module or "").startswith("edmd2d"):
            return []
        base = node.module.removeprefix("edmd2d").lstrip(".").split(".")
        base = [p for p in base if p]
    else:
        package = module.split(".")
        if not (ROOT / Path(*package)).is_dir():  # (a module: its package is the parent)
            package = package[:-1]
        base = package[:len(package) - (node.level - 1)] + (
            node.module.split(".") if node.module else [])
    for alias in node.names:
        candidate = ".".join([*base, alias.name])
        if (ROOT / Path(*candidate.split("."))).with_suffix(".py").exists() or \
                (ROOT / Path(*candidate.split("."))).is_dir():
            out.append(candidate)
        elif base:
            out.append(".".join(base))
    return out


@functools.lru_cache(maxsize=1)
def _imports():
    """``{module: (top-level imports, [(line, import) inside functions])}``."""
    found = {}
    for path in sorted(ROOT.rglob("*.py")):
        name = _module_name(path)
        tree = ast.parse(path.read_text(), str(path))
        top, local = set(), []
        for node in tree.body:
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                top.update(_resolve(name, node))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                for sub in ast.walk(node):
                    if isinstance(sub, (ast.Import, ast.ImportFrom)):
                        local.extend((sub.lineno, m) for m in _resolve(name, sub))
        top.discard(name)
        found[name] = (top, local)
    return found


def _upward(imports: dict) -> list[str]:
    """Each import of a module in a higher layer, as a sentence."""
    wrong = []
    for name, (top, _) in imports.items():
        mine = _layer_of(name)
        for other in sorted(top):
            if _layer_of(other) > mine and not name.startswith(other + "."):
                wrong.append(f"edmd2d.{name} (layer {mine}) imports edmd2d.{other} "
                             f"(layer {_layer_of(other)})")
    return wrong


def _circle(imports: dict) -> list[str]:
    """One import circle among ``imports`` (its modules in order), or ``[]``."""
    graph = {name: sorted(m for m in top if m in imports) for name, (top, _) in
             imports.items()}
    state: dict[str, int] = {}  # 1: on the current path, 2: done

    def visit(node, path):
        state[node] = 1
        for nxt in graph[node]:
            if state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt, [*path, nxt])
                if found:
                    return found
        state[node] = 2
        return []

    for node in sorted(graph):
        if node not in state:
            found = visit(node, [node])
            if found:
                return found
    return []


def test_every_module_has_a_layer_and_imports_downward():
    wrong = _upward(_imports())
    assert not wrong, "\n".join(wrong)


def test_no_import_circle():
    circle = _circle(_imports())
    assert not circle, "import circle: " + " -> ".join(circle)


def test_the_package_imports_its_own_modules_at_the_top_of_each_file():
    local = [f"edmd2d/{name.replace('.', '/')}.py:{line} imports edmd2d.{other}"
             for name, (_, found) in _imports().items() for line, other in found]
    assert not local, "\n".join(local)


def test_the_checks_find_a_circle_and_an_upward_import():
    # (The same rules on made-up imports: the checks above can fail.)
    made_up = {"simulation": ({"operations"}, []), "operations": ({"measurements"}, []),
               "measurements": ({"simulation"}, []), "geometry": (set(), [])}
    assert _circle(made_up) == ["measurements", "simulation", "operations", "measurements"]
    assert sorted(_upward(made_up)) == [
        "edmd2d.measurements (layer 2) imports edmd2d.simulation (layer 3)",
        "edmd2d.simulation (layer 3) imports edmd2d.operations (layer 7)"]
    tree = ast.parse("from . import simulation\nfrom .io import gsd\n"
                     "from ..geometry import Box\nfrom ._engine.layout import X\n")
    assert _resolve("measurements", tree.body[0]) == ["simulation"]
    assert _resolve("measurements", tree.body[1]) == ["io.gsd"]
    assert _resolve("io.gsd", tree.body[2]) == ["geometry"]
    assert _resolve("simulation", tree.body[3]) == ["_engine.layout"]
