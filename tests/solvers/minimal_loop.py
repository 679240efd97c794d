"""The minimal closed-form loop for the escapement's periodic regime, the floor the exact solver is measured
against and a second path to its cycle table: it lives in :mod:`escapement.studies.floor` (with the
ensemble's NumPy floor) and is re-exported here for the tests that load this file."""

from __future__ import annotations

from escapement.studies.floor import TWO_PI, minimal_cycles

__all__ = ["TWO_PI", "minimal_cycles"]
