"""The sequence directory: its marker (a folder this tool did not make is never written into),
its lock (one pool at a time) and the survey of every entry the sequence will write, made before
anything runs, so that a link or a FIFO where a run directory, a log, a checkpoint folder or a
result file belongs is one error at the start, not a write through it hours later."""
import errno
import fcntl
import os
import socket
import stat
from pathlib import Path
from typing import Iterable

from .runs import Config, log_path
from .safe_io import InputError, expect, kind_of, refuse, write_atomic

MARKER = ".bhnsid-sequence"
LOCK = ".bhnsid-sequence.lock"
# The files the reduction writes in the sequence directory (report.py).
RESULTS = ("sequence.json", "table_min_E_b.md", "table_min_E_b.csv", "table_min_E_b_puncture.md",
           "table_min_E_b_puncture.csv", "table_min_J.md", "table_min_J.csv", "paper_comparison.md", "failures.md",
           "eb.png", "j.png")


def open_root(root: Path, spec_file: Path) -> None:
    """Makes ROOT a sequence directory (its marker written once), or refuses: ROOT a file, a
    folder of someone else's (not empty, no marker), a marker that is not a regular file."""
    try:
        st = os.stat(root)
    except FileNotFoundError:
        st = None
    except OSError as e:
        raise InputError(f"{root}: cannot inspect the sequence directory: {e.strerror}")
    if st is not None and not stat.S_ISDIR(st.st_mode):
        raise InputError(f"{root}: is {kind_of(st.st_mode)}, not a directory; choose another --output")
    if st is not None and not expect(root / MARKER, "file"):
        try:
            foreign = any(os.scandir(root))
        except OSError as e:
            raise InputError(f"{root}: cannot read the directory: {e.strerror}")
        if foreign:
            raise InputError(f"{root}: exists and is not a sequence directory (no {MARKER}); choose another --output")
    try:
        root.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise InputError(f"{root}: cannot create the sequence directory: {e.strerror}")
    if not expect(root / MARKER, "file"):  # SLURM's array tasks all pass here: written once
        write_atomic(root / MARKER, f"{spec_file.resolve()}\n")


def hold_lock(root: Path):
    """The sequence directory's lock (an open descriptor, held until this process exits), or the
    holder's line when another `bhnsid sequence` holds it: two pools in one directory would run the
    same configurations into the same run directories. A SLURM array task and --reduce-only do not
    take it. The lock file is opened with O_NOFOLLOW and must be a regular file."""
    path = root / LOCK
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC, 0o644)
    except OSError as e:
        if e.errno == errno.ELOOP:
            raise refuse(path, stat.S_IFLNK, "lock file")
        raise InputError(f"{path}: cannot open the lock file: {e.strerror}")
    st = os.fstat(fd)
    if not stat.S_ISREG(st.st_mode):
        os.close(fd)
        raise refuse(path, st.st_mode, "lock file")
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError as e:
        holder = os.pread(fd, 200, 0).decode("utf-8", errors="replace").strip()
        os.close(fd)
        if e.errno in (errno.EWOULDBLOCK, errno.EAGAIN):
            return None, holder or "a process"
        raise InputError(f"{path}: cannot lock: {e.strerror} (a file system without flock, such as Lustre "
                         f"mounted without -o flock?)")
    try:
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"pid {os.getpid()} on {socket.gethostname()}\n".encode(), 0)
    except OSError as e:  # a full disk or a file-size limit: the lock is held, its holder not written
        os.close(fd)
        raise InputError(f"{path}: cannot write the lock's holder: {e.strerror}")
    return fd, None


def survey(root: Path, configs: Iterable[Config], results: bool = True) -> None:
    """Refuses (InputError, naming it) any entry the sequence would write or read that is not
    what it writes there: the folders grid*/xa*/rho* and a run's checkpoints/ as folders, a run's
    log rhoR.out, summary.json and timers.tsv and the result files as regular files."""
    seen = set()
    for c in configs:
        run_dir = root / c.relative_dir
        for folder in (run_dir.parent.parent, run_dir.parent):
            if folder not in seen:
                seen.add(folder)
                expect(folder, "folder")
        if expect(run_dir, "folder"):
            for name in ("summary.json", "timers.tsv"):
                expect(run_dir / name, "file")
            expect(run_dir / "checkpoints", "folder")
        expect(log_path(run_dir), "file")
    if results:
        for name in RESULTS:
            expect(root / name, "file")

