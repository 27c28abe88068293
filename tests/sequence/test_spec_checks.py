"""The sequence file and the command line are checked whole before any run, as the core checks a
parameter file: every bad value is one line naming the file, the key and what was expected (exit
2), never a traceback; a FIFO or a device is refused at once; lists are bounded and thousands of
runs schedule at once; values that differ in the 7th digit have run directories and table keys of
their own; every run passes `bhnsid check` before the first starts; --bhnsid is never taken from
PATH; a full disk is one line; an unexpected exception is one line and exit 3. Runs are the
stand-in fake_bhnsid.py (no build needed).

usage: test_spec_checks.py"""
import contextlib
import io
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path
from unittest import mock

here = Path(__file__).resolve().parent
sys.path.insert(0, str(here.parents[1] / "sequence"))
from bhnsid_sequence import cli, pool  # noqa: E402
from bhnsid_sequence.pipeline import at_targets  # noqa: E402
from bhnsid_sequence.runs import Outcome, coarse_twin, configurations, warm_source  # noqa: E402
from bhnsid_sequence.spec import SpecError, read_spec  # noqa: E402

from checklist import TINY_SPEC as SPEC  # noqa: E402


def spec_with(**changes):
    lines = [f"  {k}: {changes.pop(k)}" if k in changes else line
             for line in SPEC.splitlines() for k in [line.strip().split(":")[0]]]
    return "\n".join(lines) + "\n" + "".join(f"  {k}: {v}\n" for k, v in changes.items())


class Folder(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.d = Path(self.tmp.name)
        (self.d / "base.yaml").write_text("grid: {n: 24}\n")
        self.fake = self.d / "bin" / "bhnsid"
        self.fake.parent.mkdir()
        self.fake.write_text((here / "fake_bhnsid.py").read_text())
        self.fake.chmod(0o755)

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, text, name="spec.yaml"):
        f = self.d / name
        f.write_bytes(text if isinstance(text, bytes) else text.encode())
        return f

    def main(self, *argv):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            rc = cli.main([str(a) for a in argv])
        return rc, err.getvalue()


class SpecFile(Folder):
    BAD = [  # (what, the file's text, words of the error)
        ("NaN target", spec_with(targets="[.nan]"), "sequence.targets[0]: expected a finite number in (0, 1], got nan"),
        ("inf rho_max", spec_with(rho_max="[0.08, -.inf]"), "sequence.rho_max[1]: expected a finite number"),
        ("grid.n 64.5", spec_with(grids="[{n: 64.5, dx: 0.1}]"), "sequence.grids[0].n: expected an even integer >= 4"),
        ("count inf", spec_with(rho_max="{from: 0.05, to: 0.1, count: inf}"), "sequence.rho_max.count: expected an integer"),
        ("count 1e12", spec_with(rho_max="{from: 0.05, to: 0.1, count: 1e12}"), "sequence.rho_max.count: expected"),
        ("count 1.0e+12", spec_with(rho_max="{from: 0.05, to: 0.1, count: 1.0e+12}"), "sequence.rho_max.count"),
        ("not UTF-8", SPEC.encode() + b"# \xff\n", "not UTF-8 text"),
        ("alias bomb", "a: &a [x, x, x, x, x, x, x, x, x]\n" + "".join(
            f"{chr(98 + i)}: &{chr(98 + i)} [" + ", ".join([f"*{chr(97 + i)}"] * 9) + "]\n" for i in range(9)) + SPEC,
         "anchors and aliases"),
        ("a million values", spec_with(rho_max="[" + ", ".join(["0.1"] * 10 ** 6) + "]"), "more than the 65536"),
        ("201 values", spec_with(rho_max="[" + ", ".join(str(0.05 + i * 1e-4) for i in range(201)) + "]"),
         "sequence.rho_max: 201 values; at most 200"),
        ("deep nesting", "sequence: " + "[" * 60000, "nested deeper than 32"),
        ("duplicate key", SPEC + "  targets: [0.7]\n", "sequence.targets: duplicate key (first on line 6)"),
        ("1e400", spec_with(mass_ratio="1e400"), "sequence.mass_ratio: 1e400 overflows"),
        ("a key the sequence sets", spec_with(set="{star.rho_max: 0.1}"), "set by the sequence itself"),
    ]

    def test_every_bad_value_is_one_line_naming_the_file_and_key(self):
        for what, text, words in self.BAD:
            with self.subTest(what):
                f = self.write(text)
                start = time.monotonic()
                with self.assertRaises(SpecError) as e:
                    read_spec(f)
                self.assertLess(time.monotonic() - start, 1.0)
                self.assertTrue(str(e.exception).startswith(str(f)), str(e.exception))
                self.assertIn(words, str(e.exception))
                self.assertNotIn("\n", str(e.exception))
                rc, err = self.main(f, "--bhnsid", self.fake, "--output", self.d / "seq")
                self.assertEqual((rc, err.count("\n")), (2, 1), err)

    def test_a_fifo_or_a_device_is_refused_at_once(self):
        os.mkfifo(self.d / "pipe.yaml")
        for f in (self.d / "pipe.yaml", Path("/dev/zero")):
            start = time.monotonic()
            with self.assertRaises(SpecError) as e:
                read_spec(f)
            self.assertLess(time.monotonic() - start, 1.0)
            self.assertIn("not a regular file", str(e.exception))


