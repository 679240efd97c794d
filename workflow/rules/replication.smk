# The replication's own jobs: the runs that check the paper's claims, the readings of its printed axes,
# the verdict, the documents, and the explicit publish step that updates the tracked files.


rule checks:
    output:
        nc="results/replication/checks.nc",
    log:
        "results/logs/replication/checks.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="checks",
        scene=RUNS["checks"],
        code=CODE,
    script:
        "../scripts/simulate.py"


rule long_run:
    output:
        nc="results/replication/long_run.nc",
        timing="results/replication/long_run_timing.csv",
    log:
        "results/logs/replication/long_run.log",
    priority: 10  # one of the two longest jobs, at the head of a chain (stress table, its figure): started first
    conda:
        "../../environment/environment.yml"
    params:
        kind="long_run",
        scene=RUNS["long_run"],
        code=CODE,
    script:
        "../scripts/simulate.py"


# The paper's unstated choices read from its printed axes: every candidate reading simulated and
# autoscaled to the printed tick steps, scored by the printed limits it reproduces.
rule readings:
    output:
        csv="results/replication/readings.csv",  # 0.4 MB: out of the report; REPLICATION.md, Sec. 3, sums it up
    log:
        "results/logs/replication/readings.log",
    priority: 5  # the claims wait for it
    conda:
        "../../environment/environment.yml"
    params:
        settings={
            "model": PAPER["model"],
            "fig3": PAPER["fig3"],
            "fig4": {
                k: PAPER["fig4"][k]
                for k in (
                    "velocity_window",
                    "acceleration_window",
                    "samples_per_second",
                )
            },
            "fig5": {
                k: PAPER["fig5"][k] for k in ("K", "n_cycles", "samples_per_period")
            },
        },
        code=CODE,
    script:
        "../scripts/readings.py"


rule check_claims:
    input:
        register="src/escapement/verdict/claims.yaml",
        schema="src/escapement/verdict/claims.schema.yaml",
        fig3=outputs.data_files(
            "replication", "fig3", STUDIES["replication"]["fig3"]
        ).values(),
        fig4="results/replication/shock_detail.nc",
        fig5=outputs.data_files(
            "replication", "fig5", STUDIES["replication"]["fig5"]
        ).values(),
        checks="results/replication/checks.nc",
        readings="results/replication/readings.csv",
    output:
        csv=report(
            "results/replication/claims.csv",
            caption="../report/claims.rst",
            category="Verdict",
            labels={"table": "claims register"},
        ),
        # the limits each axis claim judged, which the article cites
        limits="results/replication/panel_limits.csv",
    log:
        "results/logs/replication/check_claims.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        fig3=outputs.data_files("replication", "fig3", STUDIES["replication"]["fig3"]),
        fig5=outputs.data_files("replication", "fig5", STUDIES["replication"]["fig5"]),
        settings={"checks": PAPER["checks"]},
        code=CODE,
    script:
        "../scripts/check_claims.py"


rule run_stress:
    input:
        long_run="results/replication/long_run.nc",
    output:
        csv=report(
            "results/replication/stress.csv",
            caption="../report/stress.rst",
            category="Speed and accuracy",
            labels={"table": "stress cases"},
        ),
    log:
        "results/logs/replication/stress.log",
    conda:
        "../../environment/environment.yml"
    params:
        code=CODE,
    script:
        "../scripts/stress.py"


# The documents, in two jobs of few inputs each: the Markdown documents with the report's HTML (the landing text,
# the claims register, REPLICATION.md), and the ReScience C article (escapement.pipeline.docs and .article). The texts
# they read are inputs and, by their contents, params: Snakemake follows an input's modification time only.
DOC_TEXTS = {
    "readme": "workflow/templates/README.md",
    "replication": "workflow/templates/REPLICATION.md",
    "timings": "workflow/templates/timings.md",
}
ARTICLE_TEXTS = {
    "citation": "CITATION.cff",
    "template": "workflow/templates/article.typ",
    "bibliography": "workflow/templates/article.bib",
}


