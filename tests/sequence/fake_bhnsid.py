#!/usr/bin/python3
"""A stand-in for bhnsid in the sequence tool's tests, quick and scriptable through the
environment: `check` passes (a memory estimate of 1 MiB); `run` writes what `bhnsid run` writes
(summary.json with its command line, timers.tsv, a checkpoint) and converges.

FAKE_PIDS=DIR      each run writes DIR/PID and, per signal received, a line "SIGNUM" to DIR/PID.signals
FAKE_SLEEP=S       each run lasts S seconds; a stop signal ends it at its "safe point": summary
                   "interrupted", exit 128 + N
FAKE_STOP_SECONDS=T  the safe point is T seconds after the first signal; a second signal exits at once
                   (as bhnsid does), without a summary
FAKE_CHECK_FAIL=TEXT `check` refuses any run whose arguments hold TEXT"""
import json
import os
import shlex
import signal
import sys
import time
from pathlib import Path

args = sys.argv[1:]
if args[:1] == ["check"]:
    refuse = os.environ.get("FAKE_CHECK_FAIL")
    if refuse and any(refuse in a for a in args):
        print(f"bhnsid: error: --set {refuse}: refused by the stand-in", file=sys.stderr)
        sys.exit(2)
    print("memory: estimated 1.0 MiB of 1.0 GiB available (stand-in)")
    sys.exit(0)
if args[:1] != ["run"]:
    sys.exit(2)
out = Path(args[args.index("--output") + 1])
if out.exists() and "--force" not in args:
    print(f"bhnsid: error: {out}: exists", file=sys.stderr)
    sys.exit(2)
out.mkdir(parents=True, exist_ok=True)
pids = os.environ.get("FAKE_PIDS")
if pids:
    Path(pids, str(os.getpid())).write_text(str(out))
received = []


def on_signal(signum, frame):
    received.append(signum)
    if pids:
        with open(Path(pids, f"{os.getpid()}.signals"), "a") as f:
            f.write(f"{signum}\n")
    if len(received) > 1:
        os._exit(128 + signum)  # a second request: at once, no summary


for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
    signal.signal(s, on_signal)


def summary(status):
    (out / "summary.json").write_text(json.dumps({
        "status": status, "message": "" if status == "converged" else f"stopped ({status})",
        "scalars": {}, "provenance": {"command_line": shlex.join(sys.argv)}}))


end = time.monotonic() + float(os.environ.get("FAKE_SLEEP", "0"))
while time.monotonic() < end:
    if received:
        time.sleep(float(os.environ.get("FAKE_STOP_SECONDS", "0")))
        summary("interrupted")
        sys.exit(128 + received[0])
    time.sleep(0.02)
(out / "checkpoints").mkdir(exist_ok=True)
(out / "checkpoints" / "checkpoint.000001").write_bytes(b"x" * 100)
(out / "timers.tsv").write_text("name\tcalls\tmean\ttotal\nTOTAL\t1\t0.01\t0.01\n")
summary("converged")