class ExactValues(Folder):
    def test_values_differing_in_the_7th_digit_have_their_own_directories_and_keys(self):
        spec = read_spec(self.write(spec_with(x_a="[0.25, 0.2500001]", rho_max="[0.08, 0.08000001, 0.09]")))
        dirs = [c.relative_dir for c in configurations(spec)]
        self.assertEqual(len(set(dirs)), 6)
        self.assertIn(Path("grid0_n24_dx0.16/xa0.2500001/rho0.08000001"), dirs)
        outcomes = [Outcome(c, "converged", scalars={}) for c in configurations(spec)]
        self.assertEqual(sorted(at_targets(spec, outcomes)["grids"]["n24_dx0.16"]), ["0.25", "0.2500001"])
        rc, _ = self.main(self.d / "spec.yaml", "--bhnsid", self.fake, "--output", self.d / "seq")
        doc = json.loads((self.d / "seq" / "sequence.json").read_text())
        self.assertEqual(rc, 0)
        self.assertEqual(len({r["dir"] for r in doc["runs"]}), 6)
        self.assertEqual(len(doc["at_targets"]["n24_dx0.16"]), 2)


class Scheduling(Folder):
    def test_five_thousand_runs_schedule_at_once_each_after_its_sources(self):
        spec = read_spec(self.write(spec_with(x_a="{from: -0.5, to: 0.5, count: 25}",
                                              rho_max="{from: 0.05, to: 0.15, count: 200}")))
        started = []

        def instant(bhnsid, spec_, root, c, warm=True):
            for s in (warm_source(spec, c), coarse_twin(spec, c)):
                self.assertTrue(s is None or s in started, f"{c} before {s}")
            started.append(c)
            return Outcome(c, "converged")

        start = time.monotonic()
        with mock.patch.object(pool, "run_one", instant):
            outcomes = pool.run_all(str(self.fake), spec, self.d / "seq", 2, stream=io.StringIO())
        self.assertEqual(len(outcomes), 5000)
        self.assertEqual(len(started), 5000)
        self.assertLess(time.monotonic() - start, 20.0)


class CommandLine(Folder):
    def test_every_run_passes_bhnsid_check_before_the_first_starts(self):
        f = self.write(SPEC)
        with mock.patch.dict(os.environ, {"FAKE_CHECK_FAIL": "rho_max=0.09"}):
            rc, err = self.main(f, "--bhnsid", self.fake, "--output", self.d / "seq")
        self.assertEqual((rc, err.count("\n")), (2, 1), err)
        self.assertIn("bhnsid check refuses the run of grid n24_dx0.16, x_a = 0.25, rho_max = 0.09", err)
        self.assertFalse((self.d / "seq" / "grid0_n24_dx0.16").exists(), "no run started")

    def test_bhnsid_is_never_taken_from_path(self):
        f = self.write(SPEC)
        trap = self.d / "onpath" / "bhnsid"
        trap.parent.mkdir()
        trap.write_text(f"#!/bin/sh\ntouch {self.d}/PWNED\n")
        trap.chmod(0o755)
        with mock.patch.dict(os.environ, {"PATH": f"{trap.parent}:{os.environ['PATH']}"}):
            for extra in ([], ["--bhnsid", self.d / "nowhere"]):
                rc, err = self.main(f, "--output", self.d / "seq", *extra)
                self.assertEqual((rc, err.count("\n")), (2, 1), err)
        self.assertFalse((self.d / "PWNED").exists())

    def test_output_empty_or_a_file_is_one_line(self):
        f = self.write(SPEC)
        for output, words in (("", "--output '': expected a directory name"), (f, "not a directory")):
            rc, err = self.main(f, "--bhnsid", self.fake, "--output", output)
            self.assertEqual((rc, err.count("\n")), (2, 1), err)
            self.assertIn(words, err)

    def test_a_full_disk_is_one_line_and_leaves_no_temporary(self):
        f = self.write(SPEC)

        def limit():
            resource.setrlimit(resource.RLIMIT_FSIZE, (2000, 2000))

        r = subprocess.run([sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv[1]); "
                            "from bhnsid_sequence.cli import main; sys.exit(main(sys.argv[2:]))",
                            str(here.parents[1] / "sequence"), str(f), "--bhnsid", str(self.fake), "--output",
                            str(self.d / "seq")], capture_output=True, text=True, preexec_fn=limit)
        errors = [line for line in r.stderr.splitlines() if not line.startswith("sequence: ")]
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(len(errors), 1, r.stderr)
        self.assertIn("cannot write: File too large", errors[0])
        self.assertEqual(list((self.d / "seq").glob("*.partial")), [])

    def test_an_unexpected_exception_is_one_line_and_exit_3(self):
        f = self.write(SPEC)
        with mock.patch.object(cli, "at_targets", side_effect=RuntimeError("boom")):
            rc, err = self.main(f, "--bhnsid", self.fake, "--output", self.d / "seq")
        err = "".join(line + "\n" for line in err.splitlines() if not line.startswith("sequence: "))
        self.assertEqual((rc, err.count("\n")), (3, 1), err)
        self.assertIn("bhnsid: internal error: RuntimeError: boom", err)


if __name__ == "__main__":
    unittest.main()
