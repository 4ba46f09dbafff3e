"""Sphinx extension of the edmd2d documentation: code that runs while the site is built.

Directives
----------
``runcode``
    Shows a block of Python, runs it, and shows what it printed, the matplotlib figures
    it left open and the image files it wrote (``.png``, ``.gif``, ...).  The blocks of
    one page share one namespace and run in order, in a working directory of their own
    under the build's doctree directory, so that the code reads as a user would type it
    (``viz.save(anim, "gas.gif")``).  Option ``:no-figures:`` closes the open figures
    without showing them (an animation's figure, say).

``example``
    A page of the gallery: runs one script of ``examples/`` as its command line would
    (``python examples/NAME.py ARGS OUT``), in the build process, and shows its
    docstring, the command, what it printed, the images it wrote and its source.
    ``:args:`` are the small settings used when the gallery is built in its default
    quick mode; ``:output:`` names the file the script is told to write (its suffix
    picks the format).  The environment variable ``EDMD2D_DOCS_GALLERY`` chooses the
    mode: ``quick`` (default), ``full`` (the scripts' own settings, without ``:args:``),
    or ``off`` (nothing is run; the pages say so).

Any exception, or a non-zero exit, in the code run is a Sphinx warning at the line of the
directive, so that a build with ``-W`` fails on it.

References and checks
---------------------
Python references to a name of ``edmd2d.__all__`` (``:class:`edmd2d.Simulation```, or
``Simulation.run`` in any docstring) are resolved to the object documented in its
defining module (``edmd2d.simulation.Simulation``).  Markdown links from a page to a
file outside ``docs/`` (the ``docs/*.md`` pages link to ``benchmarks/README.md``, for
readers of the repository) are sent to the page that covers that file
(``edmd2d_outside_links``).

After all pages are read, every public module (every module of the package whose
dotted name has no part starting with ``_``), every public name of each (its
``__all__``) and every public method and property of each public class must be
documented somewhere, and every script of ``examples/`` must have a gallery page; each
one missing is a warning.
"""

from __future__ import annotations

import ast
import contextlib
import importlib
import inspect
import io
import os
import re
import runpy
import shlex
import sys
import time
import traceback
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

from edmd2d._api import public_modules, public_names

logger = logging.getLogger(__name__)

IMAGE_SUFFIXES = (".gif", ".png", ".jpg", ".jpeg", ".svg")
GALLERY_MODES = ("quick", "full", "off")


# ------------------------------------------------------------------------ running code
def _image_files(folder: Path) -> dict[Path, int]:
    return {p: p.stat().st_mtime_ns for p in folder.iterdir()
            if p.suffix.lower() in IMAGE_SUFFIXES}


@contextlib.contextmanager
def _inside(folder: Path, argv: list[str] | None = None, path: str | None = None):
    """Run with ``folder`` as the working directory (and ``sys.argv``, ``sys.path``)."""
    old_cwd, old_argv, old_path = os.getcwd(), sys.argv, list(sys.path)
    os.chdir(folder)
    if argv is not None:
        sys.argv = argv
    if path is not None:
        sys.path.insert(0, path)
    try:
        yield
    finally:
        os.chdir(old_cwd)
        sys.argv = old_argv
        sys.path[:] = old_path


def _run(code, namespace: dict, folder: Path, *, argv=None, path=None):
    """Run ``code`` (a compiled block, or a script's path) and capture what it prints.

    Returns ``(stdout, stderr, error)``; ``error`` is the formatted traceback, or
    ``None``.  ``SystemExit`` with code 0 or ``None`` is a normal end."""
    out, err = io.StringIO(), io.StringIO()
    error = None
    with _inside(folder, argv, path), contextlib.redirect_stdout(out), \
            contextlib.redirect_stderr(err):
        try:
            if isinstance(code, str):
                runpy.run_path(code, run_name="__main__")
            else:
                exec(code, namespace)
        except SystemExit as stop:
            if stop.code not in (0, None):
                error = f"SystemExit: {stop.code}"
        except BaseException:  # noqa: BLE001 - reported as a build warning
            error = traceback.format_exc()
    return out.getvalue(), err.getvalue(), error


