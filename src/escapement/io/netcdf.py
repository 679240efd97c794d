"""Writing and reading the files: netCDF (compressed, checksummed, stamped with their provenance), CSV and text,
each written to a temporary file beside its target and renamed into place, so that a reader never sees a partial
file. A symbolic link is written through (the link stays, the file it names gets the data). A Ctrl-C during a
netCDF write or read is raised as soon as it returns, and an interrupted write leaves no file; the temporary files
of a killed process are removed by the next write of the same target.
"""

from __future__ import annotations

import csv
import errno
import os
import re
import signal
import tempfile
import threading
from collections.abc import Iterable, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

from .provenance import command_line, provenance_attributes

if TYPE_CHECKING:  # xarray is imported where a netCDF file is read or written: a CSV job does without it
    import xarray as xr

__all__ = ["DatasetError", "interrupt_deferred", "read_csv", "read_netcdf", "read_variables", "replaced",
           "stale_partials", "target_of", "writable_target", "write_csv", "write_netcdf", "write_text"]

#: the suffix of the temporary file a write fills before renaming it to its target
PARTIAL = ".partial"


class DatasetError(RuntimeError):
    """A file is missing, damaged, or lacks what it should hold; the message names it."""


def stale_partials(path: str | os.PathLike) -> list[Path]:
    """The temporary files of earlier (killed) writes of ``path``: ``.<name>.<random>.partial`` beside it, the
    random part without a dot, so that no other target's temporary files match."""
    path = Path(path)
    pattern = re.compile(rf"\.{re.escape(path.name)}\.[^./]+{re.escape(PARTIAL)}")
    return sorted(p for p in path.parent.glob(f".*{PARTIAL}") if pattern.fullmatch(p.name))


def target_of(path: str | os.PathLike) -> Path:
    """The file a write of ``path`` replaces: ``path`` with its symbolic links resolved. :class:`OSError` for a
    loop of links, :class:`IsADirectoryError` for a directory, :class:`FileExistsError` for anything else that
    exists and is not a regular file (a device, a pipe), which the rename would replace."""
    target = Path(os.path.realpath(path))
    if target.is_symlink():  # realpath stops where the links loop
        raise OSError(errno.ELOOP, os.strerror(errno.ELOOP), str(path))
    if target.is_dir():
        raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(target))
    if target.exists() and not target.is_file():
        raise FileExistsError(errno.EEXIST, "not a regular file, which a write would replace", str(target))
    return target


def writable_target(path: str | os.PathLike) -> Path:
    """:func:`target_of` ``path``, once a temporary file named as a write's has been made beside it and removed;
    else the file system's :class:`OSError` (a missing folder, a name too long, a folder that takes no new file:
    tried, as permission bits do not tell access lists, network file systems or read-only mounts)."""
    target = target_of(path)
    with tempfile.NamedTemporaryFile(dir=target.parent, prefix=f".{target.name}.", suffix=PARTIAL):
        pass
    return target


@contextmanager
def replaced(path: str | os.PathLike):
    """A temporary path beside :func:`target_of` ``path`` (its folder made if missing), renamed to it when the
    block ends without an error (removed if it raises); :func:`stale_partials` are removed first (two writes of
    one target at once are not supported: the later removes the earlier's temporary file)."""
    path = target_of(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    for stale in stale_partials(path):
        stale.unlink(missing_ok=True)
    handle, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=PARTIAL)
    os.close(handle)
    try:
        yield Path(tmp)
        mask = os.umask(0)  # mkstemp makes a private file: give it the permissions a new file gets
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    finally:
        Path(tmp).unlink(missing_ok=True)


