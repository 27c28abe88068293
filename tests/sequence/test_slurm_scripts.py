"""bhnsid sequence --slurm without a cluster: the batch scripts (--emit-only) and the submissions to a
stand-in sbatch that records its arguments: one array per rho_max rank with the runs not yet
converged, each after the previous rank (warm starts), the reduction after all; the memory request
from `bhnsid check`'s estimate; --cold forwarded; bad flags refused. The real cluster: make test-slurm.

usage: test_slurm_scripts.py BUILD_BIN SOURCE_DIR WORK_DIR"""
import os
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "sequence"))
from checklist import Checklist, arguments  # noqa: E402

bin_dir, source, work, bhnsid = arguments()
check = Checklist()


spec = work / "tiny.yaml"
spec.write_text(f"""sequence:
  base: {source}/parfiles/quickstart.yaml
  mass_ratio: 1.0
  x_a: [0.25, 0.35]
  rho_max: [0.08, 0.09, 0.1]
  targets: [0.6]
  grids: [{{n: 24, dx: 0.16}}, {{n: 20, dx: 0.192}}]
  threads: 2
""")

r = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "emit"), "--slurm", "--emit-only", "--cold",
                    "--partition", "short", "--time", "0:30:00"], capture_output=True, text=True)
print(r.stdout, r.stderr)
check(r.returncode == 0, "--emit-only exits 0")
folder = work / "emit" / "slurm"
check(sorted(p.name for p in folder.glob("*.sh")) == ["rank0.sh", "rank1.sh", "rank2.sh", "reduce.sh"],
      "one script per rho_max rank and the reduction")
rank0 = (folder / "rank0.sh").read_text()
check("#SBATCH --array=0-3" in rank0, "rank 0 holds the 4 chains (2 grids x 2 xhat_A)")
check((folder / "rank0.tasks").read_text().split() == ["grid0_n24_dx0.16/xa0.25/rho0.08", "grid0_n24_dx0.16/xa0.35/rho0.08",
                                                       "grid1_n20_dx0.192/xa0.25/rho0.08", "grid1_n20_dx0.192/xa0.35/rho0.08"],
      "its task list names the configurations")
check("#SBATCH --cpus-per-task=2" in rank0 and "#SBATCH --partition=short" in rank0 and "#SBATCH --time=0:30:00" in rank0,
      "threads, partition and time limit requested")
mem = re.search(r"#SBATCH --mem=(\d+)M", rank0)
check(mem is not None and 64 < int(mem.group(1)) < 2048, f"a memory request from bhnsid check's estimate ({mem and mem.group(0)})")
check("--cold" in rank0 and '"$SLURM_ARRAY_TASK_ID"' in rank0, "--cold and the array index reach the task")
lines = [l for l in r.stdout.splitlines() if "sbatch --parsable" in l]
check(len(lines) == 4 and lines[0].startswith("rank0=$(") and "--dependency" not in lines[0]
      and "--dependency=afterany:$rank0 " in lines[1] and "--dependency=afterany:$rank1 " in lines[2]
      and "--dependency=afterany:$rank0:$rank1:$rank2 " in lines[3],
      "the printed sbatch commands chain the ranks and the reduction, ready to paste")
check(not (work / "emit" / "grid0_n24_dx0.16").exists(), "--emit-only runs nothing")

# A stand-in sbatch: records its arguments, answers job ids 101, 102, ...
fake = work / "fakebin"
fake.mkdir()
log = work / "sbatch.log"
(fake / "sbatch").write_text(f"""#!/bin/sh
n=$(wc -l < {log} 2>/dev/null || echo 0)
echo "$@" >> {log}
echo $((101 + n))
""")
os.chmod(fake / "sbatch", 0o755)
queue = work / "queue.txt"
queue.write_text("")
(fake / "squeue").write_text(f"#!/bin/sh\ncat {queue}\n")
os.chmod(fake / "squeue", 0o755)
env = dict(os.environ, PATH=f"{fake}:{os.environ['PATH']}")
s = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "sub"), "--slurm"], capture_output=True, text=True,
                   env=env)