def _close_figures(folder: Path | None, prefix: str) -> list[Path]:
    """Save (unless ``folder`` is None) and close every open matplotlib figure."""
    if "matplotlib.pyplot" not in sys.modules:
        return []
    import matplotlib.pyplot as plt

    saved = []
    for k, num in enumerate(plt.get_fignums()):
        fig = plt.figure(num)
        if folder is not None:
            path = folder / f"{prefix}-figure-{k}.png"
            fig.savefig(path, dpi=100, bbox_inches="tight")
            saved.append(path)
        plt.close(fig)
    return saved


class _Executing(SphinxDirective):
    """What both directives share: the working folder, images and literal blocks."""

    def workdir(self, *parts: str) -> Path:
        folder = Path(self.env.doctreedir, "_executed", self.env.docname, *parts)
        folder.mkdir(parents=True, exist_ok=True)
        return folder

    def image(self, path: Path, alt: str) -> nodes.image:
        # Image URIs are relative to the page's source folder; Sphinx copies the files.
        here = Path(self.env.doc2path(self.env.docname)).parent
        uri = os.path.relpath(path, here).replace(os.sep, "/")
        return nodes.image(uri=uri, alt=alt, classes=["executed-image"])

    def literal(self, text: str, language: str, classes: list[str]) -> nodes.literal_block:
        node = nodes.literal_block(text, text, classes=classes)
        node["language"] = language
        return node

    def report(self, what: str, error: str, stderr: str) -> None:
        tail = "\n".join(stderr.strip().splitlines()[-10:])
        logger.warning("%s failed:\n%s%s", what, error,
                       f"\n(standard error)\n{tail}" if tail else "",
                       location=(self.env.docname, self.lineno))


def _ensure_agg() -> None:
    import matplotlib

    matplotlib.use("Agg")


class RunCode(_Executing):
    """``.. runcode::``: show a block of Python, run it, show its output."""

    has_content = True
    option_spec = {"no-figures": directives.flag}

    def run(self):
        _ensure_agg()
        source = "\n".join(self.content)
        blocks = self.env.temp_data.setdefault("edmd2d_runcode_blocks", [0])
        blocks[0] += 1
        namespace = self.env.temp_data.setdefault("edmd2d_runcode_namespace",
                                                  {"__name__": "__main__"})
        folder = self.workdir()
        before = _image_files(folder)
        code = compile(source, f"<{self.env.docname}, block {blocks[0]}>", "exec")
        started = time.perf_counter()
        stdout, stderr, error = _run(code, namespace, folder)
        self.env.temp_data.setdefault("edmd2d_runcode_seconds", []).append(
            time.perf_counter() - started)
        figures = _close_figures(None if "no-figures" in self.options else folder,
                                 f"block{blocks[0]}")
        written = sorted(p for p, stamp in _image_files(folder).items()
                         if before.get(p) != stamp and p not in figures)
        result = [self.literal(source, "python", ["runcode-source"])]
        if error is not None:
            self.report(f"code block {blocks[0]} of {self.env.docname}", error, stderr)
            stdout += error
        if stdout:
            result.append(self.literal(stdout.rstrip("\n"), "text", ["runcode-output"]))
        for path in written + figures:
            result.append(self.image(path, f"output of code block {blocks[0]}"))
        return result


