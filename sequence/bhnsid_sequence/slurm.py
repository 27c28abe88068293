"""A sequence on a SLURM cluster: one job array per rho_max rank (array r holds the r-th rho_max of
every chain of equal grid and xhat_A, so each run starts after the neighbour it warm-starts from;
--dependency=afterany on array r - 1; the runs of grids with a coarse twin in a second array of the
rank, after the first, so that they start from their twins as on the local pool), and the reduction
as a job after all of them. Every task runs
`bhnsid-sequence FILE --output ROOT --task LIST:K`, the same code as the local pool (runs.run_one), so
a resubmission skips what converged and the cluster's results are the local pool's."""
import hashlib
import re
import shlex
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional

from .checks import memory_request_mib
from .runs import Config, coarse_twin, configurations, failed_alike, rank, up_to_date
from .safe_io import InputError, make_folders, read_regular, say, write_atomic
from .spec import Spec


class SlurmError(InputError):
    pass


# What SLURM's own syntax allows in each option copied into an #SBATCH line. Those lines are read
# by sbatch, not by a shell, so quoting cannot protect them: anything else (a newline and a command,
# a quote, a blank) is refused.
_NAME = r"[A-Za-z0-9_.-]+"
OPTION_SYNTAX = {
    "partition": (re.compile(rf"{_NAME}(,{_NAME})*"), "partition names (letters, digits, _ - .), comma-separated"),
    "account": (re.compile(_NAME), "an account name (letters, digits, _ - .)"),
    "time": (re.compile(r"[0-9]+(:[0-9]+){0,2}|[0-9]+-[0-9]+(:[0-9]+){0,2}|INFINITE|UNLIMITED"),
             "MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM, D-HH:MM:SS or UNLIMITED"),
}


def check_option(name: str, value: str) -> None:
    pattern, expected = OPTION_SYNTAX[name]
    if len(value) > 256 or not pattern.fullmatch(value):
        raise SlurmError(f"--{name} {value!r}: expected {expected}")


@dataclass
class Options:
    partition: Optional[str] = None
    time: Optional[str] = None        # --time of every run task, e.g. 2:00:00
    account: Optional[str] = None
    cold: bool = False
    retry_failed: bool = False


def pending_by_rank(spec: Spec, root: Path, bhnsid: Optional[str] = None,
                    opt: Optional[Options] = None) -> List[List[Config]]:
    """The configurations not yet converged, by their rho_max rank along the chain; as on the local
    pool, without a failure whose start has not changed (runs.failed_alike) unless retry_failed."""
    opt = opt or Options()
    ranks = [[] for _ in spec.rho_max]
    for c in configurations(spec):
        if up_to_date(spec, c, root / c.relative_dir):
            continue
        if bhnsid and not opt.retry_failed and failed_alike(bhnsid, spec, root, c, warm=not opt.cold):
            continue
        ranks[rank(spec, c.rho_max)].append(c)
    return ranks


def _header(name: str, cpus: int, mem: int, opt: Options, array: Optional[int] = None) -> List[str]:
    # Every value here is a number or passed check_option; the job's log path, which holds the
    # user's directory name, goes on sbatch's command line instead (submit).
    lines = ["#!/bin/bash", f"#SBATCH --job-name={name}", f"#SBATCH --cpus-per-task={cpus}",
             f"#SBATCH --mem={mem}M", "#SBATCH --ntasks=1"]
    if array is not None:
        lines.append(f"#SBATCH --array=0-{array - 1}")
    for key, value in (("partition", opt.partition), ("account", opt.account)):
        if value:
            lines.append(f"#SBATCH --{key}={value}")
    if opt.time and array is not None:
        lines.append(f"#SBATCH --time={opt.time}")
    return lines


def job_prefix(spec: Spec, root: Path) -> str:
    """The job names of this sequence directory: bhnsid-seq-STEM-HASH (HASH of the directory)."""
    digest = hashlib.sha1(str(root.resolve()).encode()).hexdigest()[:8]
    stem = re.sub(r"[^A-Za-z0-9_.-]", "_", spec.file.stem)
    return f"bhnsid-seq-{stem}-{digest}"