rule render_docs:
    input:
        **DOC_TEXTS,
        claims="results/replication/claims.csv",
        stress="results/replication/stress.csv",
        readings="results/replication/readings.csv",
        checks="results/replication/checks.nc",
        fig3=outputs.data_files(
            "replication", "fig3", STUDIES["replication"]["fig3"]
        ).values(),
        benchmark="results/replication/work_precision.csv",
        long_run="results/replication/long_run.nc",
        long_run_timing="results/replication/long_run_timing.csv",
        stability="results/replication/stability_map.nc",
        stability_timing="results/replication/stability_map_timing.csv",
    output:
        readme="results/replication/docs/README.md",
        replication="results/replication/docs/REPLICATION.md",
        timings=report(
            "results/replication/docs/timings.md",
            caption="../report/timings.rst",
            category="Speed and accuracy",
            labels={"document": "measured times"},
        ),
        # the verdict's headline, for the report's landing page (workflow/report/workflow.rst)
        landing="results/replication/docs/landing.html",
        # the claims register and REPLICATION.md as HTML documents, items of the report
        verdict=report(
            "results/replication/docs/verdict.html",
            caption="../report/verdict.rst",
            category="Verdict",
            labels={"table": "claims register and stress cases"},
        ),
        replication_html=report(
            "results/replication/docs/replication.html",
            caption="../report/replication.rst",
            category="Verdict",
            labels={"table": "REPLICATION.md"},
        ),
    log:
        "results/logs/replication/render_docs.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        paper=PAPER,  # the values the documents print: an edit of config/paper.yaml renders them again
        texts=outputs.file_digest(DOC_TEXTS.values()),
        code=CODE,
    script:
        "../scripts/render_docs.py"


rule render_article:
    input:
        **ARTICLE_TEXTS,
        claims="results/replication/claims.csv",
        limits="results/replication/panel_limits.csv",
        checks="results/replication/checks.nc",
        readings="results/replication/readings.csv",
        benchmark="results/replication/work_precision.csv",
        fig3=outputs.data_files(
            "replication", "fig3", STUDIES["replication"]["fig3"]
        ).values(),
        figures=[f"results/replication/figures/{name}.svg" for name in ARTICLE_FIGURES],
    output:
        pdf="results/replication/article/article.pdf",
        metadata="results/replication/article/metadata.yaml",
        source="results/replication/article/article.typ",
        bibliography="results/replication/article/article.bib",
        # the figures the source includes, beside it: the folder compiles on its own
        figures=[
            f"results/replication/article/figures/{name}.svg"
            for name in ARTICLE_FIGURES
        ],
    log:
        "results/logs/replication/render_article.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        paper=PAPER,
        texts=outputs.file_digest(ARTICLE_TEXTS.values()),
        code=CODE,
    script:
        "../scripts/render_docs.py"


# The tracked figures and documents (figures/, README.md, REPLICATION.md), copied from results/replication/
# where what they show changed (escapement.pipeline.publish: a figure beyond an RMS tolerance of its pixels,
# its PDF with its PNG, a document where its text or a number at its printed digits differs). Only this
# target writes a tracked file: `snakemake --cores 2 publish`.
rule publish:
    input:
        publish_inputs,
    log:
        "results/logs/replication/publish.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        published=PUBLISHED,
    script:
        "../scripts/publish.py"


# A figure no rule draws (a tracked figure's name such as fig3.png, a misspelt kind): one line naming the figures
# this configuration draws, before any job.
rule unknown_figure:
    input:
        lambda w: refuse(f"results/{w.study}/figures/{w.figure}.{w.ext}"),
    output:
        "results/{study}/figures/{figure}.{ext}",
    log:
        "results/logs/{study}/unknown_figure_{figure}.{ext}.log",
    wildcard_constraints:
        figure=f"(?!(?:{'|'.join(outputs.FIGURE_NAMES)})\\.)[^/.]+",
