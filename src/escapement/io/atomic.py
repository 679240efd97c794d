"""Atomic file writing: into a temporary file beside the target, renamed into place at the end.

A reader never sees a partial file, and a failure leaves nothing behind. A process killed outright
(``SIGKILL``, power loss) cannot remove its temporary: each temporary is named after its writer,
``.{name}.{host}-{pid}.{random}.partial{suffix}`` (the target's own suffix last, for writers that
choose the format from it), so that a later write of the same target, or
:func:`remove_stale_temporaries`, removes those whose writer no longer runs.

A failed write raises :class:`WriteError` (an :class:`OSError`) naming the target and the cause:
no space left on device, permission denied, read-only file system. :func:`check_target` finds,
before any work, whether a target can be written where it is named, its directory already made.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import glob
import os
import re
import socket
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import NoReturn

__all__ = ["WriteError", "atomic_path", "check_target", "remove_stale_temporaries", "write_csv", "write_failure"]

#: the random part of a temporary's name, as :func:`tempfile.mkstemp` makes it
_RANDOM = r"[a-z0-9_]{8}"
#: any temporary of :func:`atomic_path`; the name, host and pid of its writer, and its suffix
_TEMPORARY = re.compile(
    rf"\.(?P<name>.+)\.(?P<host>[A-Za-z0-9-]+)-(?P<pid>[1-9][0-9]*)\.{_RANDOM}\.partial(?P<suffix>\.[^.]+)"
)
#: error numbers that mean a write failed, whichever file the error names
_WRITE_ERRNOS = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EROFS})


class WriteError(OSError):
    """A file could not be written; the message names the file and the cause."""

    def __str__(self) -> str:
        return f"{self.filename}: cannot write: {self.strerror}"


def _host() -> str:
    """This machine's name as it may stand in a file name: the first label, letters, digits and ``-``."""
    label = socket.gethostname().split(".")[0]
    return re.sub(r"[^A-Za-z0-9-]", "-", label) or "localhost"


def _suffix(path: Path) -> str:
    return path.suffix or ".tmp"


