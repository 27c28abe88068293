#!/usr/bin/env bash
# bench/compare_hypre.sh [N ...]   (default: 63 127 255)
# Runs bhnsid-bench poisson and the hypre peer (PFMG-CG, ../shared/peers/run_hypre.sh) on the same
# problem, interleaved (ours, peer, ours, peer ...) at 1 thread / 1 rank and 2 threads / 2 ranks,
# and prints a Markdown table: seconds (best of 3, setup included), the ratio hypre/ours, our
# cycles, factor and max error (and how far above the converged discrete solution's error it is),
# the smoother's bandwidth and the fraction of the FMG floor reached.
# Environment: PEERS (peer folder), THREADS (default "1 2"), STREAM1/STREAM2 (STREAM triad GB/s on
# 1/2 threads; defaults are BASELINES.md's 41 and 77), OUT (also write the table to this file).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
PEERS="${PEERS:-$ROOT/../shared/peers}"
THREADS="${THREADS:-1 2}"
STREAM1="${STREAM1:-41}"
STREAM2="${STREAM2:-77}"
BENCH="$ROOT/build/bin/bhnsid-bench"
[[ $# -gt 0 ]] || set -- 63 127 255

[[ -x "$BENCH" ]] || { echo "compare_hypre.sh: $BENCH missing; run 'make build' first" >&2; exit 2; }
[[ -x "$PEERS/run_hypre.sh" ]] || { echo "compare_hypre.sh: no peer at $PEERS (set PEERS)" >&2; exit 2; }
"$ROOT/scripts/install-deps.sh" --bench >&2
"$PEERS/build.sh" >&2

echo "# load before the runs: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) CPUs; $(date -u +%FT%TZ)" >&2
table="| N | threads = ranks | bhnsid s | hypre PFMG-CG s | hypre / bhnsid | cycles | factor | max error | vs converged | sweep GB/s | FMG floor s | floor / bhnsid |
|---|---|---|---|---|---|---|---|---|---|---|---|"
for n in "$@"; do
  for t in $THREADS; do
    ours="$("$BENCH" poisson --n "$n" --threads "$t")"
    peer="$(NP="$t" "$PEERS/run_hypre.sh" "$n" | tail -1 | sed 's/.*=//')"
    row="$(python3 - "$ours" "$peer" "$t" "$STREAM1" "$STREAM2" <<'PY'
import json, sys
o = json.loads(sys.argv[1]); peer = float(sys.argv[2]); t = int(sys.argv[3])
stream = float(sys.argv[4] if t == 1 else sys.argv[5]) * 1e9
n = o["n"]
# BASELINES.md: FMG reaches discretization error in about 10 work units of 24-byte sweeps.
floor = 10 * 24 * n**3 / stream
print(f"| {n} | {t} | {o['seconds']:.3f} | {peer:.3f} | {peer / o['seconds']:.1f} | {o['cycles']:.0f} | "
      f"{o['factor']:.3f} | {o['max_error']:.3e} | {100 * o['error_excess']:+.1f} % | {o['sweep_GBps']:.1f} | "
      f"{floor:.3f} | {floor / o['seconds']:.2f} |")
PY
)"
    echo "$row" >&2
    table+=$'\n'"$row"
  done
done
echo "$table"
[[ -z "${OUT:-}" ]] || echo "$table" > "$OUT"