print(s.stdout, s.stderr)
check(s.returncode == 0, "--slurm exits 0 with an sbatch that accepts")
calls = log.read_text().splitlines()
check(len(calls) == 4, "four submissions")
check(calls[1].startswith("--parsable --dependency=afterany:101 ") and calls[2].startswith("--parsable --dependency=afterany:102 "),
      "rank r after rank r - 1")
check(calls[3].startswith("--parsable --dependency=afterany:101:102:103 ") and calls[3].endswith("reduce.sh"),
      "the reduction after every array")
check("job 104" in s.stdout and "squeue -j 101,102,103,104" in s.stdout, "job ids reported")

name = re.search(r"#SBATCH --job-name=(\S+)", (work / "sub" / "slurm" / "rank0.sh").read_text()).group(1)
check(name.startswith("bhnsid-seq-tiny-") and name.endswith("-rho0"), f"job names carry the sequence and its directory ({name})")
queue.write_text(f"101_2 {name}\n")
busy = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "sub"), "--slurm"], capture_output=True,
                      text=True, env=env)
check(busy.returncode == 2 and "still queued or running (101_2)" in busy.stderr,
      "a resubmission while the sequence's jobs are queued is refused (their task lists would change)")
queue.write_text("")
check(re.search(r"--output=\S*/sub/slurm/rank0_%a\.out \S*/rank0\.sh$", calls[0]) is not None,
      "each array's log path (SLURM's %a pattern) on sbatch's command line")

# One task of an array, as slurmd would start it: runs that configuration exactly as the local pool.
task = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "sub"), "--task",
                       f"{work / 'sub' / 'slurm' / 'rank0.tasks'}:1"], capture_output=True, text=True)
print(task.stdout, task.stderr)
check(task.returncode == 0 and "grid0_n24_dx0.16/xa0.35/rho0.08: converged" in task.stdout, "a task runs its configuration")
# Resubmission: the converged configuration is left out.
log.unlink()
again = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "sub"), "--slurm"], capture_output=True,
                       text=True, env=env)
check(again.returncode == 0 and "#SBATCH --array=0-2" in (work / "sub" / "slurm" / "rank0.sh").read_text(),
      "a resubmission leaves out what converged")

bad = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "x"), "--task", "nowhere:0"], capture_output=True,
                     text=True)
check(bad.returncode == 2 and "--task nowhere:0" in bad.stderr, "a bad task is one error")
no = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "y"), "--slurm"], capture_output=True, text=True,
                    env=dict(os.environ, PATH="/nonexistent"))
check(no.returncode == 2 and "no sbatch" in no.stderr, "no sbatch: one error naming it")
# Grids with a coarse twin (48, 0.08) of (24, 0.16): their runs in a second array of the rank, after
# their twins' array and before the next rank.
twins = work / "twins.yaml"
twins.write_text(spec.read_text().replace("{n: 20, dx: 0.192}", "{n: 48, dx: 0.08}"))
t = subprocess.run([bhnsid, "sequence", str(twins), "--output", str(work / "twins"), "--slurm", "--emit-only"],
                   capture_output=True, text=True)
tf = work / "twins" / "slurm"
check(t.returncode == 0 and sorted(p.name for p in tf.glob("rank0*.tasks")) == ["rank0.tasks", "rank0f.tasks"]
      and all(line.startswith("grid1_n48") for line in (tf / "rank0f.tasks").read_text().split())
      and all(line.startswith("grid0_n24") for line in (tf / "rank0.tasks").read_text().split()),
      "the fine grid's runs of a rank in an array of their own")
order = [line.split("=")[0] for line in t.stdout.splitlines() if "=$(" in line]
check(order[:4] == ["rank0", "rank0f", "rank1", "rank1f"], f"the twins' array before the fine one, rank by rank: {order}")
e = subprocess.run([bhnsid, "sequence", str(spec), "--emit-only"], capture_output=True, text=True, cwd=work)
check(e.returncode == 2 and "--emit-only" in e.stderr, "--emit-only without --slurm is refused")
check.exit()