def check_paths(root: Path) -> None:
    """A job's log path is a SLURM filename pattern: a backslash turns its %a off (every task would
    write one file), and a control character has no place in a pasted sbatch line."""
    path = str(root.resolve())
    bad = sorted({c for c in path if c == "\\" or ord(c) < 32 or ord(c) == 127})
    if bad:
        raise SlurmError(f"--output {root}: the sequence directory's path holds {''.join(bad)!r}, which a SLURM log "
                         f"path cannot carry; choose a directory without it")


def log_pattern(path: Path) -> str:
    """sbatch --output's pattern for PATH: a % of the directory's name doubled, SLURM's escape."""
    return str(path.resolve().parent).replace("%", "%%") + "/" + path.name


def check_not_queued(spec: Spec, root: Path) -> None:
    """A resubmission rewrites the task lists that queued array tasks still read: refused while any
    job of this sequence directory is queued or running."""
    q = subprocess.run(["squeue", "-h", "-o", "%i %j"], capture_output=True, text=True)
    if q.returncode != 0:
        raise SlurmError(f"squeue: {q.stderr.strip() or 'failed'} (exit {q.returncode})")
    prefix = job_prefix(spec, root)
    mine = [line.split()[0] for line in q.stdout.splitlines() if len(line.split()) > 1 and line.split()[1].startswith(prefix)]
    if mine:
        raise SlurmError(f"{root}: jobs of this sequence are still queued or running ({', '.join(sorted(set(mine)))}); "
                         f"wait for them or scancel them before submitting again")


def write_scripts(tool: str, bhnsid: str, spec: Spec, root: Path, opt: Options,
                  estimates: Dict[int, float]) -> List[Dict]:
    """ROOT/slurm/rankR.sh with its task list rankR.tasks per non-empty rank, and reduce.sh;
    returns [{"script", "kind", "tasks", "log"}] in submission order. ESTIMATES: each grid's
    memory estimate in MiB (checks.check_runs). Every path in a shell line is quoted."""
    for name in OPTION_SYNTAX:
        if getattr(opt, name) is not None:
            check_option(name, getattr(opt, name))
    check_paths(root)
    prefix = job_prefix(spec, root)
    folder = make_folders(root, Path("slurm"))
    cpus = spec.threads if spec.threads > 0 else 1
    jobs = []
    common = [tool, str(spec.file.resolve()), "--output", str(root.resolve()), "--bhnsid", bhnsid]
    for r, pending in enumerate(pending_by_rank(spec, root, bhnsid, opt)):
        # Runs with a coarse twin (none with --cold) in an array of their own after the rest of the rank.
        fine = [c for c in pending if not opt.cold and coarse_twin(spec, c) is not None]
        parts = [("", [c for c in pending if c not in fine], f"after rank {r - 1} (warm starts)"),
                 ("f", fine, f"after rank{r} (their coarse twins) and so after rank {r - 1}")]
        for suffix, configs, after in parts:
            if not configs:
                continue
            mem = max(memory_request_mib(estimates[c.grid_index]) for c in configs)
            name = f"rank{r}{suffix}"
            tasks = folder / f"{name}.tasks"
            write_atomic(tasks, "".join(f"{c.relative_dir}\n" for c in configs))
            cmd = common + (["--cold"] if opt.cold else [])
            text = _header(f"{prefix}-rho{r}{suffix}", cpus, mem, opt, len(configs))
            text += [f"# rho_max = {spec.rho_max[r]:g}: {len(configs)} run(s); {after}",
                     "exec " + " ".join(shlex.quote(w) for w in cmd) + " --task " + shlex.quote(f"{tasks.resolve()}:")
                     + '"$SLURM_ARRAY_TASK_ID"']
            script = folder / f"{name}.sh"
            write_atomic(script, "\n".join(text) + "\n", mode=0o755)
            jobs.append({"script": script, "kind": "runs", "tasks": len(configs), "log": folder / f"{name}_%a.out"})
    reduce_text = _header(f"{prefix}-reduce", 1, 1024, opt)
    reduce_text += ["# splines, minima, error model, tables and figures of whatever converged",
                    "exec " + " ".join(shlex.quote(w) for w in common + ["--reduce-only"])]
    script = folder / "reduce.sh"
    write_atomic(script, "\n".join(reduce_text) + "\n", mode=0o755)
    jobs.append({"script": script, "kind": "reduce", "tasks": 1, "log": folder / "reduce.out"})
    return jobs


