"""One `bhnsid run` of a parameter file under parfiles/ with --set overrides, kept when its
summary.json exists (a production script can then be started again and goes on), and its summary.
The run's output goes to OUT.log beside the run directory."""
import json
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_once(exe, out, parfile, sets):
    if not os.path.exists(os.path.join(out, "summary.json")):
        cmd = [exe, "run", os.path.join(ROOT, "parfiles", parfile), "--output", out, "--force"]
        for s in sets:
            cmd += ["--set", s]
        with open(out + ".log", "w") as log:
            subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)
