"""Reading and writing inside a sequence directory without following a symbolic link, without
waiting on a FIFO or a device, and without leaving a half-written file under a final name. The
threat model is a careless user or a shared folder (a link or a FIFO left where a file of ours
was), not an attacker racing a check against its use: each entry is checked once, with lstat or
O_NOFOLLOW, when it is reached."""
import errno
import os
import stat
import sys
import tempfile
from pathlib import Path

# The umask, read once at import (in the main thread, before any worker thread), because mkstemp
# creates 0600 files and os.umask can only be read by setting it.
_UMASK = os.umask(0o022)
os.umask(_UMASK)


def one_line(text: str) -> str:
    """TEXT with every control character shown as \\xNN (a newline in a path included), as the core
    shows names: an error is one line whatever the names in it hold."""
    return "".join(c if c.isprintable() or c == " " else f"\\x{ord(c):02x}" for c in text)


class InputError(Exception):
    """Bad input or a refused entry: one line on stderr and exit 2."""

    def __init__(self, message: str):
        super().__init__(one_line(message))


def kind_of(mode: int) -> str:
    if stat.S_ISLNK(mode):
        return "a symbolic link"
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "a regular file"


def refuse(path, mode: int, want: str) -> InputError:
    return InputError(f"{path}: is {kind_of(mode)}, not the {want} bhnsid sequence writes there; "
                      f"move it away or choose another --output")


def expect(path, want: str) -> bool:
    """True when PATH is there as WANT ("file": a regular file, "folder": a directory), False when
    absent; anything else there (a symbolic link, a FIFO, ...) is refused."""
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return False
    except OSError as e:
        raise InputError(f"{path}: cannot inspect: {e.strerror}")
    ok = stat.S_ISREG(st.st_mode) if want == "file" else stat.S_ISDIR(st.st_mode)
    if not ok:
        raise refuse(path, st.st_mode, want)
    return True


def read_regular(path, cap: int, follow: bool = False, what: str = "") -> bytes:
    """The bytes of a regular file of at most CAP bytes. Opened non-blocking (a FIFO or a device is
    refused at once by fstat, never waited on or read without end) and, unless FOLLOW, without
    following a symbolic link. OSError for a missing or unreadable file, InputError for the rest."""
    flags = os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC | (0 if follow else os.O_NOFOLLOW)
    try:
        fd = os.open(path, flags)
    except OSError as e:
        if not follow and e.errno == errno.ELOOP:  # the name is a symbolic link
            raise refuse(path, stat.S_IFLNK, what or "file")
        raise
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise InputError(f"{path}: is {kind_of(st.st_mode)}, not a regular file")
        if st.st_size > cap:
            raise InputError(f"{path}: {st.st_size} bytes, more than the {cap} read from {what or 'it'}")
        chunks, size = [], 0
        while size <= cap:
            chunk = os.read(fd, min(1 << 16, cap + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > cap:
            raise InputError(f"{path}: grew past {cap} bytes while being read")
        return b"".join(chunks)
    finally:
        os.close(fd)


def read_text_or_none(path, cap: int):
    """A small file of a run directory as text, None when absent or unreadable (a run not yet
    written); a link or a FIFO in its place is refused (read_regular)."""
    try:
        return read_regular(path, cap).decode("utf-8", errors="replace")
    except InputError:
        raise
    except OSError:
        return None


def fsync_folder(folder) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass  # some file systems cannot sync a directory; the rename itself is still atomic
    finally:
        os.close(fd)


def write_atomic(path, data, mode: int = 0o644) -> None:
    """PATH holds DATA (str or bytes) completely or keeps what it held (write_with)."""
    if isinstance(data, str):
        data = data.encode()
    write_with(path, lambda f: f.write(data), mode)


def write_with(path, writer, mode: int = 0o644) -> None:
    """PATH holds what WRITER(binary file) writes, completely, or keeps what it held: written under
    a fresh private name in the same folder (mkstemp: O_CREAT|O_EXCL, so no existing name, link or
    not, is ever opened), fsynced, renamed over PATH, the folder fsynced. A PATH that is there as
    anything but a regular file is refused. A full disk is one InputError naming the file."""
    path = Path(path)
    expect(path, "file")
    try:
        fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".partial", dir=path.parent)
    except OSError as e:
        raise InputError(f"{path}: cannot write: {e.strerror}")
    try:
        os.fchmod(fd, mode & ~_UMASK)
        with os.fdopen(fd, "wb") as f:
            writer(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError as e:
        _unlink_quietly(tmp)
        raise InputError(f"{path}: cannot write: {e.strerror}")
    except BaseException:
        _unlink_quietly(tmp)
        raise
    fsync_folder(path.parent)


def _unlink_quietly(path) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass


def create_log(path):
    """A fresh log file at PATH (a run's rhoR.out), open for writing as text: an old regular file
    there is unlinked first and the new one created with O_EXCL|O_NOFOLLOW, so neither a link nor a
    second hard link of another file is ever written through; anything else there is refused."""
    if expect(path, "file"):
        os.unlink(path)
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
    except FileExistsError:
        raise InputError(f"{path}: appeared while it was being replaced; is another process writing here?")
    except OSError as e:
        raise InputError(f"{path}: cannot create: {e.strerror}")
    return os.fdopen(fd, "w")


def make_folders(root: Path, relative: Path) -> Path:
    """ROOT/RELATIVE, each folder below ROOT made when absent; one that is there as a link or a
    file is refused (a run would otherwise write wherever the link points)."""
    path = Path(root)
    try:
        path.mkdir(parents=True, exist_ok=True)  # the sequence directory itself, as the user named it
    except OSError as e:
        raise InputError(f"{path}: cannot create the folder: {e.strerror}")
    for part in Path(relative).parts:
        path = path / part
        if not expect(path, "folder"):
            try:
                os.mkdir(path)
            except FileExistsError:
                expect(path, "folder")
            except OSError as e:
                raise InputError(f"{path}: cannot create the folder: {e.strerror}")
    return path


def read_tail(path, size: int):
    """The last SIZE bytes of a regular file as text (a log's last lines), None when absent."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError as e:
        if e.errno == errno.ELOOP:
            raise refuse(path, stat.S_IFLNK, "file")
        return None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise InputError(f"{path}: is {kind_of(st.st_mode)}, not a regular file")
        return os.pread(fd, size, max(0, st.st_size - size)).decode("utf-8", errors="replace")
    finally:
        os.close(fd)


def say(text: str, stream=None) -> None:
    """One line to the terminal (stdout unless STREAM), a name's control characters shown as \\xNN.
    A closed pipe or terminal does not stop a sequence of hours: the stream is pointed at /dev/null
    and the runs go on, as `bhnsid run` does."""
    stream = stream or sys.stdout
    try:
        print(one_line(text), file=stream, flush=True)
    except (OSError, ValueError):
        try:
            fd = os.open(os.devnull, os.O_WRONLY)
            os.dup2(fd, stream.fileno())
            os.close(fd)
        except (OSError, ValueError, AttributeError):
            pass
