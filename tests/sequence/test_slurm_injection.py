"""bhnsid sequence --slurm never lets a name become a command. --partition, --account and --time
reach #SBATCH lines (read by sbatch, not a shell: quoting cannot help there), so only SLURM's own
syntax is accepted and anything else is one error naming the option, exit 2, no script written.
Paths reach shell lines (each script's exec line, the printed sbatch lines): a sequence directory
named with a quote, a blank and $(...) works, every word arrives whole, and nothing runs.

usage: test_slurm_injection.py BUILD_BIN SOURCE_DIR WORK_DIR"""
import os
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from checklist import Checklist, arguments, stand_in_bhnsid  # noqa: E402

bin_dir, source, work, bhnsid = arguments()
check = Checklist()
fake = stand_in_bhnsid(work)
(work / "base.yaml").write_text("grid: {n: 24}\n")
spec = work / "spec.yaml"
spec.write_text("sequence:\n  base: base.yaml\n  mass_ratio: 1.0\n  x_a: [0.25]\n  rho_max: [0.08, 0.09]\n"
                "  targets: [0.6]\n  grids: [{n: 24, dx: 0.16}]\n")


def emit(out, *options):
    return subprocess.run([bhnsid, "sequence", str(spec), "--output", str(out), "--bhnsid", str(fake), "--slurm",
                           "--emit-only"] + list(options), capture_output=True, text=True, cwd=work)


bad = {"--partition": ["short\n#SBATCH --wrap=touch PWNED", "x;touch PWNED", "$(touch PWNED)", "a b", "", "p'q"],
       "--account": ["acc\ntouch PWNED", "a`id`", "a b"],
       "--time": ["1:00\ntouch PWNED", "1:00:00:00", "tomorrow", "-1", "1-", "1:00 ", "١:٠٠"]}
for option, values in bad.items():
    for value in values:
        out = work / "refused"
        r = emit(out, option, value)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and lines[0].startswith(f"bhnsid: error: {option} ")
              and not (out / "slurm").exists(), f"{option} {value!r} refused in one line, no script written")
good = [("--partition", "short"), ("--partition", "short,long.gpu-1"), ("--account", "proj_1.a-b"), ("--time", "30"),
        ("--time", "30:00"), ("--time", "2:00:00"), ("--time", "1-0"), ("--time", "1-12:00"), ("--time", "1-12:00:00"),
        ("--time", "UNLIMITED")]
for option, value in good:
    r = emit(work / "accepted", option, value)
    rank0 = (work / "accepted" / "slurm" / "rank0.sh").read_text() if r.returncode == 0 else ""
    check(f"#SBATCH {option}={value}\n" in rank0, f"{option} {value} accepted into rank0.sh")
r = subprocess.run([bhnsid, "sequence", str(spec), "--bhnsid", str(fake), "--time", "1:00"], capture_output=True,
                   text=True, cwd=work)
check(r.returncode == 2 and "--time: only with --slurm" in r.stderr, "--time without --slurm is an error, not ignored")

# A directory name with a quote, a blank, $(...) and backticks: the scripts' shell lines and the
# printed sbatch lines carry it whole.
nasty = work / "Bob's runs $(touch PWNED) `touch PWNED2`"
r = emit(nasty)
print(r.stdout, r.stderr)
check(r.returncode == 0, "a sequence directory named with a quote, $(...) and backticks is accepted")
folder = nasty / "slurm"
script = (folder / "rank0.sh").read_text() if r.returncode == 0 else ""
exec_line = next((line for line in script.splitlines() if line.startswith("exec ")), "exec true")
words = subprocess.run(["bash", "-c", "SLURM_ARRAY_TASK_ID=3; printf '%s\\0' " + exec_line[len("exec "):]],
                       capture_output=True).stdout.split(b"\0")[:-1]
words = [w.decode() for w in words]
check(str(nasty.resolve()) in words and f"{folder.resolve() / 'rank0.tasks'}:3" in words,
      f"the script's exec line gives the directory and the task list back word for word ({words})")
check("#SBATCH --output" not in script, "no path of the user's in an #SBATCH line")
record = work / "sbatch.args"
(work / "onpath").mkdir()
(work / "onpath" / "sbatch").write_text(f"#!/bin/sh\nprintf '%s\\0' \"$@\" >> '{record}'\necho 7\n")
(work / "onpath" / "sbatch").chmod(0o755)
pasted = "\n".join(line for line in r.stdout.splitlines() if "=$(" in line)
p = subprocess.run(["bash", "-c", pasted], cwd=work, capture_output=True, text=True,
                   env=dict(os.environ, PATH=f"{work / 'onpath'}:{os.environ['PATH']}"))
args = record.read_bytes().decode().split("\0") if record.exists() else []
check(p.returncode == 0 and str(folder.resolve() / "rank0.sh") in args
      and f"--output={folder.resolve()}/rank0_%a.out" in args and "--dependency=afterany:7" in args,
      "the pasted sbatch lines pass each script and log path whole, the job ids chained")
check(not list(work.rglob("PWNED*")), "and nothing in the names ran")
percent = work / "100%a"
r = emit(percent)
check(r.returncode == 0 and f"--output={str(percent.resolve()).replace('%', '%%')}/slurm/rank0_%a.out" in r.stdout,
      "a % of the directory's name doubled in the log pattern (SLURM's escape)")
for name in ("a\\b", "a\nb"):
    r = emit(work / name)
    check(r.returncode == 2 and r.stderr.count("\n") == 1 and "--output" in r.stderr,
          f"--slurm with a directory name SLURM's log pattern cannot carry ({name!r}): one error")
check(re.search(r"#SBATCH --job-name=bhnsid-seq-spec-[0-9a-f]{8}-rho0\n", script) is not None,
      "the job name is made of the file's stem (letters, digits, _ . -) and a hash")
check.exit()
