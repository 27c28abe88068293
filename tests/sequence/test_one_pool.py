"""One pool per sequence directory: while a `bhnsid sequence` works in a directory, a second one
started there is refused with one error line naming the directory and the holder, and writes
nothing; once the first has ended, the next starts. --reduce-only reads beside a running pool.

The runs are a stand-in executable that passes `check` and fails every run at once (no build
needed): this test is about who may start, not about the runs."""
import contextlib
import fcntl
import io
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "sequence"))
from bhnsid_sequence import cli  # noqa: E402
from bhnsid_sequence.directory import LOCK, MARKER  # noqa: E402

SEQUENCE = """sequence:
  base: base.yaml
  mass_ratio: 1.0
  x_a: [0.2]
  rho_max: [0.1, 0.12, 0.14, 0.16]
  targets: [0.6]
  grids: [{n: 32, dx: 0.1}]
"""


class OnePool(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        d = Path(self.tmp.name)
        (d / "base.yaml").write_text("grid: {n: 32}\n")
        (d / "seq.yaml").write_text(SEQUENCE)
        self.fake = d / "bhnsid"
        self.fake.write_text('#!/bin/sh\n[ "$1" = check ] && echo "memory: estimated 1.0 MiB" && exit 0\nexit 1\n')
        self.fake.chmod(0o755)
        self.root = d / "seq"
        self.argv = [str(d / "seq.yaml"), "--output", str(self.root), "--bhnsid", str(self.fake)]

    def tearDown(self):
        self.tmp.cleanup()

    def main(self, *extra):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = cli.main(self.argv + list(extra))
        return rc, err.getvalue()

    def test_a_second_pool_is_refused_while_the_first_holds_the_directory(self):
        self.root.mkdir()
        (self.root / MARKER).write_text("seq.yaml\n")
        (self.root / LOCK).write_text("pid 4242 on elsewhere\n")
        with open(self.root / LOCK, "a+") as first:
            fcntl.flock(first, fcntl.LOCK_EX | fcntl.LOCK_NB)
            rc, err = self.main()
            self.assertEqual(rc, 2)
            self.assertIn(str(self.root), err)
            self.assertIn("another bhnsid sequence works in it (pid 4242 on elsewhere)", err)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertEqual(sorted(p.name for p in self.root.iterdir()), sorted([MARKER, LOCK]),
                             "the refused pool wrote nothing")
            rc, err = self.main("--reduce-only")
            self.assertNotIn("another bhnsid sequence", err)
        # The first has ended: the next one takes the directory and runs (its stand-in runs fail).
        rc, err = self.main()
        self.assertNotIn("another bhnsid sequence", err)
        self.assertTrue((self.root / "grid0_n32_dx0.1" / "xa0.2").is_dir())
        self.assertIn(f"pid ", (self.root / LOCK).read_text())


if __name__ == "__main__":
    unittest.main()
