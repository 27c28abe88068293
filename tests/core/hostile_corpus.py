#!/usr/bin/env python3
"""Replays the kept hostile cases of bhnsid run, --resume, --warm-start, check and validate.

Each case is what a careless user, a script or a shared folder does to a command: names holding
shell syntax, quotes or newlines; symbolic links, FIFOs and devices where the program keeps its own
files; a user's files inside the program's folders; signals. Every case must end within its time
limit with one of its expected exit codes; an input error (exit 2) is one line on stderr; nothing
outside the run directory changes (the victim file, every link's target); no command embedded in
a name runs (no PWNED file appears); no internal error (exit 3), crash or traceback.

usage: hostile_corpus.py BHNSID TEST_PLUGIN_DIR [--list]
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

BHNSID, PLUGINS = sys.argv[1], sys.argv[2]
PARFILE = "plugins: [tp_checkpoint, tp_output]\nrun:\n  max_iterations: 60\n  checkpoint_overhead: 1.0e9\n"
SLOW = "plugins: [tp_counter]\ntp_counter:\n  needed: 2.0\n  sleep_ms: 2500\n"
MMS = ("plugins: [grid, multigrid, momentum_mms, momentum]\ngrid:\n  n: 16\n  dx: 0.24\n"
       "multigrid:\n  tau_factor: 1.0e-6\nmomentum_mms:\n  puncture_phi: 0\n")
VICTIM = "my thesis\n"
INJECT = ["x'$(touch PWNED)'y", "a;touch PWNED", "`touch PWNED`", "$(touch PWNED)", "Bob's runs",
          "new\nline", "tab\there", " lead", "-dash", "δρ run", "a\"b", "*", "a\\b", "$HOME"]


class Work:
    """A case's folder: the parameter files, a user's victim file and, on demand, a stopped run."""

    def __init__(self, root):
        self.root = root
        self.par = self.write("case.yaml", PARFILE)
        self.victim = self.write("thesis.tex", VICTIM)
        self.out = os.path.join(root, "stopped")

    def write(self, name, text):
        path = os.path.join(self.root, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def stopped(self):
        """A run stopped by run.max_iterations (exit 1) with its checkpoints."""
        r = bhnsid(["run", self.par, "--output", self.out, "--set", "run.max_iterations=8"], self.root)
        assert r.returncode == 1, r.stderr
        return self.out

    def link(self, name, target=None):
        path = os.path.join(self.out, name)
        if os.path.lexists(path):
            if os.path.isdir(path) and not os.path.islink(path):
                shutil.rmtree(path)
            else:
                os.remove(path)
        os.symlink(target or self.victim, path)

    def fifo(self, name):
        path = os.path.join(self.out, name)
        if os.path.lexists(path):
            shutil.rmtree(path) if os.path.isdir(path) and not os.path.islink(path) else os.remove(path)
        os.mkfifo(path)


def bhnsid(args, cwd, timeout=30):
    return subprocess.run([BHNSID] + args + ["--plugin-path", PLUGINS], cwd=cwd, capture_output=True, text=True,
                          errors="replace", timeout=timeout)


def resume(w, *extra):
    return ["run", w.par, "--output", w.out, "--resume", "--set", "run.max_iterations=60"] + list(extra)


CASES = []


def case(kind, name, rcs, text=None, limit=20.0):
    def register(fn):
        CASES.append(dict(kind=kind, name=name, rcs=rcs, text=text, limit=limit, fn=fn))
        return fn
    return register


# Names that would run a command or break quoting if they reached a shell.
for i, n in enumerate(INJECT):
    case("names", f"run --output {n!r}", {0})(lambda w, n=n: (["run", w.par, "--output", n], None))
    case("names", f"run of a parameter file named {n!r}.yaml", {0})(
        lambda w, n=n: (["run", w.write(n.replace("/", "_") + ".yaml", PARFILE), "--output", "o"], None))
for n in ["x'$(touch PWNED)'y", "Bob's runs", "a;touch PWNED"]:
    case("names", f"validate --output {n!r} with plots", {0, 1}, limit=60)(
        lambda w, n=n: (["validate", w.write("mms.yaml", MMS), "--levels", "2", "--only", "momentum", "--with", "ire",
                         "--output", n], None))
case("names", "validate of a parameter file named a';touch PWNED;'.yaml (default output)", {0, 1}, limit=60)(
    lambda w: (["validate", w.write("a';touch PWNED;'.yaml", MMS), "--levels", "2", "--only", "momentum",
                "--with", "ire"], None))
case("names", "run --output of 4096 characters", {2}, "File name too long")(
    lambda w: (["run", w.par, "--output", "d" * 4096], None))
case("names", "run --output ''", {2}, "expected a directory name")(lambda w: (["run", w.par, "--output", ""], None))

# Links, FIFOs and foreign entries where a resume writes or reads its own files.
for entry in ["log.txt.partial", "blob.bin.partial", "params.yaml", "checkpoints", "log.txt",
              "checkpoints/checkpoint.000008", "checkpoints/checkpoint.000009.partial", ".bhnsid-run.json"]:
    # A damaged newest checkpoint is skipped with a warning, as any that does not read back.
    want = {0} if entry == "checkpoints/checkpoint.000008" else {2}

    def link_case(w, entry=entry):
        w.stopped()
        w.link(entry)
        return resume(w), None
    case("links", f"--resume with {entry} a link to the user's file", want)(link_case)

    def fifo_case(w, entry=entry):
        w.stopped()
        w.fifo(entry)
        return resume(w), None
    case("fifos", f"--resume with {entry} a FIFO", want)(fifo_case)


for entry in ["summary.json", "timers.tsv", "scalars.tsv", "blob.bin"]:
    def final_link(w, entry=entry):
        w.stopped()
        w.link(entry)
        return resume(w), None
    case("links", f"--resume with the final {entry} a link to the user's file", {2}, "symbolic link")(final_link)


def hard_link(w):
    w.stopped()
    os.link(w.victim, os.path.join(w.out, "log.txt.partial"))
    return resume(w), None


case("links", "--resume with log.txt.partial a hard link to the user's file", {2}, "hard link")(hard_link)
def temporary_lookalike(w):
    w.stopped()
    os.makedirs(os.path.join(w.out, "params.yaml.tmp.backup"))
    w.write("stopped/params.yaml.tmp.backup/notes.txt", "mine\n")
    return ["run", w.par, "--output", w.out, "--force"], None


case("foreign", "--force beside a folder named like a temporary of ours (params.yaml.tmp.backup/)", {2},
     "params.yaml.tmp.backup")(temporary_lookalike)
case("names", "run --output with a byte that is not UTF-8", {0})(lambda w: (["run", w.par, "--output", "r\udcff"], None))


def linked_folder(w):
    w.stopped()
    elsewhere = os.path.join(w.root, "elsewhere")
    os.rename(os.path.join(w.out, "checkpoints"), elsewhere)
    w.link("checkpoints", elsewhere)
    return resume(w), None


case("links", "--resume with checkpoints/ a link to another run's folder (its files must survive)", {2},
     "symbolic link")(linked_folder)
case("links", "--warm-start from a run whose checkpoints/ is a link", {2}, "symbolic link")(
    lambda w: (linked_folder(w) and None) or (["run", w.par, "--output", "warm", "--warm-start", w.out], None))


def force_with_notes(w):
    w.stopped()
    w.write("stopped/checkpoints/my_notes.txt", "notes\n")
    return ["run", w.par, "--output", w.out, "--force"], None


case("foreign", "--force on a run whose checkpoints/ holds the user's notes", {2}, "my_notes.txt")(force_with_notes)


def force_with_link(w):
    w.stopped()
    w.link("log.txt")
    return ["run", w.par, "--output", w.out, "--force"], None


case("links", "--force on a run whose log.txt is now a link (the target stays)", {0})(force_with_link)
case("foreign", "--force on a run with a user's file beside its own", {2}, "notes.txt")(
    lambda w: (w.stopped() and w.write("stopped/notes.txt", "x\n")) and (["run", w.par, "--output", w.out, "--force"], None))

# Devices and FIFOs as inputs.
case("fifos", "run of a FIFO parameter file", {2}, "not a regular file")(
    lambda w: (os.mkfifo(os.path.join(w.root, "f.yaml")), (["run", os.path.join(w.root, "f.yaml")], None))[1])
case("fifos", "check of /dev/zero", {2}, "not a regular file")(lambda w: (["check", "/dev/zero"], None))
case("fifos", "--warm-start from a FIFO", {2})(
    lambda w: (os.mkfifo(os.path.join(w.root, "src")), (["run", w.par, "--output", "o", "--warm-start", "src"], None))[1])
case("fifos", "--warm-start from /dev/zero", {2})(lambda w: (["run", w.par, "--output", "o", "--warm-start", "/dev/zero"], None))
case("fifos", "--warm-start from a run whose newest checkpoint is a FIFO", {2}, "FIFO")(
    lambda w: (w.stopped(), w.fifo("checkpoints/checkpoint.000099"),
               (["run", w.par, "--output", "o", "--warm-start", w.out], None))[2])
case("fifos", "--warm-start from a file, not a run", {2})(lambda w: (["run", w.par, "--output", "o", "--warm-start", w.victim], None))

# Mismatched checkpoints: the message names what differs.
case("messages", "--resume with another plugin set", {2}, "lacks tp_output")(
    lambda w: (w.stopped(), (["run", w.write("o.yaml", "plugins: [tp_checkpoint]\n"), "--output", w.out, "--resume"], None))[1])
case("messages", "--resume with another parameter value", {2}, "tp_checkpoint.target = 4")(
    lambda w: (w.stopped(), (resume(w, "--set", "tp_checkpoint.target=4"), None))[1])
case("messages", "--resume with run.threads = 1 (what the warning advises)", {0})(
    lambda w: (w.stopped(), (resume(w, "--set", "run.threads=1"), None))[1])
case("messages", "--warm-start with another plugin set", {2}, "lacks tp_output")(
    lambda w: (w.stopped(), (["run", w.write("o.yaml", "plugins: [tp_checkpoint]\n"), "--output", "o", "--warm-start",
                              w.out], None))[1])
case("messages", "--resume and --force together", {2}, "excludes")(
    lambda w: (w.stopped(), (resume(w, "--force"), None))[1])
case("messages", "--resume of a folder that is not a run", {2}, "not a bhnsid run directory")(
    lambda w: (os.mkdir(os.path.join(w.root, "mine")), (["run", w.par, "--output", "mine", "--resume"], None))[1])


# Signals: one request delivered twice is one stop; a stopped run keeps its state.
def signalled(sigs, gap, summary=True):
    def prepare(w):
        par = w.write("slow.yaml", SLOW)

        def act(p):
            time.sleep(1.0)
            for k, s in enumerate(sigs):
                if k:
                    time.sleep(gap)
                p.send_signal(s)
        act.summary = summary
        return ["run", par, "--output", "slow"], act
    return prepare


case("signals", "SIGTERM twice, 0.1 s apart", {143})(signalled([signal.SIGTERM, signal.SIGTERM], 0.1))
case("signals", "SIGINT twice, 0.1 s apart", {130})(signalled([signal.SIGINT, signal.SIGINT], 0.1))
case("signals", "SIGTERM twice at once", {143})(signalled([signal.SIGTERM, signal.SIGTERM], 0))
case("signals", "SIGHUP once", {129})(signalled([signal.SIGHUP], 0))
# Two different signals are two requests: the second exits at once, without the summary.
case("signals", "SIGTERM then SIGINT 0.1 s later", {130})(signalled([signal.SIGTERM, signal.SIGINT], 0.1, summary=False))
case("signals", "SIGINT, then SIGINT again a second later (a person's second Ctrl-C)", {130})(
    signalled([signal.SIGINT, signal.SIGINT], 1.0, summary=False))


def run_case(c):
    root = tempfile.mkdtemp(prefix="bhnsid-hostile-")
    try:
        w = Work(root)
        args, act = c["fn"](w)
        victim_before = open(w.victim).read()
        marker = os.path.join(w.out, ".bhnsid-run.json")
        marker_before = open(marker, "rb").read() if os.path.isfile(marker) and not os.path.islink(marker) else None
        t0 = time.monotonic()
        if act is None:
            try:
                r = bhnsid(args, root, timeout=c["limit"])
                rc, err = r.returncode, r.stderr
            except subprocess.TimeoutExpired:
                return "hung (over %.0f s)" % c["limit"]
        else:
            p = subprocess.Popen([BHNSID] + args + ["--plugin-path", PLUGINS], cwd=root, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.PIPE, text=True, errors="replace")
            act(p)
            try:
                _, err = p.communicate(timeout=c["limit"])
            except subprocess.TimeoutExpired:
                p.kill()
                return "hung after the signals"
            rc = p.returncode
            summary = os.path.join(root, "slow", "summary.json")
            kept = os.path.exists(summary) and '"status": "interrupted"' in open(summary).read()
            if kept != act.summary:
                return "an interrupted summary.json " + ("missing" if act.summary else "written after a second request")
        seconds = time.monotonic() - t0
        problems = []
        if rc not in c["rcs"]:
            problems.append(f"exit {rc}, expected {sorted(c['rcs'])}: {err.strip()[-300:]}")
        # CLI11 adds its usage hint to a usage error.
        lines = [x for x in err.splitlines() if x != "Run with --help for more information."]
        if rc == 2 and len(lines) != 1:
            problems.append(f"{err.count(chr(10))} lines on stderr for an input error: {err.strip()[-300:]}")
        if c["text"] and c["text"] not in err:
            problems.append(f"stderr lacks {c['text']!r}: {err.strip()[-300:]}")
        for bad in ("Traceback", "internal error", "AddressSanitizer", "runtime error:"):
            if bad in err:
                problems.append(f"stderr holds {bad!r}")
        if rc == 2 and marker_before is not None and os.path.isfile(marker) and open(marker, "rb").read() != marker_before:
            problems.append("a refused command rewrote the run directory's marker")
        if open(w.victim).read() != victim_before:
            problems.append("the user's file changed")
        for d, _, files in os.walk(root):
            if "PWNED" in files:
                problems.append(f"a command in a name ran ({os.path.join(d, 'PWNED')})")
        elsewhere = os.path.join(root, "elsewhere")
        if os.path.isdir(elsewhere) and not any(n.startswith("checkpoint.") for n in os.listdir(elsewhere)):
            problems.append("the linked folder's files were deleted")
        if seconds > c["limit"]:
            problems.append(f"took {seconds:.1f} s")
        return "; ".join(problems)
    finally:
        shutil.rmtree(root, ignore_errors=True)


def main():
    if "--list" in sys.argv:
        for c in CASES:
            print(f"{c['kind']:9} {c['name']!r}")
        return 0
    failed = 0
    kinds = {}
    for c in CASES:
        kinds[c["kind"]] = kinds.get(c["kind"], 0) + 1
        why = run_case(c)
        if why:
            failed += 1
            print(f"FAIL [{c['kind']}] {c['name']!r}: {why}")
    print(f"{len(CASES) - failed} of {len(CASES)} hostile cases clean ({', '.join(f'{k} {v}' for k, v in sorted(kinds.items()))})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
