"""The configurations of a sequence as ordinary run directories, and one run of them with its
starts (coarse twin, lower neighbour, bridges, cold), as the local pool (pool.py) and a SLURM array
task run it; a configuration already converged with the same command is skipped, so a killed
sequence resumes where it stopped."""
import bisect
import json
import os
import shlex
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional

from .checkpoints import drop_checkpoints, has_checkpoint, keep_newest_checkpoint
from .safe_io import create_log, expect, make_folders, read_tail, read_text_or_none
from .signals import STOP
from .spec import Grid, Spec, key

# summary.json and timers.tsv of a run are a few kB; a larger one is not a run's.
MAX_RECORD_BYTES = 4 << 20


@dataclass(frozen=True)
class Config:
    grid_index: int
    grid: Grid
    x_a: float
    rho_max: float

    @property
    def relative_dir(self) -> Path:
        return Path(f"grid{self.grid_index}_{self.grid.name}") / f"xa{key(self.x_a)}" / f"rho{key(self.rho_max)}"


def configurations(spec: Spec) -> List[Config]:
    return [Config(g, grid, xa, rho) for g, grid in enumerate(spec.grids) for xa in spec.x_a for rho in spec.rho_max]


def settings(spec: Spec, c: Config) -> Dict[str, str]:
    s = dict(spec.overrides)
    s.update({"grid.n": str(c.grid.n), "grid.dx": repr(c.grid.dx), "puncture.mass_ratio": repr(spec.mass_ratio),
              "star.x_a": repr(c.x_a), "star.rho_max": repr(c.rho_max),
              "run.threads": str(spec.threads)})
    return s


def command(bhnsid: str, spec: Spec, c: Config, out: Path, warm_from: Optional[Path] = None) -> List[str]:
    cmd = [bhnsid, "run", str(spec.base), "--output", str(out)]
    for k, v in settings(spec, c).items():
        cmd += ["--set", f"{k}={v}"]
    if warm_from is not None:
        cmd += ["--warm-start", str(warm_from)]
    return cmd


def chain(spec: Spec, c: Config) -> List[Config]:
    """The configurations of c's grid and xhat_A, by rho_max: the line along which runs warm-start."""
    return [Config(c.grid_index, c.grid, c.x_a, rho) for rho in spec.rho_max]


def warm_source(spec: Spec, c: Config) -> Optional[Config]:
    """The run c starts from when it has converged: the next lower rho_max of its chain (same grid,
    same xhat_A, so the same lattice and star position; the lowest rho_max, furthest from the
    fold, starts cold). A scheduler runs c after it."""
    i = rank(spec, c.rho_max)
    return Config(c.grid_index, c.grid, c.x_a, spec.rho_max[i - 1]) if i > 0 else None


def rank(spec: Spec, rho_max: float) -> int:
    """The index of RHO_MAX in the sequence's sorted list (a bisection: a sequence's lists are long
    enough that a linear search per configuration adds up)."""
    return bisect.bisect_left(spec.rho_max, rho_max)


def coarse_twin(spec: Spec, c: Config) -> Optional[Config]:
    """c's xhat_A and rho_max on the grid of the sequence with half the points and twice the
    spacing (the same cube, c's lattice coarsened once: (128, 0.03) for (256, 0.015)). Its
    converged fields, interpolated, start c nearer its fixed point than a neighbour in rho_max
    does (docs/performance.md); a scheduler runs c after it."""
    for g, grid in enumerate(spec.grids):
        if 2 * grid.n == c.grid.n and abs(grid.dx - 2 * c.grid.dx) <= 1e-12 * grid.dx:
            return Config(g, grid, c.x_a, c.rho_max)
    return None


def fine_twins(spec: Spec, c: Config) -> List[Config]:
    """The configurations whose coarse twin c is."""
    return [Config(g, grid, c.x_a, c.rho_max) for g, grid in enumerate(spec.grids)
            if coarse_twin(spec, Config(g, grid, c.x_a, c.rho_max)) == c]


def twin_run_dir(spec: Spec, c: Config, root: Path) -> Optional[Path]:
    """c's coarse twin when it has converged and kept its checkpoint."""
    twin = coarse_twin(spec, c)
    if twin is None:
        return None
    run_dir = root / twin.relative_dir
    return run_dir if read_outcome(twin, run_dir).status == "converged" and has_checkpoint(run_dir) else None


def still_read(spec: Spec, root: Path, d: Config) -> bool:
    """A configuration not yet run would start from d's checkpoint: a later one of d's chain whose
    nearest converged lower neighbour d is, or d's fine twin. A failed one does not hold it: it is
    run again only when the sequence resumes, from what is there then (tidy_checkpoints)."""
    d_dir = root / d.relative_dir
    line = chain(spec, d)
    for x in line[rank(spec, d.rho_max) + 1:] + fine_twins(spec, d):
        if read_outcome(x, root / x.relative_dir).status != "missing":
            continue
        if x.grid_index != d.grid_index or warm_run_dir(spec, x, root) == d_dir:
            return True
    return False


