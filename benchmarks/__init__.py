"""Measurements of the solvers that are not part of the library: the speed floors (:mod:`.floor`), the
least code that computes the solvers' numbers, timed side by side with them for the speed table."""
