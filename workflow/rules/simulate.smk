rule simulate_fig3:
    input:
        code=code("simulate_fig3.py"),
    output:
        nc="results/fig3/case_{case}.nc",
    log:
        "results/logs/simulate_fig3_{case}.log",
    benchmark:
        "results/benchmarks/simulate_fig3_{case}.tsv"
    wildcard_constraints:
        case="[a-z]",
    conda:
        "../../environment/environment.yml"
    params:
        scene=fig3_scene,
    script:
        "../scripts/simulate_fig3.py"


rule simulate_fig4:
    input:
        code=code("simulate_fig4.py"),
    output:
        nc="results/fig4/shock.nc",
    log:
        "results/logs/simulate_fig4.log",
    benchmark:
        "results/benchmarks/simulate_fig4.tsv"
    conda:
        "../../environment/environment.yml"
    params:
        scene=scenes.fig4_scene(config),
    script:
        "../scripts/simulate_fig4.py"


rule simulate_fig5:
    input:
        code=code("simulate_fig5.py"),
    output:
        nc="results/fig5/K_{K}.nc",
    log:
        "results/logs/simulate_fig5_K_{K}.log",
    benchmark:
        "results/benchmarks/simulate_fig5_K_{K}.tsv"
    wildcard_constraints:
        K="[0-9.e+-]+",
    conda:
        "../../environment/environment.yml"
    params:
        scene=fig5_scene,
    script:
        "../scripts/simulate_fig5.py"


rule simulate_checks:
    input:
        code=code("simulate_checks.py"),
    output:
        nc="results/claims/checks.nc",
    log:
        "results/logs/simulate_checks.log",
    benchmark:
        "results/benchmarks/simulate_checks.tsv"
    conda:
        "../../environment/environment.yml"
    params:
        cases=scenes.check_cases(config),
        n_cycles=config["checks"]["n_cycles"],
    script:
        "../scripts/simulate_checks.py"
