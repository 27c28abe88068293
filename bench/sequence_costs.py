#!/usr/bin/env python3
"""What a `bhnsid sequence` directory cost, from its runs' own records (docs/performance.md, "Sequences").

Usage: bench/sequence_costs.py SEQUENCE_DIR

One JSON object per grid folder (gridK_nN_dxD) on stdout: every run directory under it (the
configurations and their bridges) counted once, by how it started (its recorded command: a coarse
twin on another grid, a neighbour of its own chain, or cold), with the seconds of timers.tsv's TOTAL
and the share of the multigrid solve and of the star's outer step. A run killed before it wrote
timers.tsv is counted as unrecorded. The medians are over converged runs only.
"""
import json
import statistics
import sys
from pathlib import Path


def timers(run_dir: Path) -> dict:
    seconds = {}
    for line in (run_dir / "timers.tsv").read_text().splitlines()[1:]:
        fields = line.split("\t")
        if len(fields) == 4:
            seconds[fields[1]] = seconds.get(fields[1], 0.0) + float(fields[3])
    return seconds


def start_of(command: str, grid: str) -> str:
    words = command.split()
    if "--warm-start" not in words:
        return "cold"
    # The lattice (nN_dxD), not the grid's index: a grid run once as a sequence of its own sits
    # under another index in its warm-start paths.
    lattice = grid.split("_", 1)[-1]
    source_grid = Path(words[words.index("--warm-start") + 1]).parent.parent.name
    return "neighbour" if source_grid.split("_", 1)[-1] == lattice else "twin"


def grid_costs(grid_dir: Path) -> dict:
    runs = {"converged": 0, "failed": 0, "unrecorded": 0}
    by_start = {}
    total = solve = outer = 0.0
    converged_seconds, converged_steps = [], []
    for run_dir in sorted(p for p in grid_dir.glob("xa*/rho*") if p.is_dir()):
        try:
            summary = json.loads((run_dir / "summary.json").read_text())
            t = timers(run_dir)
        except (OSError, ValueError):
            runs["unrecorded"] += 1
            continue
        status = "converged" if summary.get("status") == "converged" else "failed"
        runs[status] += 1
        seconds = t.get("total", 0.0)
        total += seconds
        solve += t.get("multigrid.solve", 0.0)
        outer += t.get("star.outer_step", 0.0)
        start = start_of(summary.get("provenance", {}).get("command_line", ""), grid_dir.name)
        entry = by_start.setdefault(start, {"runs": 0, "converged": 0, "seconds": 0.0, "steps": []})
        entry["runs"] += 1
        entry["seconds"] += seconds
        if status == "converged":
            steps = summary.get("iterations", 0)
            entry["converged"] += 1
            entry["steps"].append(steps)
            converged_seconds.append(seconds)
            converged_steps.append(steps)
    for entry in by_start.values():
        steps = entry.pop("steps")
        entry["seconds"] = round(entry["seconds"], 1)
        entry["median_steps_converged"] = statistics.median(steps) if steps else None
    return {
        "grid": grid_dir.name,
        "runs": runs,
        "seconds_of_runs": round(total, 1),
        "median_seconds_converged": round(statistics.median(converged_seconds), 1) if converged_seconds else None,
        "median_steps_converged": statistics.median(converged_steps) if converged_steps else None,
        "seconds_per_step_converged": round(sum(converged_seconds) / sum(converged_steps), 2) if converged_steps else None,
        "multigrid_share": round(solve / total, 3) if total else None,
        "outer_step_share": round(outer / total, 3) if total else None,
        "by_start": by_start,
    }


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    root = Path(sys.argv[1])
    grids = sorted(p for p in root.glob("grid*") if p.is_dir())
    if not grids:
        print(f"sequence_costs: {root} holds no grid folder (gridK_nN_dxD): not a bhnsid sequence directory",
              file=sys.stderr)
        return 1
    for grid_dir in grids:
        print(json.dumps(grid_costs(grid_dir)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
