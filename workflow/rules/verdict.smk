rule check_claims:
    input:
        register="workflow/claims.yaml",
        fig3=expand("results/fig3/case_{case}.nc", case=config["fig3"]["cases"]),
        fig4="results/fig4/shock.nc",
        fig5=expand("results/fig5/K_{K}.nc", K=fig5_labels()),
        checks="results/claims/checks.nc",
        code=package_code(
            "model", "solvers", "paper", *IO, *PIPELINE, "pipeline/verdict.py"
        ),
    output:
        csv=report(
            "results/claims.csv",
            caption="../report/claims.rst",
            category="Verdict",
            labels={"table": "claims register"},
        ),
    log:
        "results/logs/check_claims.log",
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
        stability="results/stability/map.nc",
        stress="results/stress/summary.csv",
        templates=["workflow/templates/README.md", "workflow/templates/REPLICATION.md"],
        # the documents show the figures: rendered after them, they are never older
        figures=expand(
            "figures/{fig}.png",
            fig=[
                "fig3",
                "fig4",
                "fig5",
                "work_precision",
                "long_run",
                "stability_map",
            ],
        ),
        code=RENDER_CODE,
    output:
        readme="README.md",
        replication="REPLICATION.md",
    log:
        "results/logs/render_docs.log",
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/render_docs.py"
