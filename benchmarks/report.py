"""Turn a results dict of ``scaling.py`` into JSON, a log-log plot and Markdown tables."""

from __future__ import annotations

import json
from pathlib import Path


def write_json(results: dict, path: Path) -> None:
    path.write_text(json.dumps(results, indent=1, default=_jsonable) + "\n")


def _jsonable(x):
    if hasattr(x, "item"):  # numpy scalars
        return x.item()
    raise TypeError(f"not JSON serializable: {type(x).__name__}")


def plot(results: dict, path: Path) -> None:
    """Collisions/s and events/s against N, one line per packing fraction (log-log)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    points = results["scaling"]
    packings = sorted({p["packing"] for p in points})
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3), sharex=True)
    for ax, key, label in ((axes[0], "collisions_per_s", "disk-disk collisions / s"),
                           (axes[1], "events_per_s", "events / s (all kinds)")):
        for phi in packings:
            row = sorted((p for p in points if p["packing"] == phi), key=lambda p: p["n"])
            n = [p["n"] for p in row]
            med = [p[key]["median"] for p in row]
            lo = [p[key]["median"] - p[key]["min"] for p in row]
            hi = [p[key]["max"] - p[key]["median"] for p in row]
            ax.errorbar(n, med, yerr=[lo, hi], marker="o", ms=4, capsize=2,
                        label=f"packing {phi:g}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        sizes = sorted({p["n"] for p in points})
        ax.set_xlim(sizes[0] / 1.5, sizes[-1] * 1.5)
        ax.set_xlabel("number of disks N")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    lo, hi = axes[0].get_ylim()
    axes[0].set_ylim(lo, max(hi, 2.5e6))
    axes[0].axhline(1.5e6, color="grey", ls=":", lw=1)
    axes[0].annotate("target at N = 10^4, packing 0.5: 1.5 M/s", (0.02, 1.55e6),
                     xycoords=("axes fraction", "data"), color="grey", fontsize=8,
                     va="bottom")
    axes[0].legend(fontsize=8)
    meta = results["meta"]
    fig.suptitle(f"edmd2d, periodic box, one core ({meta['cpu']}, {meta['date']}; "
                 f"median of {results['config']['repeats']}, bars: min-max)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _m(x: float) -> str:
    """A rate in millions with 3 significant digits."""
    return f"{x / 1e6:.3g} M"


def _rate(x: float) -> str:
    if x >= 1e5:
        return _m(x)
    if x >= 1e3:
        return f"{x / 1e3:.3g} k"
    return f"{x:.3g}"


def markdown(results: dict) -> str:
    """The tables shown in benchmarks/README.md."""
    out = []
    meta = results["meta"]
    out.append(f"Run: `{meta['command']}` on {meta['date']}, {meta['cpu']}, "
               f"{meta['cores']} cores (the engine runs on one), {meta['memory_gib']:.0f} GiB, "
               f"Python {meta['python']}, numba {meta['numba']}, numpy {meta['numpy']}, "
               f"edmd2d commit {meta['commit']}{_dirty(meta)}; "
               f"load average before/after {meta['load_before']:.2f}/{meta['load_after']:.2f}.")
    end = (meta.get("commit_end", meta["commit"]), meta.get("uncommitted_end", []))
    if end != (meta["commit"], meta.get("uncommitted", [])):
        out.append(f"The engine changed during this run (at the end: commit {end[0]}"
                   f"{_dirty({'uncommitted': end[1]})}): the sweep and the peers ran the code "
                   "imported at the start, the compile and memory probes (fresh processes) "
                   "the code of their time.")
    points = results["scaling"]
    if points:
        shares = sorted(r["cpu_share"] for p in points for r in p["runs"])
        out.append(f"CPU time / wall time of the timed runs: lowest {shares[0]:.2f}, "
                   f"median {shares[len(shares) // 2]:.2f} (below 1: the process waited "
                   "for a core).")
    out.append("")
    packings = sorted({p["packing"] for p in points})
    sizes = sorted({p["n"] for p in points})
    by = {(p["n"], p["packing"]): p for p in points}

    if 0.5 in packings:
        out.append("**Packing fraction 0.5, periodic box** (median of the repeats, "
                   "min-max in brackets):")
        out.append("")
        out.append("| N | collisions/s | events/s | collisions/disk per run "
                   "| engine arrays, bytes/disk |")
        out.append("|---:|---:|---:|---:|---:|")
        for n in sizes:
            p = by.get((n, 0.5))
            if p is None:
                continue
            c, e = p["collisions_per_s"], p["events_per_s"]
            out.append(f"| {n:,} | {_m(c['median'])} ({c['min'] / 1e6:.3g}-{c['max'] / 1e6:.3g})"
                       f" | {_m(e['median'])} | {p['collisions_per_disk_per_run']:.3g} "
                       f"| {p['engine_array_bytes_per_disk']:.0f} |")
        out.append("")

    out.append("**Collisions per second, all packing fractions** (median):")
    out.append("")
    out.append("| N | " + " | ".join(f"{phi:g}" for phi in packings) + " |")
    out.append("|---:|" + "---:|" * len(packings))
    for n in sizes:
        cells = [_m(by[(n, phi)]["collisions_per_s"]["median"]) if (n, phi) in by else "-"
                 for phi in packings]
        out.append(f"| {n:,} | " + " | ".join(cells) + " |")
    out.append("")

    mem = results.get("memory") or []
    if mem:
        out.append("**Memory per disk** (bytes; each N in a fresh process, see Method):")
        out.append("")
        out.append("| N | packing | engine arrays | traced, held | traced, build peak "
                   "| traced, extra during run | peak RSS growth | RSS growth |")
        out.append("|---:|---:|---:|---:|---:|---:|---:|---:|")
        for m in mem:
            rss = m["rss_growth_bytes_per_disk"]
            out.append(
                f"| {m['n']:,} | {m['packing']:g} | {m['engine_array_bytes_per_disk']:.0f} "
                f"| {m['traced_held_bytes_per_disk']:.0f} "
                f"| {m['traced_peak_build_bytes_per_disk']:.0f} "
                f"| {m['traced_peak_run_extra_bytes_per_disk']:.2f} "
                f"| {m['peak_rss_growth_bytes_per_disk']:.0f} "
                f"| {'-' if rss is None else f'{rss:.0f}'} |")
        out.append("")

    comp = results.get("compile")
    if comp:
        out.append(f"**Compile time** (seconds, each a fresh process: import edmd2d, build "
                   f"{comp['n']} disks, first advance of {comp['n']} collisions):")
        out.append("")
        out.append("| numba cache | import | build | first advance | total in Python "
                   "| whole process |")
        out.append("|---|---:|---:|---:|---:|---:|")
        for key, label in (("cold", "off (`EDMD2D_NUMBA_CACHE=0`): compile everything"),
                           ("warm", "on, warm")):
            c = comp[key]
            out.append(f"| {label} | {c['import_s']:.2f} | {c['build_s']:.2f} "
                       f"| {c['first_advance_s']:.3f} | {c['total_s']:.2f} "
                       f"| {c['process_s']:.2f} |")
        out.append("")

    peers = results.get("peers") or {}
    rows = []
    for r in peers.get("reference", []):
        rows.append(("reference (brute force)", r["n"], r["packing"], r["box"],
                     "collisions/s", r["reference_collisions_per_s"],
                     r["edmd2d_collisions_per_s"]["median"], r["ratio"], ""))
    for r in _rows(peers.get("billiards")):
        rows.append(("billiards", r["n"], r["packing"], r["box"], "collisions/s",
                     r["billiards_collisions_per_s"], r["edmd2d_collisions_per_s"]["median"],
                     r["ratio"], ""))
    for r in _rows(peers.get("pymunk")):
        note = (f"dt = tau/{r['steps_per_free_time']}: {r['overlapping_pairs_mean']:.3g} "
                f"pairs closer than 0.99 d per sample (max {r['overlapping_pairs_max']}), "
                f"{r['pairs_closer_than_diameter_mean']:.3g} closer than d, "
                f"deepest {100 * r['deepest_overlap']:.2g}% of d, "
                f"kinetic energy drift {100 * r['kinetic_energy_drift']:+.2g}%")
        rows.append(("pymunk", r["n"], r["packing"], r["box"], "physical time/s",
                     r["pymunk_physical_time_per_s"],
                     r["edmd2d_physical_time_per_s"]["median"], r["ratio"], note))
    if rows:
        out.append("**Peers** (same equilibrated state for both codes; ratio = edmd2d / peer):")
        out.append("")
        out.append("| peer | N | packing | box | unit | peer | edmd2d | ratio | accuracy |")
        out.append("|---|---:|---:|---|---|---:|---:|---:|---|")
        for name, n, phi, box, unit, peer, edmd, ratio, note in rows:
            out.append(f"| {name} | {n:,} | {phi:g} | {box} | {unit} | {_rate(peer)} "
                       f"| {_rate(edmd)} | {ratio:,.3g} | {note} |")
        out.append("")
    for name in ("billiards", "pymunk"):
        entry = peers.get(name)
        if isinstance(entry, dict) and "skipped" in entry:
            out.append(f"{name}: skipped ({entry['skipped']}).")
        for r in entry if isinstance(entry, list) else []:
            if "error" in r:
                out.append(f"{name}, N={r['n']}: {r['error']}")
    return "\n".join(out).rstrip() + "\n"


def _dirty(meta: dict) -> str:
    changed = [line[3:] for line in meta.get("uncommitted", []) if not line.startswith("??")]
    return f" plus uncommitted changes to {', '.join(changed)}" if changed else ""


def _rows(entry):
    if not isinstance(entry, list):
        return []
    return [r for r in entry if "error" not in r]
