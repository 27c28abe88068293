"""How a sequence runs a chain of rho_max and what it keeps on disk.

Checkpoints: a run's checkpoints serve only the warm start of the next run of its chain, so a
converged run keeps its newest one until that run has converged, a failed run and the end of a
chain keep none, and a resumed sequence first removes every checkpoint no run still to come starts
from. At n = 256 one checkpoint is 2.3 GB: a sequence that kept more filled this project's disk.

Bridges: a warm start that fails is taken again through the midpoint in rho_max, twice halved at
most, before the run starts cold.

Twins: a run on a grid with a coarse twin in the sequence (half the points, twice the spacing)
starts from the twin's converged run, after it; from its neighbour in rho_max when that fails.

The runs are a stand-in executable that writes what `bhnsid run` writes (two checkpoints and
summary.json), and fails where told or when it starts too far from its neighbour, so the test needs
no build. usage: test_chain_runs.py [Checkpoints|Resume|Bridges|Twins|TimeLeft]"""
import io
import json
import os
import shlex
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "sequence"))
from bhnsid_sequence.pool import Progress, run_all, tidy_checkpoints  # noqa: E402
from bhnsid_sequence.runs import Config, Outcome, run_one  # noqa: E402
from bhnsid_sequence.spec import Grid, Spec  # noqa: E402

# A stand-in for bhnsid run: converges unless rho_max is listed in $FAKE_FAIL; records where it
# warm-started from.
FAKE = r'''#!/usr/bin/python3
import json, os, shlex, sys
from pathlib import Path
args = sys.argv[1:]
out = Path(args[args.index("--output") + 1])
sets = dict(a.split("=", 1) for a in args[1:] if "=" in a and not a.startswith("--"))
rho = sets["star.rho_max"]
out.mkdir(parents=True, exist_ok=True)
(out / "checkpoints").mkdir(exist_ok=True)
for f in (out / "checkpoints").iterdir():
    f.unlink()
for i in (3, 5):
    (out / "checkpoints" / f"checkpoint.{i:06d}").write_bytes(b"x" * 1000 * i)
warm = args[args.index("--warm-start") + 1] if "--warm-start" in args else ""
(out / "warm_from").write_text(warm)
failed = rho in os.environ.get("FAKE_FAIL", "").split()
# A warm start from a neighbour further than $FAKE_MAX_STEP in rho_max fails (a step over the fold).
if warm and abs(float(rho) - float(Path(warm).name[3:])) > float(os.environ.get("FAKE_MAX_STEP", "1")):
    failed = True
# With $FAKE_COARSE_FAILS set, so does one from another grid's run (the coarse twin).
if warm and os.environ.get("FAKE_COARSE_FAILS") and Path(warm).parents[1].name != out.parents[1].name:
    failed = True
(out / "summary.json").write_text(json.dumps({
    "status": "failed" if failed else "converged", "message": "Roche lobe overflow" if failed else "",
    "scalars": {}, "provenance": {"command_line": shlex.join(sys.argv)}}))
sys.exit(1 if failed else 0)
'''


def names(run_dir: Path):
    folder = run_dir / "checkpoints"
    return sorted(f.name for f in folder.iterdir()) if folder.is_dir() else []


class FakeChain(unittest.TestCase):
    """One chain (xhat_A = 0.2, one grid) of the stand-in runs in a fresh folder."""
    rho_max = [0.1]

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name) / "seq"
        self.fake = Path(self.tmp.name) / "bhnsid"
        self.fake.write_text(FAKE)
        self.fake.chmod(0o755)
        self.spec = Spec(file=Path("fake.yaml"), base=Path("base.yaml"), mass_ratio=1.0, x_a=[0.2],
                         rho_max=self.rho_max, targets=[0.6], grids=[Grid(32, 0.1)])
        os.environ["FAKE_FAIL"] = ""
        os.environ["FAKE_MAX_STEP"] = "1"
        os.environ["FAKE_COARSE_FAILS"] = ""

    def tearDown(self):
        self.tmp.cleanup()

    def chain_dir(self, rho):
        return self.root / Config(0, self.spec.grids[0], 0.2, rho).relative_dir