def submit(jobs: List[Dict], emit_only: bool, stream=None) -> List[str]:
    """sbatch every script, array r after array r - 1, the reduction after all (afterany: a failed
    configuration is an outcome, the next rank warm-starts from an older neighbour or cold).
    Submitted with an argv (no shell); the printed lines quote every word but the job-id
    variables, which are ours."""
    sbatch = shutil.which("sbatch")
    if not emit_only and not sbatch:
        raise SlurmError("--slurm: no sbatch on PATH (install SLURM's client, or use --emit-only to only write the scripts)")
    ids: List[str] = []
    previous: Optional[str] = None
    for job in jobs:
        # Pasted lines name plain sbatch: they run on the cluster's login node, whose PATH finds its own.
        cmd = ["sbatch" if emit_only or not sbatch else sbatch, "--parsable"]
        after = ids if job["kind"] == "reduce" else ([previous] if previous else [])
        if after:
            cmd.append("--dependency=afterany:" + ":".join(after))
        cmd += [f"--output={log_pattern(job['log'])}", str(job["script"].resolve())]
        if emit_only:
            # Lines a user can paste into a shell: each job id kept in a variable for the next.
            var = job["script"].stem.replace("-", "_")
            words = [shlex.quote(w) if not w.startswith("--dependency") else w for w in cmd]
            say(f"{var}=$({' '.join(words)})", stream)
            ids.append(f"${var}")
            previous = ids[-1]
            continue
        r = subprocess.run(cmd, capture_output=True, text=True, errors="replace", stdin=subprocess.DEVNULL)
        if r.returncode != 0:
            reason = " ".join((r.stderr.strip() or r.stdout.strip()).split())[:300]
            raise SlurmError(f"sbatch {job['script']}: {reason} (exit {r.returncode}); "
                             f"submitted before it: {', '.join(ids) or 'none'}")
        job_id = r.stdout.strip().split(";")[0]
        if not re.fullmatch(r"[0-9]+", job_id):
            raise SlurmError(f"sbatch {job['script']}: answered {job_id[:80]!r}, not a job id; "
                             f"submitted before it: {', '.join(ids) or 'none'}")
        ids.append(job_id)
        previous = job_id
        say(f"submitted {job['script'].name}: job {job_id} ({job['tasks']} task(s))", stream)
    return ids


def task_config(spec: Spec, task: str) -> Config:
    """LIST:K of --task: the K-th configuration named in the task list LIST."""
    path, _, index = task.rpartition(":")
    try:
        if not re.fullmatch(r"[0-9]{1,9}", index):
            raise ValueError(f"the index {index!r} is not a number")
        names = read_regular(path, 1 << 20, follow=True, what="a task list").decode("utf-8").split("\n")
        name = [n for n in names if n][int(index)]
    except (OSError, ValueError, IndexError, InputError) as e:
        reason = e.strerror if isinstance(e, OSError) and e.strerror else str(e) or "no such task"
        raise SlurmError(f"--task {task}: expected TASK_LIST:INDEX of a written task list ({reason})")
    for c in configurations(spec):
        if str(c.relative_dir) == name:
            return c
    raise SlurmError(f"--task {task}: {name} is no configuration of {spec.file}")