@contextmanager
def interrupt_deferred():
    """Run the block with a SIGINT recorded instead of raised, delivered to the handler it had once the block has
    ended (outside the main thread, which alone receives signals, the block runs as it is). Hand-written because
    xarray's writer, interrupted inside, can keep a lock it then waits for (a hang until a second Ctrl-C), and
    netCDF4 loses an interrupt that comes while it reads."""
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGINT) is None:
        yield  # a handler installed from outside Python cannot be put back: leave it alone
        return
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if caught:
            signal.raise_signal(signal.SIGINT)  # KeyboardInterrupt under Python's default handler


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike, history: str | None = None) -> Path:
    """Write ``ds`` to ``path`` (as :func:`replaced`) with its provenance (``history``: what wrote it, by default
    this process's command line): data variables compressed (zlib level 4), every variable with a Fletcher-32
    checksum, coordinates without ``_FillValue``. A Ctrl-C (:func:`interrupt_deferred`) is raised when the write
    returns, and no file is left."""
    ds = ds.copy()
    ds.attrs.update(provenance_attributes(history or command_line()))
    encoding = {name: {"zlib": True, "complevel": 4, "fletcher32": True} for name in ds.data_vars}
    encoding.update({name: {"_FillValue": None, "fletcher32": True} for name in ds.coords})
    with replaced(path) as tmp:
        try:
            with interrupt_deferred():
                ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
        except (OSError, RuntimeError) as err:  # what netCDF4 raises when the library fails
            raise DatasetError(f"{path}: cannot write the netCDF file ({type(err).__name__}: {err})") from err
    return Path(path)


def read_netcdf(path: str | os.PathLike, required: Iterable[str] = ()) -> xr.Dataset:
    """The dataset of ``path``, loaded with its checksums checked; :class:`DatasetError` naming the file if it cannot be
    read or lacks a ``required`` variable. A Ctrl-C (:func:`interrupt_deferred`) is raised when it returns."""
    import xarray as xr

    try:
        with interrupt_deferred(), xr.open_dataset(path, engine="netcdf4") as ds:
            loaded = ds.load()
    except FileNotFoundError as err:
        raise DatasetError(f"{path}: no such netCDF file") from err
    except (OSError, RuntimeError, ValueError) as err:  # netCDF4 and xarray on a damaged file
        raise DatasetError(f"{path}: not a readable netCDF file ({type(err).__name__}: {err})") from err
    missing = [name for name in required if name not in loaded.variables]
    if missing:
        raise DatasetError(f"{path}: lacks the variable(s) {', '.join(missing)}")
    return loaded


def read_variables(path: str | os.PathLike, names: Iterable[str]) -> dict:
    """The variables ``names`` of the netCDF file ``path`` as arrays, read without xarray (a job that needs a few
    numbers starts in a fraction of xarray's import); :class:`DatasetError` naming the file as :func:`read_netcdf`."""
    import netCDF4

    names = list(names)
    try:
        with interrupt_deferred(), netCDF4.Dataset(path) as nc:
            nc.set_auto_mask(False)  # a missing value is NaN, as xarray reads it
            missing = [name for name in names if name not in nc.variables]
            found = {name: nc[name][...] for name in names if name not in missing}
    except FileNotFoundError as err:
        raise DatasetError(f"{path}: no such netCDF file") from err
    except (OSError, RuntimeError) as err:  # what netCDF4 raises on a damaged file
        raise DatasetError(f"{path}: not a readable netCDF file ({type(err).__name__}: {err})") from err
    if missing:
        raise DatasetError(f"{path}: lacks the variable(s) {', '.join(missing)}")
    return found


def write_text(text: str, path: str | os.PathLike) -> None:
    with replaced(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def write_csv(rows: Iterable[Mapping], columns: list[str], path: str | os.PathLike) -> None:
    with replaced(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)


def read_csv(path: str | os.PathLike, columns: list[str]) -> list[dict[str, str]]:
    """The rows of ``path``, whose header must be ``columns``; :class:`DatasetError` naming the file if not."""
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            reader = csv.DictReader(handle)
            rows = list(reader)
    except OSError as err:
        raise DatasetError(f"{path}: cannot be read ({err})") from err
    if list(reader.fieldnames or ()) != columns:
        raise DatasetError(f"{path}: not a table with the columns {', '.join(columns)}")
    return rows