def _is_zombie(pid: int) -> bool:
    """Whether ``pid`` has ended and waits for its parent to collect it (Linux; elsewhere False)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except FileNotFoundError:  # no /proc, or the process has just been collected
        return False
    return stat.rpartition(")")[2].split()[0] == "Z"


def _writer_alive(host: str, pid: int) -> bool:
    """Whether the process that made a temporary may still run; a writer on another machine (a
    cluster node sharing the file system) cannot be checked, so counts as alive."""
    if host != _host():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # it exists, under another user
        return True
    return not _is_zombie(pid)


def _remove_if_stale(entry: Path, match: re.Match) -> bool:
    if match["suffix"] != _suffix(Path(match["name"])) or _writer_alive(match["host"], int(match["pid"])):
        return False
    entry.unlink(missing_ok=True)  # missing: another run removed it first
    return True


def _remove_stale_of(path: Path) -> None:
    """Remove the temporaries of ``path`` left by writers that no longer run."""
    if not path.parent.is_dir():
        return
    # One pass over the entries of the target's directory whose names start like its temporaries.
    for entry in path.parent.glob(f".{glob.escape(path.name)}.*.partial*"):
        match = _TEMPORARY.fullmatch(entry.name)
        if match and match["name"] == path.name and entry.is_file():
            _remove_if_stale(entry, match)


def _raise(err: OSError) -> NoReturn:
    raise err


def remove_stale_temporaries(directory: str | os.PathLike, recursive: bool = False) -> list[Path]:
    """Remove the temporaries of :func:`atomic_path` in ``directory`` (and its subdirectories if
    ``recursive``, symbolic links not followed) whose writer no longer runs; return them.

    Only files named like a temporary are considered, and only those made on this machine by a process
    that has ended: a live writer's temporary, or one made on another machine, is kept. A directory that
    does not exist holds none. A pid reused by a new process keeps its temporary until a later call.
    """
    directory = Path(directory)
    if not directory.is_dir():
        return []
    removed = []
    # os.walk visits each directory of the tree once (no links followed); one pass over its files.
    for root, dirs, files in os.walk(directory, onerror=_raise):
        for name in files:
            match = _TEMPORARY.fullmatch(name)
            entry = Path(root) / name
            if match and _remove_if_stale(entry, match):
                removed.append(entry)
        if not recursive:
            dirs.clear()
    return sorted(removed)


def _existing_directory(path: Path) -> Path:
    """The nearest directory of ``path`` that exists (its parent, or one above it)."""
    for directory in (path.parent, *path.parent.parents):  # at most the depth of the path
        if directory.is_dir():
            return directory
    return Path(".")


def _free_bytes(directory: Path) -> int:
    """Bytes this process may still write on the file system holding ``directory``."""
    stat = os.statvfs(directory)
    blocks = stat.f_bfree if os.geteuid() == 0 else stat.f_bavail  # root may use the reserved blocks
    return blocks * stat.f_frsize


def _probe(directory: Path, needed: int) -> int | None:
    """The error number of what makes writing in ``directory`` fail, found from the file system:
    read-only, not writable, or fewer than ``needed`` bytes free; None if none of these."""
    if os.statvfs(directory).f_flag & os.ST_RDONLY:
        return errno.EROFS
    if not os.access(directory, os.W_OK | os.X_OK):
        return errno.EACCES
    if _free_bytes(directory) < needed:
        return errno.ENOSPC
    return None


def write_failure(path: str | os.PathLike, err: BaseException, needed: int = 1) -> WriteError | None:
    """The :class:`WriteError` that names ``path`` and the cause of ``err``, a failed write of it.

    The cause is the error's number if it has one; otherwise (a library reporting only, say,
    ``NetCDF: HDF error``) it is found from the file system: read-only, not writable, or fewer than
    ``needed`` bytes free. None if no cause is found: the failure is then not the file system's.
    """
    path = Path(path)
    directory = _existing_directory(path)
    code = getattr(err, "errno", None)
    if not isinstance(code, int) or code <= 0:  # netCDF4 gives its own negative codes
        code = _probe(directory, needed)
    if code is None:
        return None
    if code in (errno.ENOSPC, errno.EDQUOT):
        cause = f"{os.strerror(code).lower()} ({_free_bytes(directory)} bytes free"
        cause += f", {needed} bytes to write)" if needed > 1 else ")"
    elif code in (errno.EACCES, errno.EPERM):
        cause = f"permission denied (in {directory})"
    else:
        cause = os.strerror(code).lower()
    if not isinstance(err, OSError) or err.errno != code:
        cause += f" [{type(err).__name__}: {err}]"
    return WriteError(code, cause, str(path))


def _concerns(err: OSError, tmp: Path) -> bool:
    """Whether an error raised while writing the temporary ``tmp`` is a failure to write it (rather
    than, say, to read the file being copied into it)."""
    if err.filename is None:
        return err.errno in _WRITE_ERRNOS
    return os.fspath(err.filename) == os.fspath(tmp)


def _raise_write_failure(path: Path, err: OSError) -> NoReturn:
    """Raise the :class:`WriteError` naming ``path`` and the cause of ``err``, or ``err`` itself."""
    failure = write_failure(path, err)
    if failure is None:
        raise err
    raise failure from err


def _remove_temporary(tmp: Path, err: BaseException) -> None:
    """Remove the temporary of a failed write, emptied first: a writer may have left it open (netCDF
    does when a full disk makes its closing fail), and its space would stay taken while it is open."""
    try:
        if tmp.is_file() and not tmp.is_symlink():
            os.truncate(tmp, 0)
        tmp.unlink(missing_ok=True)
    except OSError as cleanup:  # e.g. the file system became read-only: the first error matters more
        err.add_note(f"the temporary {tmp} could not be removed: {cleanup}")


def _make_temporary(path: Path) -> Path:
    """Make the empty temporary of ``path`` in its directory; raise :class:`WriteError` if it cannot be."""
    try:
        fd, name = tempfile.mkstemp(
            prefix=f".{path.name}.{_host()}-{os.getpid()}.", suffix=f".partial{_suffix(path)}", dir=path.parent
        )
    except OSError as err:
        _raise_write_failure(path, err)
    os.close(fd)
    return Path(name)


def _mode(entry: Path, path: Path) -> int | None:
    """The file mode of ``entry`` (symbolic links followed), None if it does not exist; a failure to look
    raises :class:`WriteError` naming ``path``, the target."""
    try:
        return os.stat(entry).st_mode
    except FileNotFoundError:
        return None
    except NotADirectoryError as err:  # a component above it is a file
        raise WriteError(errno.ENOTDIR, f"a component of {entry} is not a directory", str(path)) from err
    except PermissionError as err:
        raise WriteError(errno.EACCES, f"permission denied (in {entry.parent})", str(path)) from err
    except OSError as err:  # a name too long, a loop of symbolic links
        if err.errno not in (errno.ENAMETOOLONG, errno.ELOOP):
            raise
        raise WriteError(err.errno, os.strerror(err.errno).lower(), str(path)) from err


def check_target(path: str | os.PathLike) -> None:
    """Raise :class:`WriteError` naming ``path`` and the cause if :func:`atomic_path` could not write it
    in its directory as it stands: the directory does not exist (unlike :func:`atomic_path`, this makes
    none), is not a directory, cannot be searched; a file cannot be made in it (permission denied,
    read-only file system, the temporary's name too long for it); the target is a directory or other
    than a regular file. Nothing is left behind: the probe is an empty temporary, removed at once."""
    path = Path(path)
    directory = path.parent
    mode = _mode(directory, path)
    if mode is None:
        raise WriteError(errno.ENOENT, f"the directory {directory} does not exist", str(path))
    if not stat.S_ISDIR(mode):
        raise WriteError(errno.ENOTDIR, f"{directory} is not a directory", str(path))
    mode = _mode(path, path)
    if mode is not None and stat.S_ISDIR(mode):
        raise WriteError(errno.EISDIR, "it is a directory", str(path))
    if mode is not None and not stat.S_ISREG(mode):
        raise WriteError(errno.EINVAL, "it exists and is not a regular file (a device, pipe or socket)", str(path))
    _make_temporary(path).unlink()


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path to write; on success it replaces ``path`` (with the umask's
    permissions), on failure it is removed.

    The temporaries of ``path`` that writers killed before the end left behind are removed first.
    A failure to write raises :class:`WriteError` naming ``path`` and the cause.
    """
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        _raise_write_failure(path, err)
    _remove_stale_of(path)  # an error names the temporary it could not remove
    tmp = _make_temporary(path)
    try:
        try:
            yield tmp
        except OSError as err:
            if _concerns(err, tmp):
                _raise_write_failure(path, err)
            raise
        try:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)
            os.replace(tmp, path)
        except OSError as err:
            _raise_write_failure(path, err)
    except BaseException as err:
        _remove_temporary(tmp, err)
        raise


def write_csv(rows: list[dict], columns: list[str], path: str | os.PathLike) -> None:
    """Write ``rows`` (mappings with exactly ``columns``) as CSV, atomically."""
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
