#!/usr/bin/env python3
"""Replays the hostile-user corpus (cases.py) against bhnsid-export, the Python reader, bhnsid plot
and plot_validate.py. Every case runs in a fresh folder of its own, and besides its own expectation
(exit code, a fragment of the message) is held to what docs/reliability.md promises of every command:

- a failure is one line on stderr, and no output ever holds a Python traceback;
- nothing is written through a symbolic link: every case has a file `victim` outside its folder,
  the target of every link a case makes, and it must come out unchanged;
- no name reaches a shell: no file PWNED appears (cases put `$(touch PWNED)` in names);
- no temporary of ours is left behind (`.NAME.partial-XXXXXX`, `.plot-XXXXXX`, ...);
- a FIFO or a device is refused at once (every case ends within 10 s; a hang is killed at 30 s).

    /usr/bin/python3 replay.py --export EXE --bhnsid EXE --run RUN_DIR --work DIR [--class NAME]...

--class selects the cases of one class (cases.CLASSES); without it every case runs. The reader's
cases run `replay.py --reader-driver MODULE_DIR PATH EXPRESSION` in a process of their own.
"""

import argparse
import collections
import os
import re
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
VICTIM_TEXT = "precious: a file of the user's that no case may change\n"
# Names of our own temporaries, which must never outlive a command.
OURS = re.compile(r"(\.partial-\w{6}$)|(^\.plot-\w{6}$)|(^\.bhnsid-plots\.\w{6}$)|(^\..+\.png\.\w+\.tmp$)")


def reader_driver(module_dir, path, expression):
    """Evaluates EXPRESSION with Reader, P (the path) and np; ReaderError is the only failure allowed
    (any other exception escapes with its traceback, which the replay counts as a failure)."""
    sys.path.insert(0, module_dir)
    import numpy as np
    import bhnsid_reader

    scope = {"Reader": bhnsid_reader.Reader, "P": path, "np": np}
    try:
        eval(expression, scope)  # noqa: S307 - the corpus's own expressions
    except bhnsid_reader.ReaderError as e:
        print("ReaderError %d: %s" % (e.code, str(e).replace("\n", "\\n")), file=sys.stderr)
        return 1
    print("OK")
    return 0


class Fixture:
    def __init__(self, args):
        self.export, self.bhnsid = os.path.abspath(args.export), os.path.abspath(args.bhnsid)
        self.run = os.path.abspath(args.run)
        self.data = os.path.join(self.run, "data.h5")
        self.work = os.path.abspath(args.work)
        self.module = os.path.join(SOURCE, "reader", "python")
        self.plot_validate = os.path.join(SOURCE, "scripts", "plot_validate.py")

    def command(self, tool, args):
        if tool == "export":
            return [self.export] + args
        if tool == "plot":
            return [self.bhnsid, "plot"] + args
        if tool == "pv":
            return ["/usr/bin/python3", self.plot_validate] + args
        if tool == "py":
            return ["/usr/bin/python3", os.path.abspath(__file__), "--reader-driver", self.module] + args
        raise ValueError(tool)


def substitute(template, values):
    return re.sub(r"\{(\w+)\}", lambda m: str(values[m.group(1)]), template)


def end_session(sid):
    """SIGKILL to every process of session `sid` (ours: started with start_new_session)."""
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open("/proc/%s/stat" % pid) as f:
                fields = f.read().rsplit(")", 1)[1].split()
            if int(fields[3]) == sid:  # the session id, after state, ppid, pgrp
                os.kill(int(pid), signal.SIGKILL)
        except (OSError, ValueError, IndexError):
            pass