def warm_run_dir(spec: Spec, c: Config, root: Path) -> Optional[Path]:
    """The nearest lower converged run of c's chain, if any (an unconverged neighbour is passed over)."""
    line = chain(spec, c)
    for d in reversed(line[:rank(spec, c.rho_max)]):
        run_dir = root / d.relative_dir
        if read_outcome(d, run_dir).status == "converged" and has_checkpoint(run_dir):
            return run_dir
    return None


@dataclass
class Outcome:
    config: Config
    status: str          # converged, failed, missing
    message: str = ""
    scalars: Optional[dict] = None
    seconds: float = 0.0


def read_summary(run_dir: Path) -> Optional[dict]:
    """summary.json of a run, None when absent or not a run's summary (a run cut short)."""
    text = read_text_or_none(run_dir / "summary.json", MAX_RECORD_BYTES)
    try:
        summary = json.loads(text) if text is not None else None
    except (ValueError, RecursionError):
        return None
    return summary if isinstance(summary, dict) else None


def read_outcome(c: Config, run_dir: Path) -> Outcome:
    summary = read_summary(run_dir)
    if summary is None:
        return Outcome(c, "missing")
    seconds = 0.0
    for line in (read_text_or_none(run_dir / "timers.tsv", MAX_RECORD_BYTES) or "").splitlines():
        if line.startswith("TOTAL\t"):
            try:
                seconds = float(line.split("\t")[3])
            except (ValueError, IndexError):
                pass
    status, message, scalars = summary.get("status"), summary.get("message"), summary.get("scalars")
    return Outcome(c, status if isinstance(status, str) else "missing", message if isinstance(message, str) else "",
                   scalars if isinstance(scalars, dict) else None, seconds)


def up_to_date(spec: Spec, c: Config, run_dir: Path) -> bool:
    """Converged with exactly these settings (the run's own record of its command)."""
    return read_outcome(c, run_dir).status == "converged" and same_settings(spec, c, run_dir)


EVERY_START_TRIED = "bhnsid sequence: failed from every start tried"


def failed_alike(bhnsid: str, spec: Spec, root: Path, c: Config, warm: bool = True) -> bool:
    """c failed with exactly these settings, and nothing it would start from has changed since: the
    bhnsid executable is older than the failure, and so are the runs of its converged coarse twin
    and nearest converged lower neighbour (a run that converged later, or a new build, is a new
    start), and its attempts (twin, neighbour, bridges, cold) all ran to their end. The runs are
    deterministic, so running c again would repeat every attempt and fail the same way: at n = 256
    an edge configuration's attempts cost up to half an hour. A resumed sequence keeps such a failure; --retry-failed runs it."""
    run_dir = root / c.relative_dir
    if read_outcome(c, run_dir).status != "failed" or not same_settings(spec, c, run_dir):
        return False
    try:
        # Its attempts ran to the end: a sequence killed during a bridge or before the cold start
        # leaves the failure of an earlier attempt, which says nothing about the later ones.
        if ((read_tail(log_path(run_dir), 4096) or "").splitlines() or [""])[-1] != EVERY_START_TRIED:
            return False
        failed_at = (run_dir / "summary.json").stat().st_mtime_ns
        if os.stat(bhnsid).st_mtime_ns >= failed_at:
            return False
        starts = (twin_run_dir(spec, c, root), warm_run_dir(spec, c, root)) if warm else ()
        return all(d is None or (d / "summary.json").stat().st_mtime_ns < failed_at for d in starts)
    except OSError:
        return False


def same_settings(spec: Spec, c: Config, run_dir: Path) -> bool:
    """The run in run_dir was made with c's settings (its own record of its command)."""
    try:
        words = shlex.split(read_summary(run_dir)["provenance"]["command_line"])
    except (TypeError, KeyError, ValueError, AttributeError):
        return False
    wanted = [f"{k}={v}" for k, v in settings(spec, c).items()]
    return all(w in words for w in wanted) and str(spec.base) in words


# How many times a failed warm-start step in rho_max is halved (runs at the midpoints, "bridges")
# before the run starts cold: a step that sends the first outer step past the sigma-model's fold or
# the star over its Roche lobe is often taken in two halves (docs/validation.md §14).
BRIDGE_HALVINGS = 2


def log_path(run_dir: Path) -> Path:
    """rhoR.out beside the run directory rhoR: every attempt's output and the sequence's notes."""
    return run_dir.with_name(run_dir.name + ".out")


def _run(bhnsid: str, spec: Spec, c: Config, run_dir: Path, source: Optional[Path], log) -> int:
    # A directory of an earlier attempt (failed, killed, other settings) is replaced; --force
    # only ever removes what bhnsid wrote there. Once a stop is requested nothing starts (128 + N).
    cmd = command(bhnsid, spec, c, run_dir, source) + (["--force"] if expect(run_dir, "folder") else [])
    return STOP.run(cmd, log)


