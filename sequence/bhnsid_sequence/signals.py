"""Stopping a sequence. SIGINT, SIGTERM and SIGHUP reach bhnsid-sequence; it starts no new run,
passes the signal on once to every running `bhnsid run` (each stops at its safe point, writes its
last state and exits 128 + N), waits for them and exits 128 + N itself.

Each run is in a session of its own, so that a terminal's Ctrl-C (sent to the foreground process
group) or `timeout`'s signal to our group reaches it once, through us, not twice (bhnsid takes a
second signal as "exit at once", without its summary). Inside a SLURM job the runs stay in our
process group and nothing is passed on: SLURM signals every process of the job itself (time
limit, scancel), and a signal passed on as well would be that second one."""
import os
import signal
import subprocess
import threading
import time

STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
# One request can arrive twice within microseconds (`timeout` signals its child, then the child's
# process group); a person's second Ctrl-C comes later than this.
SAME_REQUEST_SECONDS = 0.1


class Stop:
    def __init__(self):
        self.signum = 0          # the first stop signal received, 0 while running
        self._last = (0, 0.0)    # (signal, monotonic time) of the latest request
        self._lock = threading.RLock()  # reentrant: the handler runs in the main thread, which may hold it
        self._children = {}      # pid -> Popen of every run started and not yet waited for
        self.halted = False      # an error elsewhere ended the sequence: no new run either
        self.forward = "SLURM_JOB_ID" not in os.environ

    def install(self) -> None:
        for s in STOP_SIGNALS:
            if signal.getsignal(s) == signal.SIG_IGN:
                continue  # ignored when we started (SIGHUP under nohup): stays ignored, as in the core
            signal.signal(s, self._handler)

    def exit_code(self) -> int:
        return 128 + self.signum if self.signum else 0

    def _handler(self, signum, frame) -> None:
        now = time.monotonic()
        duplicate = self._last[0] == signum and now - self._last[1] < SAME_REQUEST_SECONDS
        self._last = (signum, now)
        if duplicate:
            return
        second = self.signum != 0
        if not second:
            self.signum = signum
        with self._lock:
            children = list(self._children.values())
        if self.forward:
            for p in children:
                _send(p, signum)
        if second and not children:
            raise SystemExit(128 + self.signum)  # a second request with no run to wait for: at once

    def run(self, cmd, stdout) -> int:
        """Runs CMD to its end (stdout and stderr to STDOUT) unless a stop was requested: then
        starts nothing and returns 128 + N. A run killed by a signal returns 128 + N too."""
        with self._lock:
            if self.signum or self.halted:
                return 128 + (self.signum or signal.SIGTERM)
            p = subprocess.Popen(cmd, stdout=stdout, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                 start_new_session=self.forward)
            self._children[p.pid] = p
        try:
            rc = p.wait()
        finally:
            with self._lock:
                self._children.pop(p.pid, None)
        return 128 - rc if rc < 0 else rc

    def stop_all(self, signum=signal.SIGTERM) -> None:
        """Asks every running run to stop (an error elsewhere ends the sequence) and starts no more."""
        self.halted = True
        with self._lock:
            for p in list(self._children.values()):
                _send(p, signum)


def _send(p, signum) -> None:
    try:
        p.send_signal(signum)
    except OSError:
        pass  # ended meanwhile


STOP = Stop()