class Checkpoints(FakeChain):
    """Runs of a chain with checkpoints: what stays on disk."""
    rho_max = [0.1, 0.2, 0.3, 0.4]

    def setUp(self):
        super().setUp()
        self.line = [Config(0, self.spec.grids[0], 0.2, r) for r in self.spec.rho_max]
        os.environ["FAKE_FAIL"] = "0.3"

    def dir(self, i):
        return self.root / self.line[i].relative_dir

    def run_config(self, i):
        return run_one(str(self.fake), self.spec, self.root, self.line[i])

    def test_a_chain_keeps_only_what_the_next_warm_start_reads(self):
        self.assertEqual(self.run_config(0).status, "converged")
        self.assertEqual(names(self.dir(0)), ["checkpoint.000005"], "a converged run keeps only its newest")
        self.assertEqual(self.run_config(1).status, "converged")
        self.assertEqual((self.dir(1) / "warm_from").read_text(), str(self.dir(0)))
        self.assertEqual(names(self.dir(0)), [], "the source goes once its successor has converged")
        self.assertEqual(names(self.dir(1)), ["checkpoint.000005"])
        self.assertEqual(self.run_config(2).status, "failed")
        self.assertEqual(names(self.dir(2)), [], "a failed run keeps no checkpoint")
        self.assertEqual(names(self.dir(1)), ["checkpoint.000005"], "the source of a failed run stays")
        self.assertEqual(self.run_config(3).status, "converged")
        self.assertEqual((self.dir(3) / "warm_from").read_text(), str(self.dir(1)),
                         "past a failed neighbour to the nearest converged one")
        self.assertEqual(names(self.dir(1)), [])
        self.assertEqual(names(self.dir(3)), [], "the end of a chain keeps none")

    def test_a_resumed_sequence_first_removes_what_no_run_to_come_reads(self):
        for i in range(4):
            self.run_config(i)
        # What an interrupted sequence of an older bhnsid left: two checkpoints per run, a failed
        # run's state, a half-written one, and a file of the user's.
        for i in range(4):
            (self.dir(i) / "checkpoints").mkdir(exist_ok=True)
            for n in ("checkpoint.000007", "checkpoint.000009"):
                (self.dir(i) / "checkpoints" / n).write_bytes(b"y" * 100)
        (self.dir(3) / "checkpoints" / "checkpoint.000011.partial").write_bytes(b"z" * 10)
        (self.dir(0) / "checkpoints" / "notes.txt").write_text("mine")
        todo = [self.line[2]]  # the failed one, to be retried: it warm-starts from rho 0.2
        freed = tidy_checkpoints(self.spec, self.root, todo)
        self.assertEqual(names(self.dir(1)), ["checkpoint.000009"], "the source of a run to come keeps its newest")
        self.assertEqual(names(self.dir(0)), ["notes.txt"], "a file bhnsid did not write stays")
        self.assertEqual(names(self.dir(2)), [])
        self.assertEqual(names(self.dir(3)), [])
        self.assertEqual(freed, 100 * 7 + 10)
        self.assertEqual(tidy_checkpoints(self.spec, self.root, todo, warm=False), 100,
                         "--cold: nothing is needed")

    def test_a_whole_sequence_ends_with_no_checkpoint(self):
        outcomes = run_all(str(self.fake), self.spec, self.root, jobs=2, stream=io.StringIO())
        self.assertEqual([o.status for o in outcomes], ["converged", "converged", "failed", "converged"])
        self.assertEqual([names(self.dir(i)) for i in range(4)], [[]] * 4)
        again = io.StringIO()
        run_all(str(self.fake), self.spec, self.root, jobs=2, stream=again)
        skipped = next(line for line in again.getvalue().splitlines() if "already converged, skipped" in line)
        self.assertNotIn("min left", skipped, "no time estimate from runs skipped, none run yet")
        self.assertIn(str(self.fake), shlex.split(json.loads((self.dir(0) / "summary.json").read_text())
                                                  ["provenance"]["command_line"]))


