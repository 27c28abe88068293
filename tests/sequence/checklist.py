"""What the sequence tool's end-to-end tests share: their three arguments (the build's bin folder,
the source tree, a work folder made empty) and a list of named checks that all run and decide the
exit status together."""
import shutil
import sys
from pathlib import Path


# The smallest sequence the tests run: one grid, one xhat_A, two rho_max values (the stand-in
# fake_bhnsid.py runs it in a moment).
TINY_SPEC = """sequence:
  base: base.yaml
  mass_ratio: 1.0
  x_a: [0.25]
  rho_max: [0.08, 0.09]
  targets: [0.6]
  grids: [{n: 24, dx: 0.16}]
"""


def stand_in_bhnsid(work):
    """fake_bhnsid.py as WORK/bhnsid, executable: a sequence without a build."""
    fake = Path(work) / "bhnsid"
    fake.write_text((Path(__file__).resolve().parent / "fake_bhnsid.py").read_text())
    fake.chmod(0o755)
    return fake


def arguments():
    """BUILD_BIN SOURCE_DIR WORK_DIR from argv, WORK_DIR emptied; and the bhnsid executable."""
    bin_dir, source, work = (Path(a).resolve() for a in sys.argv[1:4])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    return bin_dir, source, work, str(bin_dir / "bhnsid")


class Checklist:
    def __init__(self):
        self.failures = []

    def __call__(self, ok, what):
        print(("ok   " if ok else "FAIL ") + what, flush=True)
        if not ok:
            self.failures.append(what)

    def exit(self):
        sys.exit(1 if self.failures else 0)
