"""make test-slurm: a tiny sequence on a real SLURM cluster (scripts/slurm-local.sh: slurmctld, slurmd
and munge on this machine) end to end, then the same sequence on the local pool: every configuration
converged in both, the job arrays ran each rho_max rank after the previous one (the warm starts), the
reduction ran as its own job, and the cluster's numbers equal the local pool's (one thread per run:
the same operations in the same order, so to the last bit).

usage: test_slurm.py BUILD_BIN SOURCE_DIR WORK_DIR"""
import json
import subprocess
import sys
import time
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
  rho_max: [0.07, 0.08, 0.09, 0.1]
  targets: [0.6, 0.62]
  grids: [{{n: 32, dx: 0.12}}, {{n: 28, dx: 0.137142857142857}}, {{n: 24, dx: 0.12}}]
  threads: 1
""")
cluster, local = work / "cluster", work / "local"
start = time.time()
r = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(cluster), "--slurm"], capture_output=True, text=True)
print(r.stdout, r.stderr, flush=True)
check(r.returncode == 0, "bhnsid sequence --slurm submits")
if r.returncode != 0:
    sys.exit(1)
ids = [line.split("job ")[1].split()[0] for line in r.stdout.splitlines() if line.startswith("submitted ")]
check(len(ids) == 5, f"four rho_max ranks and the reduction submitted ({ids})")

# Wait for every job to leave the queue (10 minutes at most: 24 runs of a second or two each).
deadline = time.time() + 600
while time.time() < deadline:
    q = subprocess.run(["squeue", "-h", "-j", ",".join(ids), "-o", "%i %T"], capture_output=True, text=True)
    if q.returncode == 0 and not q.stdout.strip():
        break
    time.sleep(2)
else:
    check(False, "the jobs left the queue within 10 minutes")
    subprocess.run(["scancel"] + ids)
    sys.exit(1)
print(f"cluster: {time.time() - start:.0f} s", flush=True)
check((cluster / "sequence.json").exists() and (cluster / "slurm" / "reduce.out").exists(),
      "the reduction job wrote sequence.json")

# Each rank after the one before: a run's log starts after its chain predecessor's summary was written.
order_ok = True
for g in sorted(p.name for p in cluster.glob("grid*_n*") if p.is_dir()):
    for xa in ("xa0.25", "xa0.35"):
        previous_end = 0.0
        for rho in ("rho0.07", "rho0.08", "rho0.09", "rho0.1"):
            d = cluster / g / xa / rho
            began = (d / "params.yaml").stat().st_mtime
            order_ok &= began >= previous_end
            previous_end = (d / "summary.json").stat().st_mtime
check(order_ok, "every run began after its lower-rho_max neighbour ended (the dependencies held)")
warm = sum("warm start from" in p.read_text() for p in cluster.glob("grid*/xa*/rho*/log.txt"))
check(warm == 18, f"18 of 24 runs warm-started from their neighbour ({warm})")

l = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(local), "--jobs", "2"], capture_output=True, text=True)
print(l.stdout, l.stderr[-1500:], flush=True)
check(l.returncode == 0, "the same sequence on the local pool")
a = json.loads((cluster / "sequence.json").read_text())
b = json.loads((local / "sequence.json").read_text())
check([x["status"] for x in a["runs"]].count("converged") == 24, "every configuration converged on the cluster")
check([x["status"] for x in b["runs"]].count("converged") == 24, "and on the local pool")
check(a["at_targets"] == b["at_targets"], "the splined quantities at the targets are the same to the bit")
check(a["minima"] == b["minima"] and a["isco"] == b["isco"], "the minima and the error model are the same to the bit")
check((cluster / "table_min_E_b.md").read_text() == (local / "table_min_E_b.md").read_text(), "the tables are the same")

again = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(cluster), "--slurm"], capture_output=True, text=True)
check(again.returncode == 0 and "nothing to submit" in again.stdout, "a second --slurm finds every run converged: nothing submitted")
check.exit()