class Resume(FakeChain):
    """A resumed sequence runs a failed configuration again only when its start has changed."""
    rho_max = [0.1, 0.2, 0.3]

    def resume(self, fail="", **kw):
        os.environ["FAKE_FAIL"] = fail  # "": run again, 0.2 would now converge
        out = io.StringIO()
        return [o.status for o in run_all(str(self.fake), self.spec, self.root, jobs=1, stream=out, **kw)], out.getvalue()

    def later_than_the_failure(self, path):
        if path.name == "summary.json":  # a neighbour converged again, with the checkpoint a start reads
            (path.parent / "checkpoints").mkdir(exist_ok=True)
            (path.parent / "checkpoints" / "checkpoint.000005").write_bytes(b"x")
        t = (self.chain_dir(0.2) / "summary.json").stat().st_mtime_ns + 10 ** 9
        os.utime(path, ns=(t, t))

    def back_to_the_past(self, path):
        os.utime(path, ns=(10 ** 9, 10 ** 9))

    def test_a_failure_from_the_same_start_is_kept(self):
        self.assertEqual(self.resume("0.2")[0], ["converged", "failed", "converged"])
        log = Path(str(self.chain_dir(0.2)) + ".out")
        before = log.stat().st_mtime_ns
        statuses, out = self.resume()
        self.assertEqual(statuses, ["converged", "failed", "converged"])
        self.assertEqual(log.stat().st_mtime_ns, before, "not run again")
        self.assertIn("1 failed before from the same start, not run again", out)
        self.assertIn("2 done, 0 running, 1 failed of 3", out)

    def test_a_failure_whose_attempts_were_cut_short_runs_again(self):
        self.resume("0.2")
        out = Path(str(self.chain_dir(0.2)) + ".out")
        self.assertEqual(out.read_text().splitlines()[-1], "bhnsid sequence: failed from every start tried")
        # What a sequence killed during 0.2's bridge or before its cold start leaves: the failure of
        # its first attempt, the log without the last line.
        out.write_text("\n".join(out.read_text().splitlines()[:-1]) + "\n")
        os.utime(self.chain_dir(0.2) / "summary.json")
        self.assertEqual(self.resume()[0][1], "converged")

    def test_no_bridge_through_a_configuration_that_failed_from_the_same_start(self):
        os.environ["FAKE_MAX_STEP"] = "0.15"  # 0.3 from 0.1 fails; the midpoint 0.2 is a configuration
        self.assertEqual(self.resume("0.2")[0], ["converged", "failed", "converged"])
        out = Path(str(self.chain_dir(0.3)) + ".out").read_text()
        self.assertIn("rho_max = 0.2 failed before from the same start, so no bridge", out)
        self.assertNotIn("bridging through", out)
        self.assertEqual((self.chain_dir(0.3) / "warm_from").read_text(), "", "cold, as after a failed bridge")

    def test_a_new_start_a_new_build_or_the_flag_runs_it_again(self):
        neighbour = self.chain_dir(0.1) / "summary.json"
        for changed in (neighbour, self.fake, None):
            (self.chain_dir(0.2) / "summary.json").unlink(missing_ok=True)  # converged in the last round
            self.assertEqual(self.resume("0.2", retry_failed=True)[0][1], "failed")
            self.assertEqual(self.resume()[0][1], "failed", "nothing changed since")
            if changed is None:
                self.assertEqual(self.resume(retry_failed=True)[0][1], "converged", "--retry-failed")
                continue
            self.later_than_the_failure(changed)
            self.assertEqual(self.resume()[0][1], "converged", f"run again after {changed} changed")
            self.back_to_the_past(changed)


