rule check_claims:
    input:
        register="workflow/claims.yaml",
        fig3=expand("results/fig3/case_{case}.nc", case=config["fig3"]["cases"]),
        fig4="results/fig4/shock.nc",
        fig5=expand("results/fig5/K_{K}.nc", K=fig5_labels()),
        checks="results/claims/checks.nc",
        readings="results/readings/axis_scores.csv",
        code=code("check_claims.py"),
    output:
        csv=report(
            "results/claims.csv",
            caption="../report/claims.rst",
            category="Verdict",
            labels={"table": "claims register"},
        ),
    log:
        "results/logs/check_claims.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        fig3_labels=list(config["fig3"]["cases"]),
        fig5_labels=fig5_labels(),
    script:
        "../scripts/check_claims.py"


rule render_docs:
    input:
        claims="results/claims.csv",
        benchmark="results/benchmark/work_precision.csv",
        long_run="results/benchmark/long_run.nc",
        long_run_timing="results/benchmark/long_run_timing.csv",
        stability="results/stability/map.nc",
        stability_timing="results/stability/timing.csv",
        stress="results/stress/summary.csv",
        readings="results/readings/axis_scores.csv",
        templates=["workflow/templates/README.md", "workflow/templates/REPLICATION.md"],
        timings_template="workflow/templates/timings.md",
        code=code("render_docs.py"),
    output:
        readme="results/docs/README.md",
        replication="results/docs/REPLICATION.md",
        timings=report(
            "results/docs/timings.md",
            caption="../report/timings.rst",
            category="Speed and accuracy",
            labels={"document": "measured times"},
        ),
        # the verdict as HTML tables, shown on the report's landing page (workflow/report/workflow.rst)
        verdict="results/docs/verdict.html",
        # REPLICATION.md as HTML, shown on the landing page too
        replication_html="results/docs/replication.html",
    log:
        "results/logs/render_docs.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/render_docs.py"


# The tracked figures and documents, copied from results/ where what they show changed: a figure
# beyond an RMS tolerance of its pixels (its PDF with its PNG), a document where its text or a number
# at its printed digits differs (escapement.pipeline.publish, which logs each comparison). Flagged
# update(): Snakemake does not delete them before the job, and restores them if it fails.
rule publish:
    input:
        published=list(PUBLISHED.values()),
        code=code("publish.py"),
    output:
        tracked=[update(path) for path in PUBLISHED],
    log:
        "results/logs/publish.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/publish.py"


# The paper's unstated choices read from its printed axes: every candidate reading simulated and
# autoscaled to the printed tick steps, scored by the printed limits it reproduces.
rule score_readings:
    input:
        code=code("score_readings.py"),
    output:
        csv=report(
            "results/readings/axis_scores.csv",
            caption="../report/readings.rst",
            category="Verdict",
            labels={"table": "axis readings"},
        ),
    log:
        "results/logs/score_readings.log",
    conda:
        "../../environment/environment.yml"
    params:
        settings={
            "model": config["model"],
            "fig3": config["fig3"],
            "fig4": {
                k: config["fig4"][k]
                for k in (
                    "velocity_window",
                    "acceleration_window",
                    "samples_per_second",
                )
            },
            "fig5": {
                k: config["fig5"][k] for k in ("K", "n_cycles", "samples_per_period")
            },
        },
    script:
        "../scripts/score_readings.py"
