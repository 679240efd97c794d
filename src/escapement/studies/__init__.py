"""Studies beyond the paper's figures: the work-precision benchmark, the long run against 50 digits, the readings
of the printed axes, the escapement error, the stress cases and the Poincare measurement on simulated motion. Import
the module you need: the package imports none of them, so that a job loads only the studies it runs.
"""
