"""One log file per job: what it did, how long it took, and the traceback if it failed."""

from __future__ import annotations

import contextlib
import logging
import time
from collections.abc import Iterator
from pathlib import Path

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
    except Exception:
        logger.exception("%s failed", what)
        raise
    finally:
        logger.removeHandler(handler)
        handler.close()
