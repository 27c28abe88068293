"""The local pool: every configuration not yet converged, `--jobs` at a time, each after the runs
it warm-starts from, with one progress line per finished run."""
import heapq
import sys
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from pathlib import Path
from typing import Dict, List, Optional

from .checkpoints import checkpoint_bytes, checkpoint_files, drop_checkpoints, keep_newest_checkpoint
from .runs import (Config, Outcome, coarse_twin, configurations, failed_alike, read_outcome, run_one, twin_run_dir,
                   up_to_date, warm_run_dir, warm_source)
from .safe_io import say
from .signals import STOP
from .spec import Spec


class Progress:
    """One terminal line: done / running / failed / total and the time left. The time left: each
    run still to come at the mean cost of the runs of its grid finished in this call (a grid with
    none yet at the others' cost per point times its n^3 points), in wall time at the parallelism
    seen so far. A run at n = 256 costs ~5x one at 128, so a count of runs alone misleads."""

    def __init__(self, todo: List[Config], skipped: int, stream=None, kept_failed: int = 0):
        self.total = len(todo) + skipped + kept_failed
        self.done, self.failed, self.running = skipped, kept_failed, 0
        self.skipped = skipped  # converged before this call: no measure of the time a run takes
        self.left = {}  # grid -> runs still to finish
        for c in todo:
            self.left[c.grid] = self.left.get(c.grid, 0) + 1
        self.seconds = {}  # grid -> the timed runs finished here (seconds of each)
        self.start = time.monotonic()
        self.stream = stream or sys.stderr

    def finished(self, o: Outcome):
        if o.status == "converged":
            self.done += 1
        else:
            self.failed += 1
        self.left[o.config.grid] -= 1
        if o.seconds > 0:  # a run that failed before its timers were written says nothing
            self.seconds.setdefault(o.config.grid, []).append(o.seconds)

    def seconds_left(self, elapsed: float) -> Optional[float]:
        work_done = sum(sum(s) for s in self.seconds.values())
        if work_done <= 0 or not any(self.left.values()):
            return None
        per_point = work_done / sum(len(s) * g.n ** 3 for g, s in self.seconds.items())
        work_left = sum(n * (sum(self.seconds[g]) / len(self.seconds[g]) if g in self.seconds else per_point * g.n ** 3)
                        for g, n in self.left.items())
        return work_left * elapsed / work_done

    def show(self, note: str = ""):
        seconds = self.seconds_left(time.monotonic() - self.start)
        left = f", about {seconds / 60:.1f} min left" if seconds is not None else ""
        say(f"sequence: {self.done} done, {self.running} running, {self.failed} failed of {self.total}{left}"
            f"{' - ' + note if note else ''}", self.stream)


def tidy_checkpoints(spec: Spec, root: Path, todo: List[Config], warm: bool = True) -> int:
    """Before a (resumed) sequence runs TODO: the checkpoints of a run only stay where a
    configuration still to run warm-starts from them (its newest one); those of failed runs, of
    runs no one needs any more and of an interrupted sequence's half-written ones go. Returns the
    bytes freed."""
    holding = [c for c in configurations(spec) if checkpoint_files(root / c.relative_dir)]
    if not holding:
        return 0  # a fresh sequence: no chain to search for the runs still read
    needed = set()
    if warm:
        for c in todo:
            for source in (warm_run_dir(spec, c, root), twin_run_dir(spec, c, root)):
                if source is not None:
                    needed.add(source)
    freed = 0
    for c in holding:
        run_dir = root / c.relative_dir
        before = checkpoint_bytes(run_dir)
        if run_dir in needed:
            keep_newest_checkpoint(run_dir)
        else:
            drop_checkpoints(run_dir)
        freed += before - checkpoint_bytes(run_dir)
    return freed


def run_all(bhnsid: str, spec: Spec, root: Path, jobs: int, stream=None, warm: bool = True,
            retry_failed: bool = False) -> List[Outcome]:
    """Runs every configuration not yet converged, `jobs` at a time; a failed configuration (the
    Roche limit, no convergence) is an outcome, never an exception, and is run again on a resume
    only when its start has changed (failed_alike) or with retry_failed. The grid of fewest points
    first: its runs are the cheapest, so the first complete grid (one grid's minima) comes early in
    a sequence of hours, and a fine run's coarse twin has run before it is due. Once a stop signal
    arrives nothing more starts; the runs going stop and are waited for."""
    todo, outcomes, kept = [], {}, []
    for c in configurations(spec):
        run_dir = root / c.relative_dir
        if up_to_date(spec, c, run_dir):
            outcomes[c] = read_outcome(c, run_dir)
        elif not retry_failed and failed_alike(bhnsid, spec, root, c, warm):
            kept.append(c)
        else:
            todo.append(c)
    converged = len(outcomes)
    for c in kept:
        outcomes[c] = read_outcome(c, root / c.relative_dir)
    freed = tidy_checkpoints(spec, root, todo, warm)
    progress = Progress(todo, converged, stream, kept_failed=len(kept))
    if converged:
        progress.show(f"{converged} already converged, skipped")
    if kept:
        progress.show(f"{len(kept)} failed before from the same start, not run again (--retry-failed runs them)")
    if freed:
        progress.show(f"{freed / 2**30:.1f} GiB of checkpoints no run still to come starts from removed")

    queue = sorted(todo, key=lambda c: c.grid.n ** 3)  # stable: the file's order within a grid
    position = {c: i for i, c in enumerate(queue)}
    ready, blockers, dependents = _dependencies(spec, queue, position, warm)
    jobs = max(1, jobs)
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        pending: Dict = {}
        try:
            while ready or pending:
                while ready and len(pending) < jobs and not (STOP.signum or STOP.halted):
                    c = queue[heapq.heappop(ready)]
                    pending[pool.submit(run_one, bhnsid, spec, root, c, warm)] = c
                    progress.running = len(pending)
                if not pending:
                    break
                finished, _ = wait(set(pending), return_when=FIRST_COMPLETED)
                for f in finished:
                    c = pending.pop(f)
                    o = f.result()
                    outcomes[c] = o
                    for d in dependents.get(c, ()):
                        blockers[d] -= 1
                        if blockers[d] == 0:
                            heapq.heappush(ready, position[d])
                    progress.finished(o)
                    progress.running = len(pending)
                    progress.show(f"{c.relative_dir}: {o.status}" + (f" ({o.message[:120]})" if o.message else ""))
        except BaseException:
            STOP.stop_all()  # a refused entry or a bug: the runs going stop, the pool waits for them
            raise
    return [outcomes[c] if c in outcomes else read_outcome(c, root / c.relative_dir) for c in configurations(spec)]


def _dependencies(spec: Spec, queue: List[Config], position: Dict[Config, int], warm: bool):
    """A run waits for the runs still to come that it would warm-start from (its neighbour in
    rho_max and its coarse twin): how many each waits for, who waits for each, and a heap of the
    queue positions of those that wait for none. Linear in the queue, so that thousands of runs
    schedule at once (a search of the queue per start was quadratic)."""
    blockers = {c: 0 for c in queue}
    dependents: Dict[Config, List[Config]] = {}
    if warm:
        for c in queue:
            for s in (warm_source(spec, c), coarse_twin(spec, c)):
                if s is not None and s in position:
                    blockers[c] += 1
                    dependents.setdefault(s, []).append(c)
    ready = [position[c] for c in queue if blockers[c] == 0]
    heapq.heapify(ready)
    return ready, blockers, dependents