class Example(_Executing):
    """``.. example:: NAME.py``: a gallery page for one script of ``examples/``."""

    required_arguments = 1
    option_spec = {"args": directives.unchanged, "output": directives.unchanged}

    def run(self):
        _ensure_agg()
        config = self.env.config
        examples = Path(self.env.srcdir, config.edmd2d_examples_dir).resolve()
        script = examples / self.arguments[0]
        if not script.is_file():
            raise self.error(f"no example {script}")
        self.env.note_dependency(str(script))
        if not hasattr(self.env, "edmd2d_examples"):
            self.env.edmd2d_examples = {}
        self.env.edmd2d_examples.setdefault(self.env.docname, set()).add(script.name)
        source = script.read_text(encoding="utf-8")
        doc = ast.get_docstring(ast.parse(source)) or ""

        result = []
        intro = nodes.container(classes=["example-docstring"])
        self.state.nested_parse(StringList(_as_rst(doc, self.state), source=str(script)),
                                0, intro)
        result.append(intro)

        mode = os.environ.get("EDMD2D_DOCS_GALLERY", "quick")
        if mode not in GALLERY_MODES:
            raise self.error(f"EDMD2D_DOCS_GALLERY must be one of {GALLERY_MODES}, "
                             f"got {mode!r}")
        args = shlex.split(self.options.get("args", "")) if mode == "quick" else []
        output = self.options.get("output")
        shown = " ".join(["python", f"examples/{script.name}", *map(shlex.quote, args),
                          *([output] if output else [])])
        if mode == "off":
            result.append(self.paragraph(
                "This build did not run the example (EDMD2D_DOCS_GALLERY=off): run "
                f"``{shown}`` to see its output."))
        else:
            folder = self.workdir(script.stem)
            for old in folder.iterdir():
                if old.is_file():
                    old.unlink()
            argv = [str(script), *args, *([str(folder / output)] if output else [])]
            started = time.perf_counter()
            stdout, stderr, error = _run(str(script), {}, folder, argv=argv,
                                         path=str(examples))
            seconds = time.perf_counter() - started
            self.env.temp_data.setdefault("edmd2d_runcode_seconds", []).append(seconds)
            _close_figures(None, "")
            # (The files it wrote are named as on its command line, without the folder.)
            stdout = stdout.replace(str(folder) + os.sep, "")
            if error is not None:
                self.report(f"examples/{script.name}", error, stderr)
                stdout += error
            where = ("with small settings" if args else "with the script's own settings")
            result.append(self.paragraph(
                f"Run while this page was built, {where} ({seconds:.1f} s):"))
            result.append(self.literal(shown, "bash", ["example-command"]))
            if args:
                result.append(self.paragraph(
                    f"``python examples/{script.name}`` runs it with its own settings "
                    "(``--help`` lists the options)."))
            if stdout:
                result.append(self.literal(stdout.rstrip("\n"), "text", ["runcode-output"]))
            for path in sorted(_image_files(folder), key=lambda p: (p.suffix != ".gif", p)):
                result.append(self.image(path, f"written by examples/{script.name}"))

        result.append(nodes.rubric(text="Source"))
        block = self.literal(source, "python", ["example-source"])
        block["linenos"] = True
        result.append(block)
        return result

    def paragraph(self, text: str) -> nodes.Element:
        holder = nodes.container()
        self.state.nested_parse(StringList([text]), self.content_offset, holder)
        return holder.children[0] if len(holder.children) == 1 else holder


def _as_rst(text: str, state) -> list[str]:
    """The lines to parse so that ``text``, reStructuredText (as every docstring of the
    project), is read as such on the page of ``state``.

    A directive on a Markdown page (the gallery's) parses nested content as Markdown
    (MyST), where a literal block's ``::`` stays on the page and roles such as
    ``:func:`` are plain text: the text goes inside MyST's ``eval-rst`` fence, longer
    than any run of backticks in it.  Its literal blocks are the script's command lines,
    highlighted as shell (the blocks the directive adds after it name their languages).
    """
    lines = [".. highlight:: bash", "", *text.splitlines()]
    if not type(state).__module__.startswith("myst_parser"):
        return lines
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    fence = "`" * max(3, longest + 1)
    return [fence + "{eval-rst}", *lines, fence]


def _report_seconds(app, doctree) -> None:
    seconds = app.env.temp_data.get("edmd2d_runcode_seconds")
    if seconds:
        logger.info("%s: ran code for %.1f s", app.env.docname, sum(seconds))


# ------------------------------------------------------ references and the API coverage
def canonical_name(module, name: str) -> str:
    """Where the documentation of ``module.name`` lives: its defining module, or, for
    one defined in a private module, the public module that exports it (a module of
    the package rather than the package itself)."""
    obj = getattr(module, name)
    if inspect.ismodule(obj):
        return obj.__name__
    if inspect.isclass(obj) or inspect.isfunction(obj):
        if any(part.startswith("_") for part in obj.__module__.split(".")):
            # (The package re-exports what its modules do: such a name is documented
            # by the module of the package that exports it, not by the package.)
            if module.__name__ == "edmd2d":
                for modname in public_modules():
                    other = importlib.import_module(modname)
                    if modname != "edmd2d" and getattr(other, name, None) is obj \
                            and name in public_names(other):
                        return f"{modname}.{name}"
            return f"{module.__name__}.{name}"
        return f"{obj.__module__}.{obj.__qualname__}"
    return f"{module.__name__}.{name}"


