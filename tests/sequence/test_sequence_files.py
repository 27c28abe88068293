"""Every sequence file under parfiles/sequences/ reads (bhnsid_sequence.spec) and every run it would
make passes `bhnsid check` at its first and last configuration of each grid, so none can rot.

usage: test_sequence_files.py BUILD_BIN SOURCE_DIR"""
import subprocess
import sys
from pathlib import Path

bin_dir, source = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
sys.path.insert(0, str(source / "sequence"))
from bhnsid_sequence.runs import configurations, settings  # noqa: E402
from bhnsid_sequence.spec import read_spec  # noqa: E402

failures = []
files = sorted((source / "parfiles" / "sequences").glob("mu*.yaml"))
if not files:
    failures.append("no sequence files in parfiles/sequences")
for f in files:
    spec = read_spec(f)
    configs = configurations(spec)
    ends = []
    for g in range(len(spec.grids)):
        on_grid = [k for k in configs if k.grid_index == g]
        ends += [on_grid[0], on_grid[-1]]
    for c in ends:
        cmd = [str(bin_dir / "bhnsid"), "check", str(spec.base)]
        for k, v in settings(spec, c).items():
            cmd += ["--set", f"{k}={v}"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        ok = r.returncode == 0
        print(("ok   " if ok else "FAIL ") + f"{f.name}: {c.relative_dir}" + ("" if ok else f": {r.stderr.strip()}"))
        if not ok:
            failures.append(f"{f.name}: {c.relative_dir}")
    print(f"ok   {f.name}: {len(configs)} configurations on {len(spec.grids)} grids")
sys.exit(1 if failures else 0)
