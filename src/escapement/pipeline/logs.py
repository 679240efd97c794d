"""One log file per job: what it did, how long it took, and why it failed: one line for an OSError or a missing or
damaged file (a DatasetError), the traceback for anything else."""

from __future__ import annotations

import contextlib
import logging
import time
from collections.abc import Iterator
from pathlib import Path

from ..io.netcdf import DatasetError

__all__ = ["logged"]


@contextlib.contextmanager
def logged(log: str | Path, what: str) -> Iterator[logging.Logger]:
    """Log to ``log`` (replacing it) for the duration of one job."""
    logger = logging.getLogger(f"escapement.pipeline.{what}")
    logger.setLevel(logging.INFO)
    Path(log).parent.mkdir(parents=True, exist_ok=True)
    handler = logging.FileHandler(log, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
    logger.addHandler(handler)
    start = time.perf_counter()
    try:
        yield logger
        logger.info("%s done in %.3f s", what, time.perf_counter() - start)
    except (OSError, DatasetError) as err:  # not a fault of the code: one line naming the file and the cause
        logger.error("%s failed: %s", what, err)
        raise SystemExit(f"{what} failed: {err}") from None
    except Exception:
        logger.exception("%s failed", what)
        raise
    finally:
        logger.removeHandler(handler)
        handler.close()
