"""The verdict: each claim of the paper checked on the replication's datasets, by one rule. It reads datasets
and never simulates: it imports only the model and the paper as printed (a test holds it to that).

A claim's entry in ``claims.yaml`` gives its quote, its part of the sentence and its readings, each with the paper's
words that admit it and its check (``module.function``, declared by :func:`~.evidence.check`, imported only when the
register is evaluated). A check reads the scenes it declares and the runs its args name (keys of the ``checks`` block
of ``config/paper.yaml``); :mod:`.engine` runs it under each reading, :mod:`.rule` gives the row's status and
:mod:`.tally` the findings'. One module of checks per part of the paper, with :mod:`.figure_axes` and :mod:`.beyond`.
"""
