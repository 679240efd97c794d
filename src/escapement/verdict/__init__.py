"""The verdict: each claim of the paper checked on the replication's datasets, by one rule. It reads datasets
and never simulates: it imports only the model and the paper as printed (a test holds it to that).

From a claim's id to its status:

1. its entry in ``claims.yaml`` (checked by ``claims.schema.yaml``) gives its quote, its part of the sentence, its
   readings (each with the paper's words that admit it) and, for each, its check, named ``module.function``, with
   its args and tolerance;
2. the check is declared beside its code by :func:`~.evidence.check`; :func:`.engine.resolved` imports it only when
   the register is evaluated, so :mod:`.rule`, :mod:`.tally` and :mod:`.scores` load no check (nor NumPy or xarray);
3. it reads the scenes it declares (a Fig. 3, 4 or 5 dataset) and the runs its args name (``runs: <name>``, a key
   of the ``checks`` block of ``config/paper.yaml``, read by :func:`.evidence.run`);
4. :func:`.engine.evaluate` runs the check of each reading, :func:`.rule.row_status` gives the row's evidence and
   status, and its sentence, one finding, takes :func:`.rule.finding_status` of its parts (:mod:`.tally`).

The checks sit one module per part of the paper (``sec2_model`` .. ``sec5_conclusions``), with
:mod:`.figure_axes` (the printed panels, scored by :mod:`.scores`) and :mod:`.beyond` (results the paper does not
state). A new claim is one entry in ``claims.yaml`` and, when no check computes it, one function declared by
:func:`~.evidence.check` in the module of its source; runs of its own are added by name to the checks block.
"""
