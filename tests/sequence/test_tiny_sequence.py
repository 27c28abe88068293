"""A tiny sequence end to end through `bhnsid sequence`: coarse grids of the quickstart binary,
three xhat_A and four rho_max, three target masses (one out of range) and three grids, run on a pool of two; then the
checks a user would make: every run directory converged, the splines' targets inside the computed
range, the error model's three grids, a minimum or the reason for none, the tables and figures
written; a second call skips every converged run; bad input is one error line.

usage: test_tiny_sequence.py BUILD_BIN SOURCE_DIR WORK_DIR"""
import json
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "sequence"))
from checklist import Checklist, arguments  # noqa: E402

bin_dir, source, work, bhnsid = arguments()

spec = work / "tiny.yaml"
spec.write_text(f"""sequence:
  base: {source}/parfiles/quickstart.yaml
  mass_ratio: 1.0
  x_a: [0.15, 0.25, 0.35]
  rho_max: [0.07, 0.08, 0.09, 0.10]
  targets: [0.6, 0.62, 0.99]
  grids: [{{n: 32, dx: 0.12}}, {{n: 28, dx: 0.137142857142857}}, {{n: 24, dx: 0.12}}]
  threads: 1
""")
check = Checklist()


r = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "seq"), "--jobs", "2"],
                   capture_output=True, text=True)
print(r.stdout[-3000:], r.stderr[-3000:])
check(r.returncode == 0, "bhnsid sequence exits 0")
if r.returncode != 0:
    sys.exit(1)
check("0 running" in r.stderr and "failed of 36" in r.stderr,
      "progress lines count done / running / failed / total")
doc = json.loads((work / "seq" / "sequence.json").read_text())
statuses = [run["status"] for run in doc["runs"]]
check(len(statuses) == 36, "36 configurations")
check(statuses.count("converged") == 36, f"all converged ({statuses.count('converged')} of 36)")
# (M0)_max of the Gamma = 2, K = 1 polytrope: 0.179862 (physics-notes §6.1, tov.py).
check(abs(doc["m0_max"] - 0.179862) < 2e-4, f"(M0)_max = {doc['m0_max']} vs 0.179862 (TOV)")
finest = doc["at_targets"]["n32_dx0.12"]
check(all("E_b" in finest[xa]["0.6"] for xa in finest), "every xhat_A has E_b at M0 = 0.6 (M0)_max")
check(all("outside the computed range" in finest[xa]["0.99"]["reason"] for xa in finest),
      "M0 = 0.99 (M0)_max is reported outside the computed range, not extrapolated")
isco = doc["isco"]["0.6"]["E_b"]
has_minimum = "E_b" in isco and isco["E_b"]["error"] is not None
check(has_minimum or "no interior minimum" in isco.get("reason", ""), "a minimum with an error bar, or why not")
if has_minimum:
    e = isco["E_b"]
    check(e["error"] >= abs(e["value"] - e["q_exact"]) - 1e-15, "the error bar is at least |Q_n - Q_e|")
    om = isco["Omega_M0"]
    check(min(p for p in om["per_grid"]) > 0, "Omega M0 at the minimum is positive on every grid")
for name in ("table_min_E_b.md", "table_min_E_b.csv", "table_min_J.md", "failures.md", "eb.png", "j.png"):
    check((work / "seq" / name).stat().st_size > 0, f"{name} written")
check("| mu_bn | M0/(M0)_max | E_b | J_over_M0sq | Omega_M0 | rho_max | x_a | C_B | sigma | P_y_BH |"
      in (work / "seq" / "table_min_E_b.md").read_text(), "Table I and II columns")

again = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "seq")], capture_output=True, text=True)
check(again.returncode == 0 and "already converged, skipped" in again.stderr, "a second call skips the converged runs")
check(json.loads((work / "seq" / "sequence.json").read_text())["isco"] == doc["isco"], "and reduces to the same answer")

bad = work / "bad.yaml"
bad.write_text("sequence:\n  base: nowhere.yaml\n  mass_ratio: 1\n  x_a: [0.1]\n  rho_max: [0.1]\n  targets: [0.5]\n")
b = subprocess.run([bhnsid, "sequence", str(bad)], capture_output=True, text=True, cwd=work)
check(b.returncode == 2 and b.stderr.count("\n") == 1 and "sequence.base" in b.stderr and str(bad) in b.stderr,
      f"bad input: one error naming the file and the key ({b.stderr.strip()})")
(work / "foreign").mkdir()
(work / "foreign" / "thesis.tex").write_text("x")
f = subprocess.run([bhnsid, "sequence", str(spec), "--output", str(work / "foreign")], capture_output=True, text=True)
check(f.returncode == 2 and "not a sequence directory" in f.stderr, "a foreign folder is refused")

check.exit()
