#!/bin/sh
# The inner cycles per outer iteration, side by side on the paper example (docs/performance.md):
# each variant of the multigrid's warm start and cycle cap run to convergence at n = N (default 64),
# one JSON line each: wall seconds, outer iterations, finest-level cycles, sigma, Omegahat.
# Usage: bench/outer_cycles.sh [N] [BHNSID]
set -eu
n=${1:-64}
bhnsid=${2:-build/bin/bhnsid}
# N goes into the Python below as an argument, never as code: only a point count is accepted.
case "$n" in ''|*[!0-9]*) echo "outer_cycles.sh: N = '$n': expected a positive whole number of points" >&2; exit 2 ;; esac
dx=$(python3 -c 'import sys; print(3.84 / int(sys.argv[1]))' "$n")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for variant in "warm_start=false loop_cycles=0" "warm_start=true loop_cycles=0 fmg_restart=1" "warm_start=true loop_cycles=0" "warm_start=true loop_cycles=1" \
               "warm_start=true loop_cycles=2" "warm_start=true loop_cycles=3" \
               "warm_start=true loop_cycles=1 fmg_restart=1"; do
  set --
  for s in $variant; do set -- "$@" --set "multigrid.$s"; done
  "$bhnsid" run parfiles/paper_example.yaml --set grid.n="$n" --set grid.dx="$dx" --set ire.exclude_cells=0 \
      "$@" --output "$dir/run" --force > /dev/null 2>&1 || echo "{\"variant\": \"$variant\", \"failed\": true}"
  python3 - "$dir/run" "$variant" <<'PY'
import json, sys
run, variant = sys.argv[1], sys.argv[2]
s = json.load(open(run + "/summary.json"))
t = {l.split("\t")[1]: float(l.split("\t")[3]) for l in open(run + "/timers.tsv") if "\t" in l and not l.startswith("bin")}
print(json.dumps({"variant": variant, "status": s["status"], "seconds": round(t["total"], 2),
                  "ire_seconds": round(t.get("ire.residuals", 0), 2), "outer_iterations": s["iterations"],
                  "cycles": s["scalars"].get("multigrid_cycles_total"), "sigma": s["scalars"].get("sigma"),
                  "omega_hat": s["scalars"].get("omega_hat")}))
PY
done
