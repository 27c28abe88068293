"""bhnsid sequence FILE.yaml [--jobs N] [--output DIR] [--reduce-only] [--slurm [--emit-only]]: every
configuration as an ordinary run, then the splines, minima, error model, tables and figures
(sequence/README.md). Exit codes as the core's: 0 done, 1 no configuration converged, 2 bad input
(one line on stderr), 3 internal error, 128 + N stopped by signal N."""
import argparse
import os
import shutil
import stat
import sys
from pathlib import Path

from .checks import check_runs
from .directory import hold_lock, open_root, survey
from .pipeline import at_targets, error_bars, first_law, minima, point_errors
from .pool import run_all
from .report import write_all
from .runs import configurations, read_outcome, run_one
from .safe_io import InputError, expect, say
from .signals import STOP
from .slurm import OPTION_SYNTAX, Options, check_not_queued, check_option, submit, task_config, write_scripts
from .spec import read_spec


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise InputError(message)


def _arguments(argv):
    p = _Parser(prog="bhnsid sequence", description=__doc__.splitlines()[0])
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
    cores = os.cpu_count() or 1
    if not 1 <= args.jobs <= 4 * cores:
        raise InputError(f"--jobs {args.jobs}: expected 1 to {4 * cores} (4 x the {cores} cores)")
    if args.output is not None and not args.output:
        raise InputError("--output '': expected a directory name")
    if args.emit_only and not args.slurm:
        raise InputError("--emit-only: only with --slurm")
    for name in OPTION_SYNTAX:
        value = getattr(args, name)
        if value is not None:
            if not args.slurm:
                raise InputError(f"--{name}: only with --slurm")
            check_option(name, value)
    if args.slurm and args.reduce_only:
        raise InputError("--slurm and --reduce-only exclude each other")
    if args.task and (args.slurm or args.reduce_only):
        raise InputError("--task: a SLURM array task's own option, alone")
    return args


def _bhnsid(args) -> str:
    """The bhnsid to run: --bhnsid, or the one beside this tool; never another found on PATH (a
    sequence of another build's runs would mix with this one's)."""
    if args.bhnsid is not None:
        path, what = Path(args.bhnsid), f"--bhnsid {args.bhnsid}"
    else:
        path = Path(sys.argv[0]).resolve().parent / "bhnsid"
        what = f"{path} (the bhnsid beside bhnsid-sequence; name another with --bhnsid)"
    try:
        mode = os.stat(path).st_mode
    except OSError as e:
        raise InputError(f"{what}: {e.strerror}")
    if not stat.S_ISREG(mode) or not os.access(path, os.X_OK):
        raise InputError(f"{what}: not an executable file")
    return str(path.resolve())  # batch scripts run it from elsewhere


def main(argv=None) -> int:
    """The entry point: bad input is one line and exit 2, anything unexpected one line and exit 3;
    never a traceback."""
    STOP.install()
    try:
        return _main(argv)
    except InputError as e:
        return _fail(str(e), 2)
    except OSError as e:  # a file system's refusal (permissions, a full disk) met outside safe_io
        where = f"{e.filename}: " if e.filename else ""
        return _fail(f"{where}{e.strerror or e}", 2)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else 0
    except KeyboardInterrupt:
        return 130
    except MemoryError:
        return _fail("out of memory", 3, internal=True)
    except Exception as e:
        return _fail(f"{type(e).__name__}: {e}", 3, internal=True)


def _fail(message: str, code: int, internal: bool = False) -> int:
    kind = "internal error" if internal else "error"
    say(f"bhnsid: {kind}: {message}" + (" (a bug: please report it)" if internal else ""), sys.stderr)
    return code


def _main(argv) -> int:
    args = _arguments(argv)
    spec = read_spec(args.file)
    bhnsid = _bhnsid(args) if not args.reduce_only else (args.bhnsid or "bhnsid")
    root = Path(args.output) if args.output is not None else Path("runs") / Path(args.file).stem
    configs = configurations(spec)
    if args.task:
        c = task_config(spec, args.task)
        open_root(root, spec.file)
        survey(root, [c], results=False)
        o = run_one(bhnsid, spec, root, c, warm=not args.cold)
        if STOP.signum:
            return STOP.exit_code()
        say(f"sequence: {c.relative_dir}: {o.status}" + (f" ({o.message})" if o.message else ""))
        return 0 if o.status == "converged" else 1
    estimates = {}
    if not args.reduce_only:
        estimates = check_runs(bhnsid, spec, elsewhere=args.slurm)
        if STOP.signum:
            return STOP.exit_code()
    open_root(root, spec.file)
    survey(root, configs)
    lock = None
    if not args.reduce_only:
        lock, holder = hold_lock(root)
        if lock is None:
            raise InputError(f"{root}: another bhnsid sequence works in it ({holder}); wait for it to end or "
                             f"stop it, or choose another --output")
    try:
        return _sequence(args, bhnsid, spec, root, configs, estimates)
    finally:
        if lock is not None:
            os.close(lock)


def _sequence(args, bhnsid, spec, root, configs, estimates) -> int:
    if args.slurm:
        expect(root / "slurm", "folder")
        done = _slurm(args, bhnsid, spec, root, estimates)
        if done is not None:
            return done
    if args.reduce_only or args.slurm:
        outcomes = [read_outcome(c, root / c.relative_dir) for c in configs]
    else:
        outcomes = run_all(bhnsid, spec, root, args.jobs, warm=not args.cold, retry_failed=args.retry_failed)
        if STOP.signum:
            stopped = sum(o.status == "interrupted" for o in outcomes)
            say(f"sequence: stopped by signal {STOP.signum}; {stopped} run(s) interrupted at their safe point; "
                f"the same command goes on where it stopped", sys.stderr)
            return STOP.exit_code()
    table = at_targets(spec, outcomes)
    found = minima(spec, table)
    try:
        errors = error_bars(spec, found)
        at_points = point_errors(spec, table)
    except ValueError as e:
        raise InputError(f"{spec.file}: sequence.grids: {e}")
    figs = write_all(spec, outcomes, table, found, errors, at_points, root, first_law(spec, table))
    converged = sum(o.status == "converged" for o in outcomes)
    say(f"sequence: {converged} of {len(outcomes)} configurations converged; wrote {root}/sequence.json, "
        f"table_min_*.md/.csv, first_law.md, failures.md, {', '.join(figs)}")
    if STOP.signum:
        return STOP.exit_code()
    return 0 if converged else 1


def _slurm(args, bhnsid, spec, root, estimates):
    """Writes the scripts and submits them (or prints the lines); an exit code, or None when every
    configuration has converged and the reduction is to run here."""
    tool = str(Path(sys.argv[0]).resolve())
    if not args.emit_only and shutil.which("squeue"):
        check_not_queued(spec, root)
    jobs = write_scripts(tool, bhnsid, spec, root,
                         Options(partition=args.partition, time=args.time, account=args.account, cold=args.cold,
                                 retry_failed=args.retry_failed), estimates)
    runs = sum(j["tasks"] for j in jobs if j["kind"] == "runs")
    if runs == 0 and not args.emit_only:
        say("sequence: every configuration has converged: nothing to submit; reducing here")
        return None
    say(f"sequence: {runs} run(s) in {len(jobs) - 1} job array(s) and the reduction; scripts in {root}/slurm")
    ids = submit(jobs, args.emit_only)
    if not args.emit_only:
        say(f"sequence: watch with `squeue -j {','.join(ids)}`; the tables appear in {root} when job "
            f"{ids[-1]} has run")
    return 0