class Bridges(FakeChain):
    """A warm start that fails is retried through the midpoint in rho_max (twice halved at most)
    before the run starts cold."""
    rho_max = [0.1, 0.3]

    def run_chain(self, max_step):
        os.environ["FAKE_MAX_STEP"] = str(max_step)
        return run_all(str(self.fake), self.spec, self.root, jobs=1, stream=io.StringIO())

    def test_one_bridge(self):
        outcomes = self.run_chain(0.15)
        self.assertEqual([o.status for o in outcomes], ["converged", "converged"])
        self.assertEqual((self.chain_dir(0.3) / "warm_from").read_text(), str(self.chain_dir(0.2)))
        self.assertEqual((self.chain_dir(0.2) / "warm_from").read_text(), str(self.chain_dir(0.1)))
        self.assertIn("bridging through rho_max = 0.2", Path(str(self.chain_dir(0.3)) + ".out").read_text())
        self.assertEqual([names(self.chain_dir(r)) for r in (0.1, 0.2, 0.3)], [[]] * 3, "no checkpoint left")

    def test_a_bridge_bridged_again(self):
        outcomes = self.run_chain(0.06)
        self.assertEqual([o.status for o in outcomes], ["converged", "converged"])
        self.assertEqual((self.chain_dir(0.2) / "warm_from").read_text(), str(self.chain_dir(0.15)))
        self.assertEqual((self.chain_dir(0.3) / "warm_from").read_text(), str(self.chain_dir(0.25)))
        self.assertEqual([names(self.chain_dir(r)) for r in (0.1, 0.15, 0.2, 0.25, 0.3)], [[]] * 5)

    def test_a_converged_bridge_with_its_checkpoint_is_reused(self):
        # What a sequence killed after its bridge converged leaves: the bridge and the source with
        # their checkpoints, the run itself not converged.
        self.run_chain(0.15)
        for rho in (0.1, 0.2):
            (self.chain_dir(rho) / "checkpoints").mkdir(exist_ok=True)
            (self.chain_dir(rho) / "checkpoints" / "checkpoint.000005").write_bytes(b"x")
        Path(str(self.chain_dir(0.2)) + ".out").unlink()
        (self.chain_dir(0.3) / "summary.json").unlink()
        self.assertEqual([o.status for o in self.run_chain(0.15)], ["converged", "converged"])
        self.assertFalse(Path(str(self.chain_dir(0.2)) + ".out").exists(), "the bridge is not run again")
        self.assertEqual((self.chain_dir(0.3) / "warm_from").read_text(), str(self.chain_dir(0.2)))

    def test_too_small_a_step_starts_cold(self):
        outcomes = self.run_chain(0.02)
        self.assertEqual([o.status for o in outcomes], ["converged", "converged"])
        self.assertEqual((self.chain_dir(0.3) / "warm_from").read_text(), "", "cold after two halvings")
        self.assertIn("starting cold", Path(str(self.chain_dir(0.3)) + ".out").read_text())


