"""The sequence never writes or deletes through a link, and removes only what bhnsid wrote: a
`checkpoints` folder linked to another folder, a checkpoint name that is a link, a run log, lock
file or sequence.json.partial that is a link, a run log hard-linked to another file. Each is
refused with one error naming it (exit 2) or left alone, and the other folder's files stay; a
note of the user's in checkpoints/ stays. Every result file is written under a fresh name, fsynced
and renamed: a write that fails leaves the old file and no temporary. Runs are the stand-in
fake_bhnsid.py (no build needed).

usage: test_links.py"""
import contextlib
import errno
import io
import os
import stat
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

here = Path(__file__).resolve().parent
sys.path.insert(0, str(here.parents[1] / "sequence"))
from bhnsid_sequence import cli, safe_io  # noqa: E402
from bhnsid_sequence.checkpoints import drop_checkpoints, keep_newest_checkpoint  # noqa: E402
from bhnsid_sequence.safe_io import InputError, write_atomic  # noqa: E402

from checklist import TINY_SPEC as SPEC  # noqa: E402


class Links(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.d = Path(self.tmp.name)
        (self.d / "base.yaml").write_text("grid: {n: 24}\n")
        (self.d / "spec.yaml").write_text(SPEC)
        self.fake = self.d / "bhnsid"
        self.fake.write_text((here / "fake_bhnsid.py").read_text())
        self.fake.chmod(0o755)
        self.seq = self.d / "seq"
        self.run_dir = self.seq / "grid0_n24_dx0.16" / "xa0.25" / "rho0.08"
        self.victim = self.d / "victim"
        self.victim.mkdir()
        for name in ("checkpoint.000001", "checkpoint.000002.partial", "data.txt"):
            (self.victim / name).write_text("the user's\n")

    def tearDown(self):
        self.tmp.cleanup()

    def sequence(self, *extra):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = cli.main([str(self.d / "spec.yaml"), "--output", str(self.seq), "--bhnsid", str(self.fake)] + list(extra))
        return rc, err.getvalue()

    def assertVictimIntact(self):
        self.assertEqual(sorted(p.name for p in self.victim.iterdir()),
                         ["checkpoint.000001", "checkpoint.000002.partial", "data.txt"])
        self.assertTrue(all(p.read_text() == "the user's\n" for p in self.victim.iterdir()))

    def assertRefused(self, rc, err, name):
        lines = [line for line in err.splitlines() if not line.startswith("sequence: ")]
        self.assertEqual(rc, 2, err)
        self.assertEqual(len(lines), 1, err)
        self.assertIn(name, lines[0])

    def test_a_linked_checkpoints_folder_is_refused_not_emptied(self):
        self.assertEqual(self.sequence()[0], 0)
        (self.run_dir / "checkpoints").symlink_to(self.victim)
        self.assertRefused(*self.sequence("--retry-failed"), "rho0.08/checkpoints: is a symbolic link")
        with self.assertRaises(InputError):
            drop_checkpoints(self.run_dir)
        with self.assertRaises(InputError):
            keep_newest_checkpoint(self.run_dir)
        self.assertVictimIntact()

    def test_a_checkpoint_name_that_is_a_link_is_refused(self):
        (self.run_dir / "checkpoints").mkdir(parents=True)
        (self.run_dir / "checkpoints" / "checkpoint.000001").symlink_to(self.victim / "checkpoint.000001")
        with self.assertRaises(InputError):
            drop_checkpoints(self.run_dir)
        self.assertVictimIntact()

    def test_only_checkpoints_are_removed_and_a_users_note_stays(self):
        folder = self.run_dir / "checkpoints"
        folder.mkdir(parents=True)
        for name in ("checkpoint.000003", "checkpoint.000005", "checkpoint.000006.partial", "notes.txt",
                     "checkpoint.old", "checkpoint.0000071"):
            (folder / name).write_text("x")
        keep_newest_checkpoint(self.run_dir)
        self.assertEqual(sorted(p.name for p in folder.iterdir()),
                         ["checkpoint.000005", "checkpoint.0000071", "checkpoint.old", "notes.txt"])
        drop_checkpoints(self.run_dir)
        self.assertEqual(sorted(p.name for p in folder.iterdir()), ["checkpoint.0000071", "checkpoint.old", "notes.txt"])

    def test_a_linked_run_log_or_lock_is_refused(self):
        for name in ("grid0_n24_dx0.16/xa0.25/rho0.08.out", ".bhnsid-sequence.lock"):
            with self.subTest(name=name):
                self.tearDown()
                self.setUp()
                (self.seq / "grid0_n24_dx0.16" / "xa0.25").mkdir(parents=True)
                (self.seq / ".bhnsid-sequence").write_text("x\n")
                (self.seq / name).symlink_to(self.victim / "data.txt")
                self.assertRefused(*self.sequence(), name.split("/")[-1])
                self.assertVictimIntact()

    def test_a_hard_linked_run_log_is_replaced_not_truncated(self):
        self.assertEqual(self.sequence()[0], 0)
        log = self.run_dir.with_name("rho0.08.out")
        log.unlink()
        os.link(self.victim / "data.txt", log)
        (self.run_dir / "summary.json").unlink()  # so that the run and its log are made again
        self.assertEqual(self.sequence()[0], 0)
        self.assertNotEqual(os.stat(log).st_ino, os.stat(self.victim / "data.txt").st_ino)
        self.assertVictimIntact()

    def test_a_partial_name_that_is_a_link_is_never_opened(self):
        self.seq.mkdir()
        (self.seq / ".bhnsid-sequence").write_text("x\n")
        (self.seq / "sequence.json.partial").symlink_to(self.victim / "data.txt")
        self.assertEqual(self.sequence()[0], 0)
        self.assertTrue((self.seq / "sequence.json").is_file() and not (self.seq / "sequence.json").is_symlink())
        self.assertVictimIntact()

    def test_a_failed_write_keeps_the_old_file_and_no_temporary(self):
        target = self.d / "out.json"
        write_atomic(target, "old\n")
        with mock.patch.object(safe_io.os, "fsync", side_effect=OSError(errno.ENOSPC, "No space left on device")):
            with self.assertRaises(InputError) as e:
                write_atomic(target, "new\n")
        self.assertIn("out.json: cannot write: No space left on device", str(e.exception))
        self.assertEqual(target.read_text(), "old\n")
        self.assertEqual(sorted(p.name for p in self.d.iterdir() if p.name.startswith("out.json")), ["out.json"])

    def test_every_final_file_is_fsynced_before_its_rename_and_the_folder_after(self):
        calls = []
        real_fsync, real_replace = os.fsync, os.replace
        with mock.patch.object(safe_io.os, "fsync", side_effect=lambda fd: calls.append(("fsync", os.fstat(fd).st_mode))
                               or real_fsync(fd)), \
                mock.patch.object(safe_io.os, "replace", side_effect=lambda a, b: calls.append(("replace", 0))
                                  or real_replace(a, b)):
            write_atomic(self.d / "x.txt", "x")
        kinds = [(k, "dir" if m and stat.S_ISDIR(m) else "file" if m else "") for k, m in calls]
        self.assertEqual(kinds, [("fsync", "file"), ("replace", ""), ("fsync", "dir")])


if __name__ == "__main__":
    unittest.main()