def public_members(cls) -> list[str]:
    """The public methods and properties a class defines itself."""
    return [name for name, attr in vars(cls).items()
            if not name.startswith("_")
            and (isinstance(attr, (property, classmethod, staticmethod))
                 or inspect.isfunction(attr))]


def _resolve_alias(app, env, node, contnode):
    """A reference to a name of ``edmd2d.__all__`` -> the name in its defining module.

    ``edmd2d.Simulation.run``, ``Simulation.run`` (in any docstring of edmd2d) and
    ``make_gas`` (where the current module is ``edmd2d``) all name
    ``edmd2d.simulation.Simulation.run`` or ``edmd2d.builders.make_gas``."""
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "")
    parts = target.split(".")
    if parts[0] == "edmd2d":
        parts = parts[1:]
    elif node.get("py:module") != "edmd2d" and len(parts) < 2:
        return None
    package = importlib.import_module("edmd2d")
    if not parts or parts[0] not in package.__all__:
        return None
    new = ".".join([canonical_name(package, parts[0]), *parts[1:]])
    if new == target:
        return None
    domain = env.get_domain("py")
    return domain.resolve_xref(env, node.get("refdoc", env.docname), app.builder,
                               node["reftype"], new, node, contnode)


_LINK = re.compile(r"\]\((?!#|[a-z]+:)([^)#\s]+)(#[^)\s]*)?\)")


def _rewrite_outside_links(app, docname, source) -> None:
    """Markdown links from a page to files outside the documentation's folder (as
    ``docs/*.md`` have, to be read on the repository) -> the page that covers each
    (``edmd2d_outside_links``: repository path -> page)."""
    mapping = app.config.edmd2d_outside_links
    if not mapping or Path(app.env.doc2path(docname)).suffix != ".md":
        return
    folder = Path(app.env.doc2path(docname)).parent
    root = Path(app.srcdir).parent

    def replace(match):
        target = (folder / match.group(1)).resolve()
        try:
            key = target.relative_to(root).as_posix()
        except ValueError:
            return match.group(0)
        if key not in mapping:
            return match.group(0)
        return f"](/{mapping[key]})"

    source[0] = _LINK.sub(replace, source[0])


def _check_coverage(app, env) -> None:
    documented = set(env.get_domain("py").objects)
    missing = []
    for modname in public_modules():
        module = importlib.import_module(modname)
        if modname not in documented:
            missing.append(f"module {modname}")
        for name in public_names(module):
            target = canonical_name(module, name)
            if target not in documented:
                missing.append(f"{modname}.{name} (expected as {target})")
            obj = getattr(module, name)
            if inspect.isclass(obj):
                missing += [f"{target}.{member}" for member in public_members(obj)
                            if f"{target}.{member}" not in documented]
    for item in sorted(set(missing)):
        logger.warning("not in the API reference: %s", item)
    examples = Path(app.srcdir, app.config.edmd2d_examples_dir).resolve()
    shown = set().union(*env.edmd2d_examples.values()) if hasattr(env, "edmd2d_examples") \
        else set()
    for script in sorted(examples.glob("[!_]*.py")):
        if script.name not in shown:
            logger.warning("examples/%s has no page in the gallery (an ``example`` "
                           "directive)", script.name)


def _forget_examples(app, env, docname) -> None:
    if hasattr(env, "edmd2d_examples"):
        env.edmd2d_examples.pop(docname, None)


def _merge_examples(app, env, docnames, other) -> None:
    if hasattr(other, "edmd2d_examples"):
        if not hasattr(env, "edmd2d_examples"):
            env.edmd2d_examples = {}
        env.edmd2d_examples.update(other.edmd2d_examples)


def setup(app):
    app.add_config_value("edmd2d_examples_dir", "../examples", "env")
    app.add_config_value("edmd2d_outside_links", {}, "env")
    app.connect("source-read", _rewrite_outside_links)
    app.connect("env-purge-doc", _forget_examples)
    app.connect("env-merge-info", _merge_examples)
    app.add_directive("runcode", RunCode)
    app.add_directive("example", Example)
    app.connect("doctree-read", _report_seconds)
    app.connect("missing-reference", _resolve_alias)
    app.connect("env-check-consistency", _check_coverage)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
