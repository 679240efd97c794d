"""The verdict: each claim of the paper checked on the replication's datasets, by one rule. It reads datasets
and never simulates: it imports only the model and the paper as printed (a test holds it to that).

A claim's entry in ``claims.yaml`` (checked by ``claims.schema.yaml``) gives its quote, its part of the sentence and
its readings, each with the paper's words that admit it and its check: ``module.function`` of this package, declared
by :func:`~.evidence.check` and imported only when the register is evaluated (:func:`.engine.resolved`). A check
reads the scenes it declares and the runs its args name (keys of the ``checks`` block of ``config/paper.yaml``);
:func:`.engine.evaluate` runs it under each reading, :func:`.rule.row_status` gives the row's evidence and status,
and a sentence, one finding, takes :func:`.rule.finding_status` of its parts (:mod:`.tally`). The checks sit one
module per part of the paper, with :mod:`.figure_axes` (the printed panels) and :mod:`.beyond` (beyond the paper).
"""
