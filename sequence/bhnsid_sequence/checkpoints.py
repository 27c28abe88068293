"""A run's checkpoints as the sequence keeps or removes them (2.3 GB each at n = 256). Only the
entries bhnsid itself names in RUN/checkpoints (checkpoint.NNNNNN, and checkpoint.NNNNNN.partial
of a write cut short: the core's own rule for what it removes) are ever touched; anything else
the user put there stays, and the folder goes only when empty. A `checkpoints` that is a link or
a file, or a checkpoint name that is not a regular file, is refused (exit 2): removing through it
would delete another folder's files."""
import errno
import os
import re
import stat
from pathlib import Path
from typing import List, Optional, Tuple

from .safe_io import InputError, refuse

_NAME = re.compile(r"checkpoint\.[0-9]{6}(\.partial)?")


def _open_folder(run_dir: Path) -> Optional[int]:
    path = run_dir / "checkpoints"
    try:
        return os.open(path, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    except FileNotFoundError:
        return None
    except OSError as e:
        if e.errno in (errno.ELOOP, errno.ENOTDIR):
            raise refuse(path, os.lstat(path).st_mode, "folder")
        raise InputError(f"{path}: cannot open: {e.strerror}")


def checkpoint_files(run_dir: Path) -> List[Tuple[str, int]]:
    """(name, bytes) of bhnsid's checkpoint entries in RUN_DIR/checkpoints, by name."""
    fd = _open_folder(run_dir)
    if fd is None:
        return []
    try:
        out = []
        for name in os.listdir(fd):
            if not _NAME.fullmatch(name):
                continue
            st = os.stat(name, dir_fd=fd, follow_symlinks=False)
            if not stat.S_ISREG(st.st_mode):
                raise refuse(run_dir / "checkpoints" / name, st.st_mode, "checkpoint file")
            out.append((name, st.st_size))
        return sorted(out)
    finally:
        os.close(fd)


def is_complete(name: str) -> bool:
    """checkpoint.NNNNNN: a finished one, which a warm start can read."""
    return not name.endswith(".partial")


def has_checkpoint(run_dir: Path) -> bool:
    return any(is_complete(name) for name, _ in checkpoint_files(run_dir))


def _remove(run_dir: Path, keep: Optional[str]) -> None:
    fd = _open_folder(run_dir)
    if fd is None:
        return
    try:
        for name in os.listdir(fd):
            if name == keep or not _NAME.fullmatch(name):
                continue
            st = os.stat(name, dir_fd=fd, follow_symlinks=False)
            if not stat.S_ISREG(st.st_mode):
                raise refuse(run_dir / "checkpoints" / name, st.st_mode, "checkpoint file")
            os.unlink(name, dir_fd=fd)
    finally:
        os.close(fd)
    if keep is None:
        try:
            os.rmdir(run_dir / "checkpoints")
        except OSError:
            pass  # something of the user's is there: not ours to remove


def drop_checkpoints(run_dir: Path) -> None:
    """Removes bhnsid's checkpoint entries of RUN_DIR, and the folder when nothing else is in it."""
    _remove(run_dir, None)


def keep_newest_checkpoint(run_dir: Path) -> None:
    """Of a converged run's checkpoints only the newest complete one, the one a warm start reads;
    bhnsid keeps two so that a run killed while writing can resume, which a converged run never does."""
    complete = [name for name, _ in checkpoint_files(run_dir) if is_complete(name)]
    if complete:
        _remove(run_dir, complete[-1])
    else:
        _remove(run_dir, None)


def checkpoint_bytes(run_dir: Path) -> int:
    return sum(size for _, size in checkpoint_files(run_dir))
