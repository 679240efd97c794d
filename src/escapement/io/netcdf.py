"""Writing and reading the files: netCDF (compressed, checksummed, stamped with their provenance), CSV and text, each
replaced whole (:func:`replaced`), so that a reader never sees a partial file.

Every file proves it is whole before it is read: a CSV file's first line is ``# rows: N; sha256: <hex>``, the digest
of the bytes after it; a netCDF file's global attribute ``sha256`` digests its raw variables and every other
attribute (Fletcher-32 does not cover the attributes). A file cut, emptied or changed is refused in one line naming
the command that rebuilds it.
"""

from __future__ import annotations

import csv
import errno
import hashlib
import io
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
#: the global attribute of a netCDF file that holds its digest (:func:`netcdf_digest`)
DIGEST = "sha256"
#: what netCDF4 and HDF5 raise on reading a damaged file (its header, its data, its attributes, its names: a
#: UnicodeDecodeError is a ValueError)
DAMAGED = (OSError, RuntimeError, AttributeError, KeyError, ValueError)


class DatasetError(RuntimeError):
    """A file is missing, damaged, or lacks what it should hold; the message names it."""


def damaged(path: str | os.PathLike, why: str) -> DatasetError:
    """The one-line refusal of the damaged file ``path``, naming the command that rebuilds it."""
    return DatasetError(f"{path}: damaged ({' '.join(why.split())}); rebuild it: snakemake --cores 2 --forcerun {path}")


def netcdf_digest(nc) -> str:
    """The sha256 of the open netCDF4 dataset ``nc``, its variables read raw, so that no decoding can change it."""
    import numpy as np

    nc.set_auto_maskandscale(False)
    nc.set_auto_chartostring(False)
    digest = hashlib.sha256()

    def add(*parts):
        for part in parts:
            part = np.asarray(part)
            digest.update(repr(part.ravel().tolist()).encode() if part.dtype == object else part.tobytes())
            digest.update(f"\0{part.dtype.str}{part.shape}\0".encode())

    add(*(x for name in sorted(set(nc.ncattrs()) - {DIGEST}) for x in (name, nc.getncattr(name))))
    for name, variable in sorted(nc.variables.items()):
        add(name, str(variable.dtype), *variable.dimensions, variable.shape, variable[...])
        add(*(x for attr in sorted(variable.ncattrs()) for x in (attr, variable.getncattr(attr))))
    return digest.hexdigest()


@contextmanager
def checked_netcdf(path: str | os.PathLike):
    """The netCDF4 dataset of ``path``, open, once its digest is checked; else :class:`DatasetError`."""
    import netCDF4

    with interrupt_deferred():
        nc = None
        try:
            nc = netCDF4.Dataset(path)
            stored = nc.getncattr(DIGEST) if DIGEST in nc.ncattrs() else None
            whole = stored == netcdf_digest(nc)
        except FileNotFoundError as err:
            raise DatasetError(f"{path}: no such netCDF file") from err
        except DAMAGED as err:
            if nc is not None:
                nc.close()
            raise damaged(path, f"{type(err).__name__}: {getattr(err, 'strerror', None) or err}") from err
        with nc:  # the caller's block reads what the digest vouched for: its errors are its own, not damage
            if not whole:
                raise damaged(path, f"its content does not match its digest ({DIGEST} = {stored!r})")
            yield nc


def stale_partials(path: str | os.PathLike) -> list[Path]:
    """The temporary files of earlier (killed) writes of ``path``: ``.<name>.<random without a dot>.partial``."""
    path = Path(path)
    pattern = re.compile(rf"\.{re.escape(path.name)}\.[^./]+{re.escape(PARTIAL)}")
    return sorted(p for p in path.parent.glob(f".*{PARTIAL}") if pattern.fullmatch(p.name))


def target_of(path: str | os.PathLike) -> Path:
    """The file a write of ``path`` replaces, its symbolic links resolved; :class:`OSError` for a loop of links,
    :class:`IsADirectoryError` for a directory, :class:`FileExistsError` for anything else not a regular file."""
    target = Path(os.path.realpath(path))
    if target.is_symlink():  # realpath stops where the links loop
        raise OSError(errno.ELOOP, os.strerror(errno.ELOOP), str(path))
    if target.is_dir():
        raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(target))
    if target.exists() and not target.is_file():
        raise FileExistsError(errno.EEXIST, "not a regular file, which a write would replace", str(target))
    return target


def writable_target(path: str | os.PathLike) -> Path:
    """:func:`target_of` ``path``, once a temporary file has been made beside it and removed (permission bits do
    not tell access lists, network file systems or read-only mounts); else the file system's :class:`OSError`."""
    target = target_of(path)
    with tempfile.NamedTemporaryFile(dir=target.parent, prefix=f".{target.name}.", suffix=PARTIAL):
        pass
    return target


