"""Every public function, class, method and property has a complete numpy-style docstring.

Public: the names of each public module's ``__all__`` (a public module is one whose
dotted name has no part starting with ``_``; ``edmd2d.__all__`` among them), and the
methods and properties that a public class defines itself.  Each must have a
docstring that numpydoc parses without complaint, with

- a ``Parameters`` section if it takes parameters (other than ``self``/``cls``; a
  class: those of its constructor, which a dataclass may document as ``Attributes``),
  naming every parameter of the signature and no other;
- a ``Returns`` (or ``Yields``) section if it returns (or yields) a value, judged
  from its source: a ``return`` with a value other than ``None``.  Classes and
  properties need none.

The same rule decides what the API reference must cover (``docs/_ext/edmd2d_docs.py``).
"""

from __future__ import annotations

import ast
import dataclasses
import importlib
import importlib.util
import inspect
import textwrap
import warnings

import pytest
from numpydoc.docscrape import NumpyDocString  # (numpydoc: in the test extra)

import edmd2d
from edmd2d._api import public_modules, public_names

# Docstrings that fail the rules, in files whose owners are changing them; each entry
# makes its test an expected failure (strict: a test that starts passing fails, so that
# the entry is removed).
KNOWN_FAILURES: dict[str, str] = {
}


def public_objects() -> dict[str, tuple[object, str]]:
    """``{qualified name: (object, kind)}``, kind ``function``, ``method``, ``class`` or
    ``property``, each object once under the name of its defining module."""
    found: dict[str, tuple[object, str]] = {}
    for modname in public_modules():
        module = importlib.import_module(modname)
        for name in public_names(module):
            obj = getattr(module, name)
            if not (inspect.isclass(obj) or inspect.isfunction(obj)):
                continue  # modules and constants
            qualified = f"{obj.__module__}.{obj.__qualname__}"
            if inspect.isfunction(obj):
                found[qualified] = (obj, "function")
                continue
            found[qualified] = (obj, "class")
            for member, attr in vars(obj).items():
                if member.startswith("_"):
                    continue
                if isinstance(attr, property):
                    found[f"{qualified}.{member}"] = (attr, "property")
                elif isinstance(attr, staticmethod):
                    found[f"{qualified}.{member}"] = (getattr(obj, member), "function")
                elif isinstance(attr, classmethod) or inspect.isfunction(attr):
                    found[f"{qualified}.{member}"] = (getattr(obj, member), "method")
    return found


def _signature_parameters(obj, skip_self: bool) -> list[str]:
    try:
        params = list(inspect.signature(obj).parameters)
    except (TypeError, ValueError):
        return []
    if skip_self and params and params[0] in ("self", "cls"):
        params = params[1:]
    return params


def _constructor_parameters(cls) -> tuple[list[str], bool]:
    """The constructor's parameters, and whether the class is a record (a dataclass or
    named tuple, whose fields may be documented as ``Attributes``)."""
    record = dataclasses.is_dataclass(cls) or (issubclass(cls, tuple)
                                               and hasattr(cls, "_fields"))
    own = any(("__init__" in vars(base) or "__new__" in vars(base))
              for base in cls.__mro__ if base.__module__.startswith("edmd2d"))
    if not (own or record):
        return [], record  # the constructor of object, Exception, ...: nothing to say
    return _signature_parameters(cls, False), record


def _returns_value(func) -> tuple[bool, bool]:
    """Whether the source of ``func`` returns a value, and whether it yields."""
    try:
        source = textwrap.dedent(inspect.getsource(func))
    except (OSError, TypeError):
        return False, False
    body = ast.parse(source).body[0].body
    returns = yields = False
    stack = list(body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef,
                             ast.Lambda)):
            continue  # a nested function's returns are its own
        if isinstance(node, ast.Return) and node.value is not None and not (
                isinstance(node.value, ast.Constant) and node.value.value is None):
            returns = True
        if isinstance(node, (ast.Yield, ast.YieldFrom)):
            yields = True
        stack.extend(ast.iter_child_nodes(node))
    return returns, yields


def _names(section) -> list[str]:
    """The names of a parameter list; ``x, y : float`` documents both, ``**kwargs``
    documents ``kwargs``."""
    return [part.strip().lstrip("*") for item in section for part in item.name.split(",")
            if part.strip()]


def problems(obj, kind: str) -> list[str]:
    """What is wrong with the docstring of ``obj`` (empty if nothing)."""
    # (A method that overrides one of a base class may inherit its docstring, as the
    # API reference shows it.)
    raw = inspect.getdoc(obj)
    if not raw or not raw.strip():
        return ["no docstring"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        doc = NumpyDocString(raw)
    found = [f"numpydoc: {w.message}" for w in caught]
    if kind == "property":
        return found
    documented = _names(doc["Parameters"]) + _names(doc["Other Parameters"])
    record = False
    if kind == "class":
        params, record = _constructor_parameters(obj)
    else:
        params = _signature_parameters(obj, kind == "method")
    accepted = documented + (_names(doc["Attributes"]) if record else [])
    missing = [p for p in params if p not in accepted]
    if params and not accepted:
        found.append(f"no Parameters section (takes {', '.join(params)})")
    elif missing:
        found.append(f"parameters not documented: {', '.join(missing)}")
    unknown = [p for p in documented if p not in params]
    if unknown:
        found.append(f"documented parameters not in the signature: {', '.join(unknown)}")
    if kind in ("function", "method"):
        returns, yields = _returns_value(obj)
        if yields and not (doc["Yields"] or doc["Returns"]):
            found.append("no Yields section")
        elif returns and not (doc["Returns"] or doc["Yields"]):
            found.append("no Returns section")
    return found


OBJECTS = public_objects()


def _cases():
    for name in sorted(OBJECTS):
        if name in KNOWN_FAILURES:
            yield pytest.param(name, id=name, marks=pytest.mark.xfail(
                strict=True, reason=KNOWN_FAILURES[name]))
        else:
            yield pytest.param(name, id=name)


@pytest.mark.parametrize("name", list(_cases()))
def test_public_docstring_is_complete(name):
    obj, kind = OBJECTS[name]
    assert problems(obj, kind) == []


def test_known_failures_name_public_objects():
    assert sorted(set(KNOWN_FAILURES) - set(OBJECTS)) == []


def test_every_name_of_the_package_is_checked():
    for name in edmd2d.__all__:
        obj = getattr(edmd2d, name)
        if inspect.isclass(obj) or inspect.isfunction(obj):
            assert f"{obj.__module__}.{obj.__qualname__}" in OBJECTS


@pytest.mark.parametrize("source, kind, expected", [
    ('''def f(a, b):
        """Sum.

        Parameters
        ----------
        a : int
            One.
        c : int
            Not there.

        Returns
        -------
        int
        """
        return a + b''', "function",
     ["parameters not documented: b", "documented parameters not in the signature: c"]),
    ('''def f(a):
        """No sections."""
        return a''', "function",
     ["no Parameters section (takes a)", "no Returns section"]),
    ('''def f():
        """Yields without saying so."""
        yield 1''', "function", ["no Yields section"]),
    ('''def f(*args, **kwargs):
        """Pass-through.

        Parameters
        ----------
        *args, **kwargs
            Handed on.
        """
        print(args, kwargs)''', "function", []),
])
def test_the_rules_on_small_cases(source, kind, expected, tmp_path):
    # The function is written to a file, so that inspect finds its source.
    path = tmp_path / "case.py"
    path.write_text(source + "\n")
    spec = importlib.util.spec_from_file_location("case", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert problems(module.f, kind) == expected
