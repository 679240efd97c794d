"""The experiments: each scene of the workflow run and measured, its results returned plain.

Above the solvers, the paper's equations and the studies, below input and output: the runs of
Figs. 3, 4 and 5 (:mod:`.figures`), the runs of the claims register (:mod:`.checks`), the long
run (:mod:`.long_run`), a chunk of the stability map (:mod:`.stability`) and the escapement
error (:mod:`.escapement_error`). Each returns runs, arrays and numbers, never a dataset or a
file: :mod:`escapement.io` makes the datasets of them and writes them, and
:mod:`escapement.pipeline` calls the one, then the other.
"""
