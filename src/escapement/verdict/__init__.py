"""The verdict: each claim of the paper checked on the replication's datasets, by one rule. It reads datasets
and never simulates: it imports only the model and the paper as printed (a test holds it to that).

From a claim's id to its status:

1. its entry in ``claims.yaml`` (package data beside this module, checked by ``claims.schema.yaml``) gives its
   quote, verbatim, its part of the sentence, its readings (each with the paper's words that admit it) and, for
   each, its check, named ``module.function`` of this package, with its args and tolerance;
2. that function is the check, declared beside its code by :func:`~.evidence.check` (the scenes it reads, the args
   that name its runs, the other args it needs, what it consumes); :func:`.engine.resolved` imports it when the
   register is evaluated, so a module that needs only :mod:`.rule`, :mod:`.tally` or :mod:`.scores` loads no check
   (nor NumPy or xarray: those three read and write text and tables);
3. its runs are the scenes it declares (a Fig. 3, 4 or 5 dataset) and the runs its args name (``runs: <name>``),
   each a key of the ``checks`` block of ``config/paper.yaml``, which alone states their settings; the checks
   scene (:func:`escapement.scenes.runs.checks`) writes each under that name, and the check reads it by that name
   (:func:`.evidence.run`), its settings with it;
4. :func:`.engine.evaluate` runs the check of each reading and :func:`.rule.row_status` gives the row's evidence and
   status (a reading or threshold the project chose weighs agreement and failure alike: consistent, undetermined);
   its sentence, one finding, takes :func:`.rule.finding_status` of its parts (:mod:`.tally`).

For example ``eq21_multiplier`` quotes "The eigenvalue can be obtained by substituting the fixed point into Eq. (20)
μ2 = g (x˙ 1 ∗) = (1 − b)4", read as stated, ``check: sec3_map.multiplier_paper_cases``, ``args: {runs: paper}``,
tolerance 1e-8. That check, ``@check(runs=("runs",))`` in :mod:`.sec3_map`, reads ``run(ev, "paper")``: the rows of
the checks dataset's table of group ``paper``, which the checks block states as ``paper: {from: fig3}`` (the Fig. 3
cases, fig3a and fig3b); it compares each measured mu2 with the printed 0.6561: both hold, the evidence is
independent (the check declares no law, fitted input or threshold), so the row, and its finding, is reproduced.

The checks sit one module per part of the paper, a check used by several parts in the earliest: :mod:`.sec2_model`,
:mod:`.sec3_equations` (Eqs. (2)-(5), Sec. 3.3), :mod:`.sec3_steps` (Eqs. (10)-(15)), :mod:`.sec3_map` (Eqs. (7),
(8), (16)-(21), Sec. 3.4), :mod:`.sec3_period` (Eqs. (22)-(25)), :mod:`.sec4_fig3` (with Sec. 4's text on no
figure), :mod:`.sec4_fig4`, :mod:`.sec4_fig5`, :mod:`.sec5_conclusions`, :mod:`.figure_axes` (the printed panels,
scored by :mod:`.scores`) and :mod:`.beyond` (results the paper does not state). Adding a claim is one entry in
``claims.yaml`` and, when no check computes it, one function declared by :func:`~.evidence.check` in the module of
its source; a claim on runs of its own adds them, by name, to the checks block (and the name to the schema's), and
a new kind of measurement its builder to :data:`escapement.scenes.probes.MEASURES`.
"""
