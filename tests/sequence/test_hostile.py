"""Replays the hostile-case corpus (hostile_cases.py) against `bhnsid sequence` as a user runs it
(the build's bhnsid, which execs bhnsid-sequence), each case in a fresh folder, and checks what
every case promises: its exit code; on failure exactly one line on stderr, `bhnsid: error: ...`,
holding the expected words; never a Python traceback; no PWNED* file; the victim folder (where
every link points) unchanged; the time bound. Prints the count by kind.

usage: test_hostile.py BUILD_BIN SOURCE_DIR WORK_DIR [NAME_SUBSTRING]"""
import fcntl
import os
import resource
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

here = Path(__file__).resolve().parent
sys.path.insert(0, str(here))
from checklist import Checklist, arguments  # noqa: E402
from hostile_cases import CASES, DEFAULT  # noqa: E402

bin_dir, source, work, bhnsid = arguments()
only = sys.argv[4] if len(sys.argv) > 4 else ""
check = Checklist()
fake_text = (here / "fake_bhnsid.py").read_text()
SIGNALS = {"TERM": signal.SIGTERM, "INT": signal.SIGINT, "HUP": signal.SIGHUP}


def fill(text, w):
    if isinstance(text, bytes):
        return text
    return (text.replace("{W}", str(w)).replace("{SEQ}", str(w / "seq")).replace("{FAKE}", str(w / "bin" / "bhnsid"))
            .replace("{BHNSID}", bhnsid).replace("{SRC}", str(source)))


def path_in(w, p):
    p = Path(fill(p, w))
    return p if p.is_absolute() else w / p


def snapshot(folder):
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def fake_tools(w, c):
    """W/bin/bhnsid (the stand-in) and, on PATH, an sbatch and squeue as the case asks, and a
    bhnsid that must never run (it would leave PWNED)."""
    tools = w / "bin"
    onpath = w / "onpath"
    tools.mkdir()
    onpath.mkdir()
    (tools / "bhnsid").write_text(fake_text)
    scripts = {"squeue": "#!/bin/sh\nexit 0\n"}
    if c.get("sbatch") == "ok":
        scripts["sbatch"] = (f"#!/bin/sh\nprintf '%s\\0' \"$@\" >> {w}/sbatch.args\n"
                             f"n=$(ls {w}/sbatch.ids 2>/dev/null | wc -l); touch {w}/sbatch.ids; echo $((100 + n))\n")
    elif c.get("sbatch") == "evil":
        scripts["sbatch"] = "#!/bin/sh\necho 123\necho 'touch PWNED'\n"
    if c.get("path_bhnsid"):
        scripts["bhnsid"] = f"#!/bin/sh\ntouch {w}/PWNED\nexit 0\n"
    for name, text in scripts.items():
        (onpath / name).write_text(text)
    for f in list(tools.iterdir()) + list(onpath.iterdir()):
        f.chmod(0o755)
    return onpath


def prepare(w, c, env, holds):
    (w / "base.yaml").write_text("grid: {n: 24}\n")
    text = c["spec"]
    (w / "spec.yaml").write_bytes(text if isinstance(text, bytes) else fill(text, w).encode())
    victim = w / "victim"
    victim.mkdir()
    for name in ("data.txt", "summary.json", "checkpoint.000001", "checkpoint.000002.partial"):
        (victim / name).write_text(f"the user's {name}\n")
    for step in c["prepare"]:
        op, args = step[0], [fill(a, w) for a in step[1:]]
        if op == "first_run":
            r = subprocess.run([bhnsid, "sequence"] + [fill(a, w) for a in DEFAULT], cwd=w, env=env,
                               capture_output=True, text=True)
            check(r.returncode == 0, f"{c['name']}: its first run ({r.stderr.strip()[-200:]})")
            continue
        p = path_in(w, args[0])
        if op == "write":
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_bytes(args[1] if isinstance(args[1], bytes) else args[1].encode())
        elif op == "mkdir":
            p.mkdir(parents=True, exist_ok=True)
        elif op == "link":
            p.parent.mkdir(parents=True, exist_ok=True)
            p.symlink_to(args[1])
        elif op == "fifo":
            p.parent.mkdir(parents=True, exist_ok=True)
            os.mkfifo(p)
        elif op == "lock":
            f = open(p, "a+")
            fcntl.flock(f, fcntl.LOCK_EX)
            holds.append(f)
        else:
            raise ValueError(op)