def _bridge(bhnsid: str, spec: Spec, root: Path, c: Config, source: Config, log, halvings: int) -> int:
    """c failed from the converged run `source`: runs the midpoint in rho_max from source, then c
    from the midpoint, each failing step halved again up to `halvings` times. The midpoint is an
    ordinary run directory of the chain (rhoR beside the configurations; not in the tables).
    Returns c's last exit status."""
    mid = Config(c.grid_index, c.grid, c.x_a, float(f"{(source.rho_max + c.rho_max) / 2:.6g}"))
    if halvings == 0 or mid.rho_max in (source.rho_max, c.rho_max):
        return 1
    mid_dir = root / mid.relative_dir
    if mid.rho_max in spec.rho_max and failed_alike(bhnsid, spec, root, mid):
        # The midpoint is a configuration that failed from this same source (and more) and nothing
        # has changed since: as a bridge it would fail again.
        print(f"bhnsid sequence: the step from rho_max = {source.rho_max:g} failed; the midpoint "
              f"rho_max = {mid.rho_max:g} failed before from the same start, so no bridge", file=log, flush=True)
        return 1
    print(f"bhnsid sequence: the step from rho_max = {source.rho_max:g} failed; bridging through "
          f"rho_max = {mid.rho_max:g} ({mid_dir})", file=log, flush=True)
    if not (up_to_date(spec, mid, mid_dir) and has_checkpoint(mid_dir)):
        with create_log(log_path(mid_dir)) as mid_log:
            rc = _run(bhnsid, spec, mid, mid_dir, root / source.relative_dir, mid_log)
            if rc == 1:
                rc = _bridge(bhnsid, spec, root, mid, source, mid_log, halvings - 1)
        if rc != 0 or read_outcome(mid, mid_dir).status != "converged":
            drop_checkpoints(mid_dir)
            return rc if rc not in (0, 2) else 1
    keep_newest_checkpoint(mid_dir)
    rc = _run(bhnsid, spec, c, root / c.relative_dir, mid_dir, log)
    if rc == 1:
        rc = _bridge(bhnsid, spec, root, c, mid, log, halvings - 1)
    drop_checkpoints(mid_dir)  # c has converged from it or from a later bridge, or starts cold
    return rc


def run_one(bhnsid: str, spec: Spec, root: Path, c: Config, warm: bool = True) -> Outcome:
    """Runs one configuration in its run directory (the pool's worker and a SLURM array task alike),
    warm-started from its converged coarse twin, else from its nearest converged lower-rho_max
    neighbour, when there is one."""
    run_dir = root / c.relative_dir
    make_folders(root, c.relative_dir.parent)
    twin = twin_run_dir(spec, c, root) if warm else None
    source = warm_run_dir(spec, c, root) if warm else None
    with create_log(log_path(run_dir)) as log:
        rc = 1
        if twin is not None:
            rc = _run(bhnsid, spec, c, run_dir, twin, log)
            if rc in (1, 2):
                print(f"bhnsid sequence: the run from the coarser {twin} ended with exit {rc}; starting from "
                      f"{source or 'its own initial guess'} instead", file=log, flush=True)
        if rc in (1, 2):
            rc = _run(bhnsid, spec, c, run_dir, source, log)
        # Exit 1 (the run failed) or 2 (the start refused); a signal (exit >= 128, or negative: the
        # user's Ctrl-C, a job's time limit) stops here instead of starting the run again.
        if rc == 1 and source is not None:
            rc = _bridge(bhnsid, spec, root, c, warm_source_config(spec, c, root, source), log, BRIDGE_HALVINGS)
        if rc in (1, 2) and source is not None:
            # The neighbour refused as a start (another build since, a damaged checkpoint), or the
            # run failed from it and from the bridges (the cold start, below the sigma-model's
            # fold, may still converge): from the run's own initial guess instead; the log keeps
            # every attempt.
            print(f"bhnsid sequence: the run from {source} ended with exit {rc}; starting cold", file=log,
                  flush=True)
            rc = _run(bhnsid, spec, c, run_dir, None, log)
        if rc == 1 and read_outcome(c, run_dir).status == "failed":
            # Every start was tried to its end, the last one failing by itself (not stopped by a
            # signal): what failed_alike requires before a resume may keep this failure.
            print(EVERY_START_TRIED, file=log, flush=True)
    outcome = read_outcome(c, run_dir)
    if outcome.status == "converged":
        # A run's checkpoints (2.3 GB each at n = 256) serve only the warm starts of the next run of
        # its chain and of its fine twin: the newest is kept until those have converged (from it or
        # otherwise), none when nothing warm-starts (--cold).
        for d in (coarse_twin(spec, c), warm_source_config(spec, c, root, source)):
            if d is not None and not still_read(spec, root, d):
                drop_checkpoints(root / d.relative_dir)
        if warm and still_read(spec, root, c):
            keep_newest_checkpoint(run_dir)
        else:
            drop_checkpoints(run_dir)
    else:
        # A failed configuration is run again from its start (--force) when the sequence resumes:
        # its last state would only fill the disk (fifty of them at n = 256 are more than this
        # project's machine holds); its log and summary.json say why it failed.
        drop_checkpoints(run_dir)
    return outcome


def warm_source_config(spec: Spec, c: Config, root: Path, source: Optional[Path]) -> Optional[Config]:
    """The configuration of c's chain whose run directory `source` is."""
    return next((d for d in chain(spec, c) if root / d.relative_dir == source), None)


