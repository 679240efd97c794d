"""Studies beyond the paper's figures: the work-precision benchmark (:mod:`.benchmark`), the long run
against 50 digits (:mod:`.long_run`), the readings of the printed axes (:mod:`.readings`), the escapement
error (:mod:`.escapement_error`), the stress cases (:mod:`.stress`) and the measurement of the Poincare map on
simulated motion (:mod:`.poincare`). Import the module you need: the package imports none of them, so that a job
loads only the studies it runs.
"""
