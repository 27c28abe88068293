"""Every run of the sequence checked by `bhnsid check` before any runs: on each grid, every xhat_A
and every rho_max passes once (with the `set:` overrides of every run), so a value the core
refuses is one error at the start rather than a run refused one by one and reported as an
outcome. `check` also gives each grid's memory estimate, which --slurm requests."""
import math
import re
import subprocess
from typing import Dict

from .runs import Config, settings
from .safe_io import InputError
from .signals import STOP
from .spec import Spec, key

_UNITS = {"B": 1 / 1048576, "KiB": 1 / 1024, "MiB": 1.0, "GiB": 1024.0, "TiB": 1048576.0}
_ESTIMATE = re.compile(r"memory: estimated ([0-9.]+) (B|KiB|MiB|GiB|TiB)")
# A submit host smaller than a compute node refuses the run for its own memory: the estimate is
# in that refusal, and on a cluster the run is still possible.
_TOO_LARGE_HERE = re.compile(r"the run needs an estimated ([0-9.]+) (B|KiB|MiB|GiB|TiB), more than")


def check_runs(bhnsid: str, spec: Spec, elsewhere: bool = False) -> Dict[int, float]:
    """The estimated MiB of a run on each grid (by grid index). A configuration `bhnsid check`
    refuses is an InputError naming it and the core's own reason; ELSEWHERE (runs on a cluster's
    nodes) accepts a refusal for this machine's memory. Returns early, with what it has, when a
    stop signal arrives."""
    estimates: Dict[int, float] = {}
    for g, grid in enumerate(spec.grids):
        for i in range(max(len(spec.x_a), len(spec.rho_max))):
            if STOP.signum:
                return estimates
            c = Config(g, grid, spec.x_a[i % len(spec.x_a)], spec.rho_max[i % len(spec.rho_max)])
            mib = _check(bhnsid, spec, c, elsewhere)
            estimates[g] = max(estimates.get(g, 0.0), mib)
    return estimates


def _check(bhnsid: str, spec: Spec, c: Config, elsewhere: bool) -> float:
    cmd = [bhnsid, "check", str(spec.base)]
    for k, v in settings(spec, c).items():
        cmd += ["--set", f"{k}={v}"]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, errors="replace", stdin=subprocess.DEVNULL)
    except OSError as e:
        raise InputError(f"{bhnsid}: cannot run bhnsid check: {e.strerror}")
    m = _ESTIMATE.search(r.stdout) if r.returncode == 0 else None
    if m is None and r.returncode == 2 and elsewhere:
        m = _TOO_LARGE_HERE.search(r.stderr)
    if m is not None:
        return float(m.group(1)) * _UNITS[m.group(2)]
    if r.returncode >= 128 or r.returncode < 0:
        return math.nan  # stopped by a signal: the caller sees STOP
    lines = (r.stderr or r.stdout).strip().splitlines()
    reason = lines[0] if lines else f"exit {r.returncode} and no message"
    reason = reason[len("bhnsid: error: "):] if reason.startswith("bhnsid: error: ") else reason
    raise InputError(f"{spec.file}: bhnsid check refuses the run of grid {c.grid.name}, x_a = {key(c.x_a)}, "
                     f"rho_max = {key(c.rho_max)}: {reason}")


def memory_request_mib(estimate_mib: float) -> int:
    """--mem of a run task: `bhnsid check`'s own estimate of the run (every plugin's fields and
    buffers, docs/reliability.md) plus half again and 64 MiB for what it does not count."""
    return int(math.ceil(1.5 * estimate_mib + 64))
