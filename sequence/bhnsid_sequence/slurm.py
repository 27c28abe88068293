"""A sequence on a SLURM cluster: one job array per rho_max rank (array r holds the r-th rho_max of
every chain of equal grid and xhat_A, so each run starts after the neighbour it warm-starts from;
--dependency=afterany on array r - 1; the runs of grids with a coarse twin in a second array of the
rank, after the first, so that they start from their twins as on the local pool), and the reduction
as a job after all of them. Every task runs
`bhnsid-sequence FILE --output ROOT --task LIST:K`, the same code as the local pool (runs.run_one), so
a resubmission skips what converged and the cluster's results are the local pool's."""
import hashlib
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional

from .report import write_atomic
from .runs import Config, coarse_twin, configurations, failed_alike, settings, up_to_date
from .spec import Spec


class SlurmError(Exception):
    pass


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
        ranks[spec.rho_max.index(c.rho_max)].append(c)
    return ranks


_UNITS = {"B": 1 / 1048576, "KiB": 1 / 1024, "MiB": 1.0, "GiB": 1024.0, "TiB": 1048576.0}


def memory_request_mib(bhnsid: str, spec: Spec, c: Config) -> int:
    """--mem of a run task: `bhnsid check`'s own estimate of the run (every plugin's fields and
    buffers, docs/reliability.md) plus half again and 64 MiB for what it does not count."""
    cmd = [bhnsid, "check", str(spec.base)]
    for k, v in settings(spec, c).items():
        cmd += ["--set", f"{k}={v}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r"memory: estimated ([0-9.]+) (B|KiB|MiB|GiB|TiB)", r.stdout)
    if not m:
        # A submit host smaller than a compute node refuses the run for its own memory: the estimate
        # is in that refusal.
        m = re.search(r"the run needs an estimated ([0-9.]+) (B|KiB|MiB|GiB|TiB), more than", r.stderr)
    if not m:
        raise SlurmError(f"{spec.file}: bhnsid check refused {c.relative_dir}: {(r.stderr or r.stdout).strip()[:300]}")
    return int(math.ceil(1.5 * float(m.group(1)) * _UNITS[m.group(2)] + 64))


def _header(name: str, out: str, cpus: int, mem: int, opt: Options, array: Optional[int] = None) -> List[str]:
    lines = ["#!/bin/bash", f"#SBATCH --job-name={name}", f"#SBATCH --output={out}", f"#SBATCH --cpus-per-task={cpus}",
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
    """#SBATCH lines are split at blanks and give % and quotes meanings of their own."""
    bad = set(str(root.resolve())) & set(" \t\n\"'\\%")
    if bad:
        raise SlurmError(f"--output {root}: the sequence directory's path holds {''.join(sorted(bad))!r}, which SLURM's "
                         f"#SBATCH --output lines cannot carry; choose a directory without it")


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


def write_scripts(tool: str, bhnsid: str, spec: Spec, root: Path, opt: Options) -> List[Dict]:
    """ROOT/slurm/rankR.sh with its task list rankR.tasks per non-empty rank, and reduce.sh;
    returns [{"script", "kind", "tasks"}] in submission order."""
    check_paths(root)
    prefix = job_prefix(spec, root)
    folder = root / "slurm"
    folder.mkdir(parents=True, exist_ok=True)
    cpus = spec.threads if spec.threads > 0 else 1
    mem_by_grid: Dict[int, int] = {}
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
            for c in configs:
                if c.grid_index not in mem_by_grid:
                    mem_by_grid[c.grid_index] = memory_request_mib(bhnsid, spec, c)
            mem = max(mem_by_grid[c.grid_index] for c in configs)
            name = f"rank{r}{suffix}"
            tasks = folder / f"{name}.tasks"
            write_atomic(tasks, "".join(f"{c.relative_dir}\n" for c in configs))
            cmd = common + (["--cold"] if opt.cold else [])
            text = _header(f"{prefix}-rho{r}{suffix}", str((folder / f"{name}_%a.out").resolve()), cpus, mem, opt,
                           len(configs))
            text += [f"# rho_max = {spec.rho_max[r]:g}: {len(configs)} run(s); {after}",
                     "exec " + " ".join(shlex.quote(w) for w in cmd) + " --task " + shlex.quote(f"{tasks.resolve()}:")
                     + '"$SLURM_ARRAY_TASK_ID"']
            script = folder / f"{name}.sh"
            write_atomic(script, "\n".join(text) + "\n")
            os.chmod(script, 0o755)
            jobs.append({"script": script, "kind": "runs", "tasks": len(configs)})
    reduce_text = _header(f"{prefix}-reduce", str((folder / "reduce.out").resolve()), 1, 1024, opt)
    reduce_text += ["# splines, minima, error model, tables and figures of whatever converged",
                    "exec " + " ".join(shlex.quote(w) for w in common + ["--reduce-only"])]
    script = folder / "reduce.sh"
    write_atomic(script, "\n".join(reduce_text) + "\n")
    os.chmod(script, 0o755)
    jobs.append({"script": script, "kind": "reduce", "tasks": 1})
    return jobs


def submit(jobs: List[Dict], emit_only: bool, stream=sys.stdout) -> List[str]:
    """sbatch every script, array r after array r - 1, the reduction after all (afterany: a failed
    configuration is an outcome, the next rank warm-starts from an older neighbour or cold)."""
    sbatch = shutil.which("sbatch")
    if not emit_only and not sbatch:
        raise SlurmError("--slurm: no sbatch on PATH (install SLURM's client, or use --emit-only to only write the scripts)")
    ids: List[str] = []
    previous: Optional[str] = None
    for job in jobs:
        cmd = [sbatch or "sbatch", "--parsable"]
        after = ids if job["kind"] == "reduce" else ([previous] if previous else [])
        if after:
            cmd.append("--dependency=afterany:" + ":".join(after))
        cmd.append(str(job["script"]))
        if emit_only:
            # Lines a user can paste into a shell: each job id kept in a variable for the next.
            var = job["script"].stem.replace("-", "_")
            words = [shlex.quote(w) if not w.startswith("--dependency") else w for w in cmd]
            print(f"{var}=$({' '.join(words)})", file=stream)
            ids.append(f"${var}")
            previous = ids[-1]
            continue
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise SlurmError(f"sbatch {job['script']}: {r.stderr.strip() or r.stdout.strip()} (exit {r.returncode}); "
                             f"submitted before it: {', '.join(ids) or 'none'}")
        job_id = r.stdout.strip().split(";")[0]
        ids.append(job_id)
        previous = job_id
        print(f"submitted {job['script'].name}: job {job_id} ({job['tasks']} task(s))", file=stream)
    return ids


def task_config(spec: Spec, task: str) -> Config:
    """LIST:K of --task: the K-th configuration named in the task list LIST."""
    path, _, index = task.rpartition(":")
    try:
        names = Path(path).read_text().split("\n")
        name = [n for n in names if n][int(index)]
    except (OSError, ValueError, IndexError) as e:
        raise SlurmError(f"--task {task}: expected TASK_LIST:INDEX of a written task list ({e})")
    for c in configurations(spec):
        if str(c.relative_dir) == name:
            return c
    raise SlurmError(f"--task {task}: {name} is no configuration of {spec.file}")