@contextmanager
def replaced(path: str | os.PathLike):
    """A temporary path beside :func:`target_of` ``path``, renamed to it when the block ends without an error
    (removed if it raises); :func:`stale_partials` are removed first."""
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
    """Run the block with a SIGINT recorded instead of raised, delivered once the block has ended. Hand-written
    because xarray's writer, interrupted inside, can keep a lock it then waits for, and netCDF4 loses an interrupt
    that comes while it reads."""
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
    """Write ``ds`` to ``path`` with its provenance (``history``: what wrote it, by default this process's command
    line), compressed, checksummed and stamped with its digest; an interrupted write leaves no file."""
    import netCDF4

    ds = ds.copy()
    ds.attrs.update(provenance_attributes(history or command_line()))
    encoding = {name: {"zlib": True, "complevel": 4, "fletcher32": True} for name in ds.data_vars}
    encoding.update({name: {"_FillValue": None, "fletcher32": True} for name in ds.coords})
    with replaced(path) as tmp:
        try:
            with interrupt_deferred():
                ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
                with netCDF4.Dataset(tmp, "a") as nc:
                    nc.setncattr(DIGEST, netcdf_digest(nc))
        except (OSError, RuntimeError) as err:  # what netCDF4 raises when the library fails
            raise DatasetError(f"{path}: cannot write the netCDF file ({type(err).__name__}: {err})") from err
    return Path(path)


def read_netcdf(path: str | os.PathLike, required: Iterable[str] = ()) -> xr.Dataset:
    """The dataset of ``path``, loaded once :func:`checked_netcdf` has checked it and found the ``required``
    variables; else :class:`DatasetError` naming the file."""
    import xarray as xr

    with checked_netcdf(path) as nc:
        _require(path, required, nc.variables)
        loaded = xr.open_dataset(xr.backends.NetCDF4DataStore(nc)).load()
    loaded.set_close(None)  # the file is closed: read from the checked handle, not opened again
    return loaded


def read_variables(path: str | os.PathLike, names: Iterable[str]) -> dict:
    """The variables ``names`` of the netCDF file ``path`` as arrays, read without xarray (a fraction of its import
    time); :class:`DatasetError` naming the file as :func:`read_netcdf`."""
    with checked_netcdf(path) as nc:
        _require(path, names := list(names), nc.variables)
        nc.set_auto_maskandscale(True)  # the digest read the values raw: scaled again,
        nc.set_auto_mask(False)  # but a missing value is NaN, as xarray reads it
        nc.set_auto_chartostring(True)
        return {name: nc[name][...] for name in names}


def _require(path, names: Iterable[str], present) -> None:
    if missing := [name for name in names if name not in present]:
        raise DatasetError(f"{path}: lacks the variable(s) {', '.join(missing)}")


def write_text(text: str, path: str | os.PathLike) -> None:
    with replaced(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def write_csv(rows: Iterable[Mapping], columns: list[str], path: str | os.PathLike) -> None:
    """The table ``rows`` with the header ``columns``, under the first line of its row count and digest."""
    text, rows = io.StringIO(), list(rows)
    writer = csv.DictWriter(text, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    body = text.getvalue().encode("utf-8")
    with replaced(path) as tmp:
        tmp.write_bytes(f"# rows: {len(rows)}; sha256: {hashlib.sha256(body).hexdigest()}\n".encode() + body)


def read_csv(path: str | os.PathLike, columns: list[str]) -> list[dict[str, str]]:
    """The rows of ``path``, whose header must be ``columns``, once its row count and digest are checked."""
    try:
        head, _, body = Path(path).read_bytes().partition(b"\n")
    except OSError as err:
        raise DatasetError(f"{path}: cannot be read ({err})") from err
    stamp = re.fullmatch(rb"# rows: (\d+); sha256: ([0-9a-f]{64})", head)
    if stamp is None:
        raise damaged(path, f"its first line is {head[:80]!r}, not '# rows: N; sha256: <hex>'")
    if hashlib.sha256(body).hexdigest() != stamp[2].decode():
        raise damaged(path, "its content does not match its digest")
    reader = csv.DictReader(io.StringIO(body.decode("utf-8"), newline=""))
    rows = list(reader)
    if len(rows) != int(stamp[1]):
        raise damaged(path, f"it holds {len(rows)} rows, its first line says {int(stamp[1])}")
    if list(reader.fieldnames or ()) != columns:
        raise DatasetError(f"{path}: not a table with the columns {', '.join(columns)}; rebuild it: "
                           f"snakemake --cores 2 --forcerun {path}")
    return rows