def run_case(fx, case):
    """Runs one case; a list of what went wrong (empty: passed)."""
    w = os.path.join(fx.work, case.id)
    victims = os.path.join(fx.work, "victims", case.id)
    for d in (w, victims):
        if os.path.lexists(d):
            shutil.rmtree(d)
        os.makedirs(d)
    victim = os.path.join(victims, "victim")
    with open(victim, "w") as f:
        f.write(VICTIM_TEXT)
    values = {"w": w, "data": fx.data, "run": fx.run, "victim": victim, "bhnsid": fx.bhnsid}
    values.update(case.setup(w, values) or {})
    args = [substitute(a, values) for a in case.args]
    before = {os.path.join(r, n) for r, ds, fs in os.walk(w) for n in ds + fs}
    start = time.monotonic()
    # A session of its own: a hung case is ended with everything it started (a plot script too).
    p = subprocess.Popen(fx.command(case.tool, args), cwd=w, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         start_new_session=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    try:
        out, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        end_session(p.pid)
        p.communicate()
        return ["hung: killed after 30 s"]
    rc, out, err = p.returncode, out.decode("utf-8", "replace"), err.decode("utf-8", "replace")
    elapsed = time.monotonic() - start
    problems = []
    expected = case.rc if isinstance(case.rc, tuple) else (case.rc,)
    if rc not in expected:
        problems.append("exit %d, expected %s" % (rc, " or ".join(map(str, expected))))
    if "Traceback" in out + err:
        problems.append("a Python traceback")
    lines = [line for line in err.splitlines() if line.strip()]
    if rc != 0 and len(lines) != 1:
        problems.append("%d lines on stderr, expected one" % len(lines))
    if case.text and case.text not in err + out:
        problems.append("the message lacks %r" % case.text)
    if case.absent and case.absent in err + out:
        problems.append("the message holds %r" % case.absent)
    if elapsed > 10:
        problems.append("took %.1f s (a FIFO waited on, an endless input read?)" % elapsed)
    with open(victim, "rb") as f:
        if f.read() != VICTIM_TEXT.encode():
            problems.append("written through a symbolic link: the victim file changed")
    for root in (w, os.getcwd()):
        for r, ds, fs in os.walk(root):
            if "PWNED" in fs:
                problems.append("a name reached a shell: %s/PWNED exists" % r)
                os.remove(os.path.join(r, "PWNED"))
    for r, ds, fs in os.walk(w):
        for n in ds + fs:
            if OURS.search(n) and os.path.join(r, n) not in before:
                problems.append("a temporary was left behind: %s" % os.path.join(r, n))
    if case.check and not problems:
        try:
            problems += case.check(w, values, rc, out, err) or []
        except OSError as e:
            problems.append("the check could not run: %s" % e)
    if problems:
        problems.append("stderr: %s" % err.strip()[-400:])
    return problems


def main(argv):
    if len(argv) > 1 and argv[1] == "--reader-driver":
        return reader_driver(*argv[2:5])
    ap = argparse.ArgumentParser()
    ap.add_argument("--export", required=True)
    ap.add_argument("--bhnsid", required=True)
    ap.add_argument("--run", required=True, help="a finished run directory of quickstart.yaml")
    ap.add_argument("--work", required=True)
    ap.add_argument("--class", dest="classes", action="append", default=[])
    args = ap.parse_args(argv[1:])
    sys.path.insert(0, HERE)
    import cases

    unknown = set(args.classes) - set(cases.CLASSES)
    if unknown:
        print("unknown class(es): %s (known: %s)" % (", ".join(sorted(unknown)), ", ".join(cases.CLASSES)))
        return 2
    fx = Fixture(args)
    os.makedirs(fx.work, exist_ok=True)
    selected = [c for c in cases.CASES if not args.classes or c.cls in args.classes]
    ids = collections.Counter(c.id for c in cases.CASES)
    assert all(n == 1 for n in ids.values()), "duplicate case ids"
    failed = 0
    kinds = collections.Counter()
    for case in selected:
        kinds[case.kind] += 1
        problems = run_case(fx, case)
        print("%-4s %-44s %s" % ("ok" if not problems else "FAIL", case.id, "; ".join(problems)))
        failed += bool(problems)
    print("%d case(s), %d failed; by kind: %s" % (len(selected), failed,
                                                  ", ".join("%s %d" % kv for kv in sorted(kinds.items()))))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
