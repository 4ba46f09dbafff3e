"""The command line: ``edmd2d run``, ``edmd2d resume``, ``edmd2d info`` and ``edmd2d sweep``.

``edmd2d run CONFIG.toml`` builds the system a TOML configuration describes (see
:mod:`edmd2d.config` and ``examples/gas.toml``), runs it through its equilibration and
its measurement window (the protocol that the sweep's task,
:func:`edmd2d.ensemble.eos_task`, follows too), and writes into an output directory:

- ``config.toml``, a copy of the configuration;
- ``trajectory.gsd``, a GSD frame every ``gsd_every`` (with ``[output] gsd_every``);
- ``checkpoint.edmd2d``, a checkpoint every ``checkpoint_every`` of simulated time
  and/or ``checkpoint_minutes`` of wall-clock time, and always at the end of the
  equilibration and of the run, holding in
  its metadata the configuration, the seed, the end time and the state of the
  measurement, so that ``edmd2d resume`` can go on from it;
- ``results.json``: the measured values with their error bars, the table, the
  configuration, the edmd2d version and the seed.

While it runs it prints a table, one row per block of the measurement window: the
time, the collisions per second of wall-clock time, and the temperature and the
compressibility factor ``Z`` over the window so far with their error bars (the
:class:`~edmd2d.operations.Measure` of the run, read after each block), under a
progress bar (``--no-progress`` hides it).

``edmd2d resume CHECKPOINT`` continues a run from its checkpoint, bit for bit as if it
had not stopped (``--until T`` to run to another end); ``edmd2d info FILE`` describes
a GSD file or a checkpoint.  ``edmd2d sweep CONFIG.toml`` measures the equation of
state over a grid of parameter sets and seeds (:mod:`edmd2d.ensemble`, a sweep
configuration of :func:`edmd2d.config.load_sweep`, ``examples/eos_sweep.toml``) on a
Dask cluster (a local one by default, ``--scheduler ADDRESS`` or ``serial``), writing
``results.csv`` and ``results.json``; run again, it resumes (exit code 1 if a task
failed).  Mistakes in the input (a misspelt key, a value of the wrong type, a missing
file) end with a message naming the key and its line, on standard error, and exit
code 2; a simulation that fails (an inelastic collapse, say) with its
message and exit code 1.
"""

from __future__ import annotations

import argparse
import dataclasses
import inspect
import json
import math
import os
import secrets
import shutil
import sys
import textwrap
import time as _time
import zipfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from . import _atomic, ensemble
from . import checkpoint as _checkpoint
from . import config as _config
from . import progress as _progress
from ._runs import DONE, FAILED, INTERRUPTED, RunProtocol
from ._version import __version__
from .config._build import wall_openings
from .io import gsd as _gsd

__all__ = ["main", "UserError", "CONFIG_FILE", "GSD_FILE", "CHECKPOINT_FILE",
           "RESULTS_FILE"]

#: The copy of the configuration in the output directory.
CONFIG_FILE = "config.toml"
#: The GSD trajectory in the output directory.
GSD_FILE = "trajectory.gsd"
#: The checkpoint in the output directory, from which ``edmd2d resume`` continues.
CHECKPOINT_FILE = "checkpoint.edmd2d"
#: The measured values with their error bars, as JSON, in the output directory.
RESULTS_FILE = "results.json"
# The kind of metadata `edmd2d run` puts in its checkpoints, and its version.
_RUN_FORMAT = "edmd2d-run"
_RUN_VERSION = 2


class UserError(Exception):
    """A mistake in what the command line was given: reported without a traceback."""


