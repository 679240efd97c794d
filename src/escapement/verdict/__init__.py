"""The verdict: each claim of the paper checked on the replication's datasets, by one rule. It reads datasets
and never simulates: it imports only the model and the paper as printed (a test holds it to that).

* :mod:`.rule`: the statuses, the kinds of evidence, and the one rule that gives a row's and a finding's status;
* :mod:`.engine`: the register ``claims.yaml`` (checked by ``claims.schema.yaml``, both package data beside it)
  evaluated into one row per claim; :mod:`.tally`: the findings and the headline;
* :mod:`.evidence`: what every check reads (the datasets) and answers (:class:`~.evidence.Verdict`);
* :mod:`.scores`: the candidate readings of the paper's open choices scored against its printed axes;
* the checks, one module per part of the paper: :mod:`.sec2_model`, :mod:`.sec3_equations` (Eqs. (2)-(5) and the
  words of Sec. 3.3), :mod:`.sec3_steps` (Eqs. (10)-(15)), :mod:`.sec3_map` (Eqs. (7), (8), (16)-(21) and Sec. 3.4),
  :mod:`.sec3_period` (Eqs. (22)-(25)), :mod:`.sec4_fig3`, :mod:`.sec4_fig4`, :mod:`.sec4_fig5` (Sec. 4 by figure;
  its text on no figure with Fig. 3), :mod:`.sec5_conclusions`, :mod:`.figure_axes` (the printed panels) and
  :mod:`.beyond` (results the paper does not state). A check used by several parts sits in the earliest.

Adding a claim is one entry in ``claims.yaml`` (its quote, source, part, readings and tolerance) and, when no
registered check computes it, one function decorated by :func:`~.evidence.check` in the module of its source. A run
the check needs is a variable of the checks dataset, made by :mod:`escapement.scenes.probes` from the ``checks``
block of ``config/paper.yaml``.
"""