class Twins(FakeChain):
    """Grid 0 (64, 0.05) has a coarse twin, grid 1 (32, 0.1): the same cube coarsened once."""
    rho_max = [0.1, 0.2]

    def setUp(self):
        super().setUp()
        self.spec.grids = [Grid(64, 0.05), Grid(32, 0.1)]

    def at(self, g, rho):
        return self.root / Config(g, self.spec.grids[g], 0.2, rho).relative_dir

    def test_the_fine_run_starts_from_its_coarse_twin(self):
        outcomes = run_all(str(self.fake), self.spec, self.root, jobs=2, stream=io.StringIO())
        self.assertEqual([o.status for o in outcomes], ["converged"] * 4)
        for rho in (0.1, 0.2):
            self.assertEqual((self.at(0, rho) / "warm_from").read_text(), str(self.at(1, rho)))
        self.assertEqual((self.at(1, 0.2) / "warm_from").read_text(), str(self.at(1, 0.1)), "the coarse chain as before")
        self.assertEqual([names(self.at(g, r)) for g in (0, 1) for r in (0.1, 0.2)], [[]] * 4, "no checkpoint left")

    def test_the_coarse_grid_runs_first(self):
        self.spec.grids = [Grid(64, 0.05), Grid(48, 0.05), Grid(32, 0.1)]  # finest first, as the file has them
        out = io.StringIO()
        run_all(str(self.fake), self.spec, self.root, jobs=1, stream=out)
        order = [line.split(" - ")[1].split("/")[0] for line in out.getvalue().splitlines() if " - " in line]
        self.assertEqual(order, ["grid2_n32_dx0.1"] * 2 + ["grid1_n48_dx0.05"] * 2 + ["grid0_n64_dx0.05"] * 2)

    def test_a_failed_start_from_the_twin_falls_back_to_the_neighbour(self):
        os.environ["FAKE_COARSE_FAILS"] = "1"
        outcomes = run_all(str(self.fake), self.spec, self.root, jobs=1, stream=io.StringIO())
        self.assertEqual([o.status for o in outcomes], ["converged"] * 4)
        self.assertEqual((self.at(0, 0.1) / "warm_from").read_text(), "", "the chain's first: cold")
        self.assertEqual((self.at(0, 0.2) / "warm_from").read_text(), str(self.at(0, 0.1)))
        self.assertIn("the run from the coarser", Path(str(self.at(0, 0.2)) + ".out").read_text())
        self.assertEqual([names(self.at(g, r)) for g in (0, 1) for r in (0.1, 0.2)], [[]] * 4)

    def test_the_twin_keeps_its_checkpoint_until_the_fine_run_has_read_it(self):
        coarse = Config(1, self.spec.grids[1], 0.2, 0.2)  # the end of the coarse chain
        self.assertEqual(run_one(str(self.fake), self.spec, self.root, coarse).status, "converged")
        self.assertEqual(names(self.at(1, 0.2)), ["checkpoint.000005"], "its fine twin is still to run")
        fine = Config(0, self.spec.grids[0], 0.2, 0.2)
        self.assertEqual(tidy_checkpoints(self.spec, self.root, [fine]), 0)
        self.assertEqual(run_one(str(self.fake), self.spec, self.root, fine).status, "converged")
        self.assertEqual((self.at(0, 0.2) / "warm_from").read_text(), str(self.at(1, 0.2)))
        self.assertEqual(names(self.at(1, 0.2)), [], "read: gone")


class TimeLeft(unittest.TestCase):
    """The progress line's estimate weighs each run still to come by its grid's cost."""

    def test_each_grid_at_its_own_cost_and_an_unmeasured_one_by_its_points(self):
        fine, coarse, other = Grid(64, 0.05), Grid(32, 0.1), Grid(48, 0.05)
        todo = [Config(g, grid, 0.2, r) for g, grid in enumerate((fine, coarse, other)) for r in (0.1, 0.2)]
        p = Progress(todo, skipped=3, stream=io.StringIO())
        self.assertIsNone(p.seconds_left(10.0), "nothing timed yet")
        p.finished(Outcome(todo[2], "converged", seconds=4.0))
        p.finished(Outcome(todo[0], "converged", seconds=30.0))
        p.finished(Outcome(todo[4], "failed", seconds=0.0))  # no timers: not a measure
        # Left: one fine (30 s), one coarse (4 s), one other at the cost per point of the two timed
        # runs, 34 / (64^3 + 32^3), times 48^3; 34 s of runs in 17 s of wall (two at a time).
        per_point = 34.0 / (64 ** 3 + 32 ** 3)
        self.assertAlmostEqual(p.seconds_left(17.0), (30 + 4 + per_point * 48 ** 3) / 2)
        self.assertEqual((p.done, p.failed, p.total), (5, 1, 9))


if __name__ == "__main__":
    unittest.main()
