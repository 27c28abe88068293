"""bhnsid sequence FILE.yaml [--jobs N] [--output DIR] [--reduce-only] [--slurm [--emit-only]]: every
configuration as an ordinary run, then the splines, minima, error model, tables and figures
(sequence/README.md)."""
import argparse
import fcntl
import os
import shutil
import socket
import sys
from pathlib import Path

from .pipeline import at_targets, error_bars, minima, point_errors
from .report import write_all, write_atomic
from .runs import configurations, read_outcome, run_all, run_one
from .slurm import Options, SlurmError, check_not_queued, submit, task_config, write_scripts
from .spec import SpecError, read_spec

MARKER = ".bhnsid-sequence"
LOCK = ".bhnsid-sequence.lock"


def hold_lock(root: Path):
    """The sequence directory's lock (an open file, held until this process exits), or None when
    another `bhnsid sequence` holds it: two pools in one directory would run the same configurations
    into the same run directories. A SLURM array task and --reduce-only do not take it."""
    lock = open(root / LOCK, "a+")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        lock.close()
        return None
    lock.seek(0)
    lock.truncate()
    lock.write(f"pid {os.getpid()} on {socket.gethostname()}\n")
    lock.flush()
    return lock


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="bhnsid sequence", description=__doc__.splitlines()[0])
    p.add_argument("file", help="sequence file (YAML, a section 'sequence')")
    p.add_argument("--output", help="sequence directory (default runs/<file stem>)")
    p.add_argument("--jobs", type=int, default=1, help="runs at once (each with sequence.threads threads)")
    p.add_argument("--reduce-only", action="store_true", help="only reduce the runs already there")
    p.add_argument("--cold", action="store_true",
                   help="start every run from its own initial guess (no warm start from a converged neighbour)")
    p.add_argument("--retry-failed", action="store_true",
                   help="run failed configurations again even where their start has not changed since they failed")
    p.add_argument("--bhnsid", help="the bhnsid executable (default: the one beside this tool)")
    p.add_argument("--slurm", action="store_true",
                   help="submit the runs as SLURM job arrays (one per rho_max rank) and the reduction as a job after them")
    p.add_argument("--emit-only", action="store_true", help="with --slurm: write the batch scripts, submit nothing")
    p.add_argument("--partition", help="with --slurm: the partition of every job")
    p.add_argument("--time", help="with --slurm: the time limit of every run task (e.g. 2:00:00)")
    p.add_argument("--account", help="with --slurm: the account of every job")
    p.add_argument("--task", help=argparse.SUPPRESS)  # TASK_LIST:INDEX, one run of a SLURM array task
    args = p.parse_args(argv)
    try:
        spec = read_spec(args.file)
        if args.jobs < 1:
            raise SpecError(f"--jobs: expected at least 1, got {args.jobs}")
        if args.emit_only and not args.slurm:
            raise SpecError("--emit-only: only with --slurm")
        if args.slurm and args.reduce_only:
            raise SpecError("--slurm and --reduce-only exclude each other")
    except SpecError as e:
        print(f"bhnsid: error: {e}", file=sys.stderr)
        return 2
    here = Path(sys.argv[0]).resolve().parent
    bhnsid = args.bhnsid or str(here / "bhnsid")
    if not (os.path.isfile(bhnsid) and os.access(bhnsid, os.X_OK)):
        found = shutil.which("bhnsid")
        if not found:
            print(f"bhnsid: error: --bhnsid: no bhnsid executable at {bhnsid} or on PATH", file=sys.stderr)
            return 2
        bhnsid = found
    bhnsid = str(Path(bhnsid).resolve())  # batch scripts run it from elsewhere
    root = Path(args.output) if args.output else Path("runs") / Path(args.file).stem
    # A folder this tool did not make is never written into (its runs would mix with others').
    if root.exists() and not (root / MARKER).exists() and any(root.iterdir()):
        print(f"bhnsid: error: {root}: exists and is not a sequence directory (no {MARKER}); choose another --output",
              file=sys.stderr)
        return 2
    root.mkdir(parents=True, exist_ok=True)
    if not (root / MARKER).exists():  # SLURM's array tasks all pass here: written once
        write_atomic(root / MARKER, f"{Path(args.file).resolve()}\n")
    lock = None
    if not args.task and not args.reduce_only:
        lock = hold_lock(root)
        if lock is None:
            holder = (root / LOCK).read_text().strip() or "a process"
            print(f"bhnsid: error: {root}: another bhnsid sequence works in it ({holder}); wait for it to end or "
                  f"stop it, or choose another --output", file=sys.stderr)
            return 2
    if args.task:
        try:
            c = task_config(spec, args.task)
        except SlurmError as e:
            print(f"bhnsid: error: {e}", file=sys.stderr)
            return 2
        o = run_one(bhnsid, spec, root, c, warm=not args.cold)
        print(f"sequence: {c.relative_dir}: {o.status}" + (f" ({o.message})" if o.message else ""))
        return 0 if o.status == "converged" else 1
    if args.slurm:
        try:
            tool = str(Path(sys.argv[0]).resolve())
            if not args.emit_only and shutil.which("squeue"):
                check_not_queued(spec, root)
            jobs = write_scripts(tool, bhnsid, spec, root,
                                 Options(partition=args.partition, time=args.time, account=args.account, cold=args.cold,
                                         retry_failed=args.retry_failed))
            runs = sum(j["tasks"] for j in jobs if j["kind"] == "runs")
            if runs == 0 and not args.emit_only:
                print("sequence: every configuration has converged: nothing to submit; reducing here")
            else:
                print(f"sequence: {runs} run(s) in {len(jobs) - 1} job array(s) and the reduction; scripts in {root}/slurm")
                ids = submit(jobs, args.emit_only)
                if not args.emit_only:
                    print(f"sequence: watch with `squeue -j {','.join(ids)}`; the tables appear in {root} when job "
                          f"{ids[-1]} has run")
                return 0
        except SlurmError as e:
            print(f"bhnsid: error: {e}", file=sys.stderr)
            return 2
    if args.reduce_only or args.slurm:
        outcomes = [read_outcome(c, root / c.relative_dir) for c in configurations(spec)]
    else:
        outcomes = run_all(bhnsid, spec, root, args.jobs, warm=not args.cold, retry_failed=args.retry_failed)
    table = at_targets(spec, outcomes)
    found = minima(spec, table)
    try:
        errors = error_bars(spec, found)
        at_points = point_errors(spec, table)
    except ValueError as e:
        print(f"bhnsid: error: {spec.file}: sequence.grids: {e}", file=sys.stderr)
        return 2
    figs = write_all(spec, outcomes, table, found, errors, at_points, root)
    converged = sum(o.status == "converged" for o in outcomes)
    print(f"sequence: {converged} of {len(outcomes)} configurations converged; wrote {root}/sequence.json, "
          f"table_min_*.md/.csv, failures.md, {', '.join(figs)}")
    return 0 if converged else 1