def run(w, c, env):
    def limits():
        if c.get("fsize") is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (c["fsize"], c["fsize"]))
        if c.get("nohup"):
            signal.signal(signal.SIGHUP, signal.SIG_IGN)

    argv = [bhnsid, "sequence"] + [fill(a, w) for a in c["argv"]]
    streams = {}
    for name in ("stdout", "stderr"):
        if c.get(f"close_{name}"):  # a pipe whose reader has gone, as `| head -1` leaves it
            read_end, streams[name] = os.pipe()
            os.close(read_end)
        else:
            streams[name] = subprocess.PIPE
    p = subprocess.Popen(argv, cwd=w, env=env, stdin=subprocess.DEVNULL, preexec_fn=limits, start_new_session=True,
                         **streams)
    for fd in streams.values():
        if fd != subprocess.PIPE:
            os.close(fd)
    if c.get("signal"):
        name, to_group = c["signal"]
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and not any(f.name.isdigit() for f in (w / "pids").iterdir()):
            time.sleep(0.05)
        (os.killpg if to_group else os.kill)(p.pid, SIGNALS[name])
    try:
        out, err = p.communicate(timeout=c.get("timeout", 20))
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        return None, (out or b"").decode(errors="replace"), (err or b"").decode(errors="replace")
    return p.returncode, (out or b"").decode(errors="replace"), (err or b"").decode(errors="replace")


def replay(c):
    w = work / c["name"]
    w.mkdir()
    onpath = fake_tools(w, c)
    (w / "pids").mkdir()
    env = dict(os.environ, PATH=f"{onpath}:{os.environ['PATH']}", FAKE_PIDS=str(w / "pids"), **c.get("env", {}))
    env.pop("SLURM_JOB_ID", None)
    holds = []
    prepare(w, c, env, holds)
    victim = snapshot(w / "victim")
    start = time.monotonic()
    rc, out, err = run(w, c, env)
    seconds = time.monotonic() - start
    for f in holds:
        f.close()
    name = f"{c['kind']}/{c['name']}"
    # A failure is one error line; a failure during the runs comes after their progress lines.
    lines = [line for line in err.splitlines() if line.strip() and not line.startswith("sequence: ")]
    problems = []
    if rc != c["rc"]:
        problems.append(f"exit {rc}, expected {c['rc']}")
    if "Traceback" in out + err:
        problems.append("a Python traceback")
    if c["rc"] == 2 and (len(lines) != 1 or not lines[0].startswith("bhnsid: error: ") or c["says"] not in lines[0]):
        problems.append(f"expected one line 'bhnsid: error: ...{c['says']}...'")
    if list(w.rglob("PWNED*")) or list(Path(source).glob("PWNED*")):
        problems.append("a PWNED file was created")
    if snapshot(w / "victim") != victim:
        problems.append("the victim folder changed (written or deleted through a link)")
    for k in c.get("keeps", []):
        if not (w / k).exists():
            problems.append(f"{k} is missing")
    for pattern in c.get("absent", []):
        if list(w.glob(pattern)):
            problems.append(f"{pattern} exists")
    if c.get("paste") and rc == 0:
        problems += paste(w, out, env)
    live = [f.name for f in (w / "pids").iterdir() if f.name.isdigit() and Path(f"/proc/{f.name}").exists()
            and Path(f"/proc/{f.name}/stat").read_text().split(")")[-1].split()[0] != "Z"]
    if live:
        problems.append(f"runs outlived the sequence: {live}")
    said = f": {lines[-1][:150]}" if lines and rc == 2 else ""
    check(not problems, f"{name} ({seconds:.1f} s){said}" + (": " + "; ".join(problems) + f"\n     stderr: {err[-600:]!r}"
                                                              if problems else ""))


def paste(w, out, env):
    """The printed sbatch lines, pasted into bash with a recording sbatch: every argument arrives
    whole and nothing runs."""
    lines = [line for line in out.splitlines() if "=$(" in line]
    record = w / "pasted.args"
    fake = w / "onpath" / "sbatch"
    fake.write_text(f"#!/bin/sh\nprintf '%s\\0' \"$@\" >> {record}\necho 7\n")
    fake.chmod(0o755)
    r = subprocess.run(["bash", "-c", "\n".join(lines)], cwd=w, env=env, capture_output=True, text=True)
    words = record.read_bytes().split(b"\0") if record.exists() else []
    scripts = [x for x in words if x.endswith(b".sh")]
    problems = []
    if r.returncode != 0 or len(scripts) != len(lines) or not all(Path(x.decode()).is_file() for x in scripts):
        problems.append(f"the pasted sbatch lines did not pass each script whole ({r.stderr.strip()[:200]})")
    return problems


selected = [c for c in CASES if only in c["name"]]
names = [c["name"] for c in CASES]
check(len(set(names)) == len(names), "every case has a name of its own")
for c in selected:
    replay(c)
kinds = Counter(c["kind"] for c in selected)
print(f"{len(selected)} cases: " + ", ".join(f"{k} {n}" for k, n in sorted(kinds.items())))
check.exit()