def _say(text: str, stream=None) -> None:
    """Print ``text`` to ``stream`` (standard output by default).  If the reader has
    gone (``edmd2d run ... | head``), further output is dropped and the run goes on
    to write its files."""
    stream = sys.stdout if stream is None else stream
    try:
        print(text, file=stream, flush=True)
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, stream.fileno())
        os.close(devnull)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit code: 0 on success, 2 for a mistake in the input (a message on
        standard error), 1 for a simulation that failed, 130 when interrupted.
    """
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # (--help, or argparse's own message on a bad option)
        return exc.code if isinstance(exc.code, int) else 0
    if args.command is None:
        parser.print_help(sys.stderr)
        return 2
    try:
        return args.handler(args)
    except (UserError, _config.ConfigError) as exc:
        _say(f"edmd2d: error: {exc}", sys.stderr)
        return 2
    except RuntimeError as exc:
        _say(f"edmd2d: the simulation failed: {exc}", sys.stderr)
        return 1


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="edmd2d",
        description="Exact event-driven simulation of hard disks in two dimensions: run a "
                    "TOML configuration, resume a run from its checkpoint, or describe a "
                    "GSD file or a checkpoint.",
        epilog="See 'edmd2d COMMAND --help' for each command.")
    parser.add_argument("--version", action="version", version=f"edmd2d {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    run = sub.add_parser(
        "run", help="run a configuration",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Build the system of a TOML configuration, equilibrate it, measure it "
                    "over its window in blocks (one row of the table each) and write the "
                    "GSD trajectory, checkpoints and results.json into the output "
                    "directory (files of an earlier run there are replaced).",
        epilog="A configuration, every table and key (see examples/gas.toml):\n\n"
               + _config_example())
    run.add_argument("config", type=Path, metavar="CONFIG.toml", help="the configuration")
    run.add_argument("--output", "-o", type=Path, metavar="DIR",
                     help="the output directory (default: CONFIG-run/ next to the "
                          "configuration)")
    run.add_argument("--until", type=float, metavar="T",
                     help="stop at the simulated time T, before the configuration's end "
                          "(continue later with 'edmd2d resume')")
    run.add_argument("--no-progress", action="store_true", help="no progress bar")
    run.set_defaults(handler=_cmd_run)

    resume = sub.add_parser(
        "resume", help="continue a run from its checkpoint",
        description="Continue a run of 'edmd2d run' from its checkpoint, bit for bit as if it "
                    "had not stopped: the same positions, velocities, counts and measured "
                    "values as an uninterrupted run.  The GSD trajectory keeps its frames "
                    "up to the checkpoint and goes on.")
    resume.add_argument("checkpoint", type=Path, metavar="CHECKPOINT",
                        help=f"the checkpoint ({CHECKPOINT_FILE} in the run's directory)")
    resume.add_argument("--until", type=float, metavar="T",
                        help="stop at the simulated time T: before the run's end, to "
                             "resume again later; after it, the run's end moves there and "
                             "the measurement goes on in blocks of the same length")
    resume.add_argument("--output", "-o", type=Path, metavar="DIR",
                        help="write into DIR (default: the checkpoint's directory)")
    resume.add_argument("--no-progress", action="store_true", help="no progress bar")
    resume.set_defaults(handler=_cmd_resume)

    info = sub.add_parser(
        "info", help="describe a GSD file or a checkpoint",
        description="Describe a GSD trajectory (frames, disks, box, species, walls, "
                    "times) or an edmd2d checkpoint (time, disks, box, species, walls, "
                    "physics, counts and the run it belongs to).")
    info.add_argument("file", type=Path, metavar="FILE", help="a .gsd file or a checkpoint")
    info.set_defaults(handler=_cmd_info)

    sweep = sub.add_parser(
        "sweep", help="measure the equation of state over a grid of parameters",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Run the equation-of-state task of edmd2d.ensemble (build a gas, "
                    "equilibrate it, measure Z, the pressure, the temperature, the "
                    "collision rate and |psi_6| in blocks) for every parameter set of the "
                    "configuration's grid and every replica, each with its own seed, on a "
                    "Dask cluster, and write results.csv (a row per task), results.json "
                    "and tasks/<task-id>/ (each task's checkpoint) into the output "
                    "directory.  Run again with the same output, the sweep resumes: "
                    "finished tasks are kept, the others continue from their checkpoints "
                    "(a directory of another sweep is refused).",
        epilog="A sweep configuration (see examples/eos_sweep.toml) has the [gas] and [run]\n"
               "tables of 'edmd2d run --help' (not its [model] and [[walls]]; [output] takes\n"
               "checkpoint_every only) and a [sweep] table:\n\n"
               + _config_example(_config.load_sweep.__doc__)
               + "\n[run] also takes equilibrate_collisions (collisions per disk, instead of\n"
                 "equilibrate).  The local cluster has one single-threaded worker process per\n"
                 "core (or --workers N).  Dask is an optional dependency: pip install\n"
                 "'edmd2d[ensemble]'.\n")
    sweep.add_argument("config", type=Path, metavar="CONFIG.toml",
                       help="the sweep configuration")
    sweep.add_argument("--scheduler", metavar="ADDRESS|serial",
                       help="the address of a Dask scheduler (tcp://host:8786), or 'serial' "
                            "for one task after another in this process, without Dask "
                            "(default: a local cluster)")
    sweep.add_argument("--workers", type=_positive_int, metavar="N",
                       help="worker processes of the local cluster (default: one per core)")
    sweep.add_argument("--output", "-o", type=Path, metavar="DIR",
                       help="the output directory (default: CONFIG-sweep/ next to the "
                            "configuration)")
    sweep.add_argument("--no-progress", action="store_true", help="no progress bar")
    sweep.set_defaults(handler=_cmd_sweep)
    return parser


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def _config_example(doc: str | None = None) -> str:
    """The annotated configuration of a docstring (default :mod:`edmd2d.config`'s)."""
    doc = inspect.cleandoc(_config.__doc__ if doc is None else doc).split("::", 1)[1]
    block = []
    for line in doc.splitlines()[1:]:
        if line.strip() and not line.startswith("    "):
            break
        block.append(line)
    return textwrap.dedent("\n".join(block)).strip("\n") + "\n"


# ------------------------------------------------------------------ run and resume
def _cmd_run(args) -> int:
    cfg = _config.load(args.config)
    out = args.output if args.output is not None else (
        args.config.parent / f"{args.config.stem}-run")
    gsd_every = cfg.data["output"]["gsd_every"]
    if gsd_every is not None:
        _need_gsd("[output] gsd_every")
    seed = cfg.data["model"]["seed"]
    text = cfg.text
    if seed is None:
        seed = secrets.randbits(32)
        text = _with_seed(cfg.text, seed)
    sim, removed = _config.build(cfg, seed)
    _make_dir(out)
    (out / CONFIG_FILE).write_text(text, encoding="utf-8")
    if gsd_every is None:
        # (The files of an earlier run in the directory are replaced; a trajectory this
        # run does not write must not pass for one of its own.)
        (out / GSD_FILE).unlink(missing_ok=True)
    run = cfg.data["run"]
    meta = RunProtocol.start(sim, {
        "format": _RUN_FORMAT, "version": _RUN_VERSION, "edmd2d": __version__,
        "config": cfg.data, "config_file": str(args.config), "seed": seed,
        "removed_disks": removed, "rows": [], "wall_seconds": 0.0,
        "wall_openings": wall_openings(cfg.data["walls"])[1]}, run)
    meta["end"] = meta["window_start"] + run["duration"]
    if removed:
        _say(f"{removed} disks of the lattice start crossed wall segments and were left "
             f"out: {len(sim)} disks")
    until = meta["end"]
    if args.until is not None:
        if not sim.time < args.until <= meta["end"]:
            raise UserError(f"--until {args.until:g} must lie after the start "
                            f"(t={sim.time:g}) and not after the run's end "
                            f"(t={meta['end']:g})")
        until = args.until
    return _Runner(sim, meta, out, progress=not args.no_progress,
                   resumed=False).execute(until)


def _with_seed(text: str, seed: int) -> str:
    """The configuration ``text`` with the seed drawn for it written into ``[model]``,
    so that the copy in the output directory runs the same system again (``text`` as
    it is where the seed cannot be put in plainly)."""
    lines = text.splitlines()
    entry = f"seed = {seed}  # drawn by edmd2d run"
    heads = [k for k, line in enumerate(lines)
             if line.split("#", 1)[0].strip() == "[model]"]
    if heads:
        lines.insert(heads[0] + 1, entry)
    else:
        lines += ["", "[model]", entry]
    new = "\n".join(lines) + "\n"
    try:
        if _config.loads(new).data["model"]["seed"] == seed:
            return new
    except _config.ConfigError:
        pass
    return text


def _cmd_resume(args) -> int:
    path = args.checkpoint
    meta = _read_checkpoint_metadata(path)
    if meta.get("format") != _RUN_FORMAT:
        raise UserError(f"{path} was not written by 'edmd2d run': it holds no run to "
                        "continue (load it in Python with edmd2d.checkpoint.load)")
    if meta.get("version") != _RUN_VERSION:
        raise UserError(f"{path} holds a run of format version {meta.get('version')}; this "
                        f"edmd2d {__version__} continues version {_RUN_VERSION}")
    failure = meta.get("failure")
    if failure is not None:
        _say(f"edmd2d: this run failed at t={failure['time']:g}: {failure['error']}\n"
             "Continuing from its checkpoint would meet the same event.  Change the "
             "configuration (for an inelastic collapse, a larger [model] tc; for disks "
             "at rest under gravity, [model] resting = true) and run it again, or load the "
             f"state in Python with edmd2d.checkpoint.load('{path}').", sys.stderr)
        return 1
    sim = _load_checkpoint(path)
    until = meta["end"]
    if args.until is not None:
        if not args.until > sim.time:
            raise UserError(f"--until {args.until:g} must lie after the checkpoint's time "
                            f"t={sim.time:g}")
        # (Before the run's end: stop there, as run --until does; after it: the run's
        # end moves, and the measurement goes on in blocks of the same length.)
        until = args.until
        meta["end"] = max(meta["end"], until)
    if sim.time >= until:
        _say(f"the run is complete at t={sim.time:g}; give --until T to go on")
        return 0
    out = args.output if args.output is not None else path.parent
    _make_dir(out)
    if out.resolve() != path.parent.resolve():
        source = path.parent / CONFIG_FILE
        if source.exists():
            shutil.copyfile(source, out / CONFIG_FILE)
    if meta["config"]["output"]["gsd_every"] is not None:
        _need_gsd("resuming a run with a GSD trajectory")
        source = path.parent / GSD_FILE
        if source.exists():
            _gsd.copy_until(source, out / GSD_FILE, sim.time)
    return _Runner(sim, meta, out, progress=not args.no_progress,
                   resumed=True).execute(until)


class _Runner:
    """One run of ``edmd2d run`` or ``edmd2d resume``: the table and the files around
    the run protocol."""

    def __init__(self, sim, meta: dict, out: Path, *, progress: bool, resumed: bool):
        self.sim, self.meta, self.out = sim, meta, out
        self.progress, self.resumed = progress, resumed
        self.bar = None
        self.clock = _time.perf_counter()
        self.wall0 = meta["wall_seconds"]
        self.last_row = (self.clock, sim.counts.collisions)
        config = meta["config"]
        self.protocol = RunProtocol(
            sim, meta, out / CHECKPOINT_FILE, run=config["run"], output=config["output"],
            gsd=out / GSD_FILE, resumed=resumed, on_block=self._row,
            annotate=self._annotate)

    def execute(self, until: float) -> int:
        sim, meta = self.sim, self.meta
        self._print_head(until)
        if self.progress:
            self.bar, _ = _progress.bar(True, total=until - sim.time, unit="time",
                                        desc="edmd2d")
        self.last_row = (_time.perf_counter(), sim.counts.collisions)
        try:
            status = self.protocol.execute(until, progress=self.bar or False)
        finally:
            if self.bar is not None:
                self.bar.close()
                self.bar = None
        if status == DONE:
            status = "complete" if until >= meta["end"] else "stopped"
        results = self._results(status)
        _write_json(self.out / RESULTS_FILE, results)
        self._print_tail(results, self.protocol.path)
        if status == FAILED:
            _say(f"edmd2d: the simulation failed: {meta['failure']['error']}", sys.stderr)
            return 1
        return 130 if status == INTERRUPTED else 0

    # -------------------------------------------------------------- the table
    def _print(self, line: str) -> None:
        if self.bar is not None:
            try:
                self.bar.write(line, file=sys.stdout)
            except BrokenPipeError:
                _say("")  # (drops the output from here on)
        else:
            _say(line)

    def _print_head(self, until: float) -> None:
        meta, sim = self.meta, self.sim
        run = meta["config"]["run"]
        what = "resuming" if self.resumed else "running"
        start, blocks, end = self._planned()
        self._print(f"{what} {len(sim)} disks from t={sim.time:g} to t={until:g}; measuring "
                    f"t={start:g}..{end:g} in {blocks} blocks of "
                    f"{run['duration'] / run['blocks']:g} (seed {meta['seed']})")
        self._print("each row: the window so far, mean +- standard error over its blocks")
        self._print(_ROW_HEAD)
        for row in meta["rows"]:
            self._print(_row_text(row) + ("   (before the checkpoint)" if self.resumed
                                          else ""))

    def _row(self, sim, measure) -> None:
        now = _time.perf_counter()
        if measure.blocks == 0:  # (the window opens)
            self.last_row = (now, sim.counts.collisions)
            return
        m = measure.result()
        then, collisions = self.last_row
        rate = (sim.counts.collisions - collisions) / max(now - then, 1e-9)
        self.last_row = (now, sim.counts.collisions)
        row = {"time": sim.time, "collisions_per_second": rate, "blocks": m.blocks,
               "temperature": m.temperature, "temperature_error": m.temperature_error,
               "compressibility_factor": m.compressibility_factor,
               "compressibility_factor_error": m.compressibility_factor_error}
        self.meta["rows"].append(row)
        self._print(_row_text(row))

    def _print_tail(self, results: dict, path: Path) -> None:
        sim = self.sim
        status = results["status"]
        measurement = self.protocol.result()
        if measurement is not None:
            _say(measurement.summary())
        if status == "complete":
            _say(f"done at t={sim.time:g}: {sim.counts.collisions} collisions; results in "
                 f"{self.out / RESULTS_FILE}")
        elif status == FAILED:
            _say(f"failed at t={sim.time:g}: what was measured before is in "
                 f"{self.out / RESULTS_FILE} (status 'failed'), the state before the "
                 f"failure in {path}", sys.stderr)
        else:
            _say(f"{status} at t={sim.time:g}; continue with: edmd2d resume {path}",
                 sys.stderr if status == INTERRUPTED else sys.stdout)

    def _planned(self) -> tuple[float, int, float]:
        """The measurement to the run's end: its start, its blocks and its end (the
        configured window, or more blocks of the same length after a resume past it)."""
        blocks = self.protocol.blocks_until(self.meta["end"])
        return self.meta["window_start"], blocks, self.protocol.block_edge(blocks)

    # -------------------------------------------------------------- the files
    def _annotate(self, meta: dict) -> None:
        meta["wall_seconds"] = self.wall0 + (_time.perf_counter() - self.clock)

    def _results(self, status: str) -> dict:
        sim, meta = self.sim, self.meta
        measurement = self.protocol.result()
        files = {"config": CONFIG_FILE, "checkpoint": CHECKPOINT_FILE}
        if meta["config"]["output"]["gsd_every"] is not None:
            files["gsd"] = GSD_FILE
        box = sim.box
        measure = self.protocol.measure
        planned = self.protocol.blocks_until(meta["end"])
        return {
            "edmd2d": __version__,
            "status": status,
            "error": (meta.get("failure") or {}).get("error") if status == FAILED else None,
            "config_file": meta["config_file"],
            "seed": meta["seed"],
            "time": sim.time,
            "end": meta["end"],
            "n": len(sim),
            "removed_disks": meta["removed_disks"],
            "box": {"width": box.width, "height": box.height,
                    "periodic": list(box.periodic)},
            "counts": dataclasses.asdict(sim.counts),
            "kinetic_energy": sim.kinetic_energy(),
            "window": {"start": meta["window_start"],
                       "duration": self.protocol.block_edge(planned) - meta["window_start"],
                       "blocks": planned,
                       "blocks_measured": 0 if measure is None else measure.blocks},
            "measurement": None if measurement is None else _measurement_json(measurement),
            "table": meta["rows"],
            "wall_seconds": self.wall0 + (_time.perf_counter() - self.clock),
            "files": files,
            "config": meta["config"],
        }


_ROW_HEAD = (f"{'time':>12} {'coll/s':>10} {'T':>12} {'+- error':<11} "
             f"{'Z':>10} {'+- error':<11}")


def _row_text(row: dict) -> str:
    def err(value):
        return f"{value:<8.2g}" if value is not None and math.isfinite(value) else f"{'-':<8}"

    return (f"{row['time']:>12.6g} {row['collisions_per_second']:>10.3g} "
            f"{row['temperature']:>12.6f} +- {err(row['temperature_error'])} "
            f"{row['compressibility_factor']:>10.5f} +- "
            f"{err(row['compressibility_factor_error'])}")


def _measurement_json(m) -> dict:
    """A Measurement as JSON: ``{"value", "error"}`` for the quantities with error bars,
    lists for arrays, ``null`` for values that are not finite."""
    out = {}
    names = {f.name for f in dataclasses.fields(m)}
    for f in dataclasses.fields(m):
        name = f.name
        if name.endswith("_error") and name[:-6] in names:
            continue
        value = _plain(getattr(m, name))
        if name + "_error" in names:
            value = {"value": value, "error": _plain(getattr(m, name + "_error"))}
        out[name] = value
    return out


def _plain(value):
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, (np.generic,)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _write_json(path: Path, data: dict) -> None:
    """Write ``data`` as strict JSON (``null`` for values that are not finite), through
    a temporary file renamed over ``path``: a reader never sees half a file."""
    _atomic.write_text(path, json.dumps(_plain_tree(data), indent=1, allow_nan=False) + "\n")


def _plain_tree(value):
    if isinstance(value, dict):
        return {k: _plain_tree(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain_tree(v) for v in (value.tolist() if isinstance(value, np.ndarray)
                                         else value)]
    return _plain(value)


def _make_dir(path: Path) -> None:
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UserError(f"cannot make the output directory {path}: {exc.strerror}") from None


def _need_gsd(what: str) -> None:
    try:
        import gsd.hoomd  # noqa: F401
    except ImportError:
        raise UserError(f"{what} needs the gsd package (a dependency of edmd2d): "
                        "pip install gsd") from None


def _read_checkpoint_metadata(path: Path) -> dict:
    if path.suffix == ".toml":
        raise UserError(f"{path} is a configuration, not a checkpoint: run it with "
                        f"'edmd2d run {path}'")
    try:
        return _checkpoint.read_metadata(path)
    except FileNotFoundError:
        raise UserError(f"{path}: no such file") from None
    except (OSError, ValueError) as exc:
        raise UserError(str(exc)) from None


def _load_checkpoint(path: Path):
    try:
        return _checkpoint.load(path)
    except FileNotFoundError:
        raise UserError(f"{path}: no such file") from None
    except (OSError, ValueError) as exc:
        raise UserError(str(exc)) from None


# ------------------------------------------------------------------ sweep
def _cmd_sweep(args) -> int:
    cfg = _config.load_sweep(args.config)
    out = args.output if args.output is not None else (
        args.config.parent / f"{args.config.stem}-sweep")
    scheduler = args.scheduler
    if args.workers is not None and scheduler is not None:
        raise UserError("--workers sets the size of the local cluster; it cannot go with "
                        "--scheduler")
    if scheduler != "serial":
        try:
            import distributed  # noqa: F401
        except ImportError:
            raise UserError("a sweep on Dask needs dask.distributed: pip install "
                            "'edmd2d[ensemble]' (or give --scheduler serial)") from None
    sweep = cfg.data["sweep"]
    points = sweep["parameters"]
    total = len(points) * sweep["replicas"]
    where = ("in this process" if scheduler == "serial" else
             f"on {scheduler}" if scheduler is not None else
             f"on a local cluster of {args.workers or os.cpu_count()} workers")
    _say(f"sweeping {len(points)} parameter sets x {sweep['replicas']} replicas = {total} "
         f"tasks {where}; results in {out}")
    try:
        result = ensemble.sweep(
            ensemble.eos_task, points, replicas=sweep["replicas"], seed=sweep["seed"],
            output=out, scheduler=scheduler, workers=args.workers,
            progress=not args.no_progress,
            metadata={"config_file": str(args.config), "config": cfg.text})
    except KeyboardInterrupt:
        done = ensemble.load(out)
        _say(f"interrupted: {len(done.tasks)} of {done.total} tasks finished; run the same "
             "command again to resume", sys.stderr)
        return 130
    except (OSError, ValueError) as exc:
        raise UserError(str(exc)) from None
    _print_sweep(result, points)
    return 0 if result.complete else 1


def _print_sweep(result, points: list) -> None:
    varied = [k for k in dict.fromkeys(k for p in points for k in p)
              if len({json.dumps(p.get(k)) for p in points}) > 1]
    head = "".join(f"{k:>18}" for k in varied)
    _say(f"{'task':<12}{head} {'Z':>10} {'+- error':<9} {'T':>9} {'coll/disk/t':>12} "
         f"{'|psi6|':>7}")
    for t in result.tasks:
        cells = "".join(f"{str(t['parameters'].get(k)):>18}" for k in varied)
        v = t["values"]
        if t["status"] != "ok":
            _say(f"{t['task']:<12}{cells} failed: {t['error']['type']}: "
                 f"{t['error']['message']}")
            continue
        err = v["Z_error"]
        err = f"{err:<9.2g}" if err is not None and math.isfinite(err) else f"{'-':<9}"
        _say(f"{t['task']:<12}{cells} {v['Z']:>10.5f} {err} {v['temperature']:>9.5f} "
             f"{v['collision_rate']:>12.5g} {v['psi6']:>7.3f}")
    failed = len(result.failed)
    _say(f"{len(result.tasks)} of {result.total} tasks finished, {failed} failed; results in "
         f"{result.output / 'results.csv'}")


# ------------------------------------------------------------------ info
def _cmd_info(args) -> int:
    path = args.file
    if not path.exists():
        raise UserError(f"{path}: no such file")
    if path.is_dir():
        raise UserError(f"{path} is a directory; give a .gsd file or a checkpoint")
    with open(path, "rb") as f:
        head = f.read(4)
    # (A checkpoint is a zip file; one cut short is still one, to be called damaged.)
    if zipfile.is_zipfile(path) or head == b"PK\x03\x04":
        _say(_checkpoint_info(path))
    else:
        _say(_gsd_info(path))
    return 0


def _describe(lines: list) -> str:
    width = max(len(k) for k, _ in lines)
    return "\n".join(f"  {k:<{width}}  {v}" for k, v in lines)


def _species_text(species: np.ndarray, radii: np.ndarray, masses: np.ndarray) -> str:
    parts = []
    for s in np.unique(species):
        sel = species == s
        r, m = radii[sel], masses[sel]
        parts.append(f"{int(s)}: {int(sel.sum())} (radius {_values((r.min(), r.max()))}, "
                     f"mass {_values((m.min(), m.max()))})")
    return "; ".join(parts)


def _segments(k: int) -> str:
    return f"{k} segment" + ("" if k == 1 else "s")


def _values(span: tuple) -> str:
    lo, hi = span
    return f"{lo:g}" if lo == hi else f"{lo:g}-{hi:g}"


def _box_text(width: float, height: float, periodic) -> str:
    px, py = periodic
    kind = {(True, True): "periodic", (False, False): "walled",
            (True, False): "periodic in x, walled in y",
            (False, True): "walled in x, periodic in y"}[(bool(px), bool(py))]
    return f"{width:.6g} x {height:.6g}, {kind}"


def _family_text(name: str, family) -> str:
    """A registered physics family by its name and the single numbers it logs
    (``rough tangential_restitution 0.5, friction inf, ...``)."""
    numbers = [f"{key} {float(value[0]):g}" for key, value in family.log().items()
               if np.size(value) == 1]
    return " ".join([name.replace("_", " "), ", ".join(numbers)]).strip()


def _checkpoint_info(path: Path) -> str:
    meta = _read_checkpoint_metadata(path)
    sim = _load_checkpoint(path)
    c = sim.counts
    physics = []
    table = sim.restitution
    if (table != 1.0).any():
        physics.append("restitution " + (f"{table[0, 0]:g}" if table.size == 1
                                         else str(table.tolist())) + f", tc {sim.tc:g}")
    if sim.wall_restitution != 1.0:
        physics.append(f"wall restitution {sim.wall_restitution:g}")
    if sim.gravity.any():
        physics.append(f"gravity ({sim.gravity[0]:g}, {sim.gravity[1]:g})")
    if sim.thermostat is not None:
        physics.append(f"thermostat kT={sim.thermostat[0]:g}, rate={sim.thermostat[1]:g}")
    if sim.wall_temperatures:
        physics.append(f"heated walls {sim.wall_temperatures}")
    physics += [_family_text(name, family) for name, family in sim.families.items()]
    lines = [
        ("time", f"{sim.time:.10g}"),
        ("disks", f"{len(sim)}"),
        ("species", _species_text(sim.species, sim.radii, sim.masses)),
        ("box", _box_text(sim.box.width, sim.box.height, sim.box.periodic)),
        ("walls", _segments(len(sim.walls))),
        ("physics", ", ".join(physics) or "elastic"),
        ("counts", f"{c.collisions} collisions, {c.wall_collisions} wall collisions, "
                   f"{c.events} events"),
        ("energy", f"kinetic {sim.kinetic_energy():.10g}"),
    ]
    if meta.get("format") == _RUN_FORMAT and meta.get("version") == _RUN_VERSION:
        protocol = RunProtocol(sim, meta, path, run=meta["config"]["run"],
                               output=meta["config"]["output"])
        done = 0 if protocol.measure is None else protocol.measure.blocks
        blocks = protocol.blocks_until(meta["end"])
        lines += [
            ("run", f"of {meta['config_file']}, seed {meta['seed']}, to t={meta['end']:g}"),
            ("measured", f"{done} of {blocks} blocks of t={meta['window_start']:g}.."
                         f"{protocol.block_edge(blocks):g}"),
        ]
        if meta.get("failure") is not None:
            lines.append(("failed", f"at t={meta['failure']['time']:g}: "
                                    f"{meta['failure']['error']}"))
    return f"{path}: edmd2d checkpoint\n" + _describe(lines)


def _gsd_info(path: Path) -> str:
    _need_gsd("reading a GSD file")
    try:
        info = _gsd.describe(path)
    except ValueError as exc:
        raise UserError(f"{path} is neither a GSD file nor an edmd2d checkpoint ({exc})"
                        ) from None
    if info["frames"] == 0:
        return f"{path}: GSD file, no frames"
    lines = [("frames", f"{info['frames']}")]
    if info["times"] is not None:
        lines.append(("time", f"{info['times'][0]:.10g} .. {info['times'][1]:.10g}"))
    lines.append(("disks", f"{info['n']}"))
    width, height = info["box"]
    lines.append(("box", _box_text(width, height, info["periodic"])))
    lines.append(("species", "; ".join(
        f"{s['name']}: {s['count']} (diameter {_values(s['diameters'])}, mass "
        f"{_values(s['masses'])})" for s in info["species"])))
    lines.append(("walls", _segments(info["walls"])))
    if info["collisions"] is not None:
        lines.append(("collisions", f"{info['collisions']} at the last frame"))
    return f"{path}: GSD file (HOOMD schema)\n" + _describe(lines)


if __name__ == "__main__":
    sys.exit(main())
