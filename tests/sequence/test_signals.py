"""SIGTERM, SIGINT and SIGHUP to `bhnsid sequence`: every running run receives the signal exactly
once (a terminal's Ctrl-C to the whole process group and `timeout`'s double delivery included),
stops at its safe point, is waited for, and no new run starts; the sequence exits 128 + N and no
run survives it. A person's second Ctrl-C is passed on too (the runs exit at once). First with a
stand-in bhnsid whose runs wait to be stopped and count the signals they receive, then with the
real one on a tiny sequence of the quickstart.

usage: test_signals.py BUILD_BIN SOURCE_DIR WORK_DIR"""
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from checklist import Checklist, arguments, stand_in_bhnsid  # noqa: E402

bin_dir, source, work, bhnsid = arguments()
check = Checklist()
fake = stand_in_bhnsid(work)


def sequence_file(name, base, grids="[{n: 24, dx: 0.16}]"):
    f = work / name
    f.write_text(f"sequence:\n  base: {base}\n  mass_ratio: 1.0\n  x_a: [0.25, 0.3, 0.35]\n"
                 f"  rho_max: [0.08, 0.09]\n  targets: [0.6]\n  grids: {grids}\n  threads: 1\n")
    return f


def alive(pid):
    try:
        return Path(f"/proc/{pid}/stat").read_text().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


def wait_for(test, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if test():
            return True
        time.sleep(0.05)
    return False


base = work / "base.yaml"
base.write_text("grid: {n: 24}\n")
spec = sequence_file("fake.yaml", base)


def stop_fake(name, send, expect_rc, expect_signals, stop_seconds="0"):
    """Starts the sequence (two runs at a time, each 60 s unless stopped), SEND(process) once both
    runs are going, and checks what follows."""
    pids = work / f"pids_{name}"
    pids.mkdir()
    env = dict(os.environ, FAKE_PIDS=str(pids), FAKE_SLEEP="60", FAKE_STOP_SECONDS=stop_seconds)
    p = subprocess.Popen([bhnsid, "sequence", str(spec), "--output", str(work / name), "--jobs", "2", "--bhnsid", str(fake)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, start_new_session=True)
    started = wait_for(lambda: len([f for f in pids.iterdir() if f.name.isdigit()]) == 2, 30)
    check(started, f"{name}: two runs started")
    if started:
        send(p)
    try:
        _, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        _, err = p.communicate()
    runs = [f for f in pids.iterdir() if f.name.isdigit()]
    print(err[-800:])
    check(p.returncode == expect_rc, f"{name}: exit {p.returncode}, expected {expect_rc}")
    check("Traceback" not in err, f"{name}: no traceback")
    check(len(runs) == 2, f"{name}: no run started after the signal ({len(runs)} started)")
    check(not any(alive(int(f.name)) for f in runs), f"{name}: no run outlives the sequence")
    got = [(pids / f"{f.name}.signals").read_text().split() if (pids / f"{f.name}.signals").exists() else []
           for f in runs]
    check(len(got) == 2 and all(g == expect_signals for g in got), f"{name}: each run received {expect_signals} ({got})")
    return runs


runs = stop_fake("sigterm", lambda p: os.kill(p.pid, signal.SIGTERM), 143, ["15"])
check(all(json.loads((Path(f.read_text()) / "summary.json").read_text())["status"] == "interrupted" for f in runs),
      "sigterm: each run stopped at its safe point (summary 'interrupted')")
stop_fake("ctrl_c", lambda p: os.killpg(p.pid, signal.SIGINT), 130, ["2"])
stop_fake("sighup", lambda p: os.kill(p.pid, signal.SIGHUP), 129, ["1"])


def timeout_style(p):
    os.kill(p.pid, signal.SIGTERM)  # what `timeout` does: the child, then its process group
    os.killpg(p.pid, signal.SIGTERM)


stop_fake("double_delivery", timeout_style, 143, ["15"])


def second_ctrl_c(p):
    os.killpg(p.pid, signal.SIGINT)
    time.sleep(0.5)
    os.killpg(p.pid, signal.SIGINT)


stop_fake("second_ctrl_c", second_ctrl_c, 130, ["2", "2"], stop_seconds="20")

# The real bhnsid: a run of the quickstart at n = 24 stops between multigrid cycles.
real = sequence_file("real.yaml", source / "parfiles" / "quickstart.yaml")
seq = work / "real"
p = subprocess.Popen([bhnsid, "sequence", str(real), "--output", str(seq), "--jobs", "2"], stdout=subprocess.PIPE,
                     stderr=subprocess.PIPE, text=True)


def children():
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                if str(seq).encode() in (d / "cmdline").read_bytes() and int(d.name) != p.pid and alive(int(d.name)):
                    out.append(int(d.name))
            except OSError:
                pass
    return out


check(wait_for(lambda: len(children()) > 0 and any(seq.glob("grid*/xa*/rho*/params.yaml")), 60),
      "real: a bhnsid run started")
going = children()
p.send_signal(signal.SIGTERM)
try:
    _, err = p.communicate(timeout=60)
except subprocess.TimeoutExpired:
    p.kill()
    _, err = p.communicate()
print(err[-800:])
check(p.returncode == 143, f"real: exit {p.returncode}, expected 143")
check(not any(alive(pid) for pid in going) and not children(), f"real: no bhnsid run survives ({going})")
statuses = [json.loads(s.read_text())["status"] for s in seq.glob("grid*/xa*/rho*/summary.json")]
check("interrupted" in statuses, f"real: the running run stopped at its safe point ({statuses})")
check.exit()
