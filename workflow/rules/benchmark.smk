rule run_work_precision:
    input:
        code=code("run_work_precision.py"),
    output:
        csv="results/benchmark/work_precision.csv",
    log:
        "results/logs/run_work_precision.log",
    benchmark:
        "results/benchmarks/run_work_precision.tsv"
    conda:
        "../../environment/environment.yml"
    threads: 1  # an indicative table beside the other jobs; the benchmark target times with the machine to itself
    params:
        scene=scenes.benchmark_scene(config),
        settings=scenes.benchmark_settings(config),
    script:
        "../scripts/run_work_precision.py"


use rule run_work_precision as run_work_precision_full with:
    output:
        csv="results/benchmark/work_precision_full.csv",
    log:
        "results/logs/run_work_precision_full.log",
    benchmark:
        "results/benchmarks/run_work_precision_full.tsv"
    threads: 2  # the machine to itself while it times
    params:
        scene=scenes.benchmark_scene(config),
        settings=scenes.benchmark_settings(config, slow=True),


rule plot_work_precision:
    input:
        csv="results/benchmark/work_precision.csv",
        code=code("plot_work_precision.py"),
    output:
        png=report(
            "results/figures/work_precision.png",
            caption="../report/work_precision.rst",
            category="Speed and accuracy",
            labels={"figure": "work-precision"},
        ),
        pdf="results/figures/work_precision.pdf",
    log:
        "results/logs/plot_work_precision.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        case=config["benchmark"]["case"],
    script:
        "../scripts/plot_work_precision.py"


use rule plot_work_precision as plot_work_precision_full with:
    input:
        csv="results/benchmark/work_precision_full.csv",
        code=code("plot_work_precision.py"),
    output:
        png="results/benchmark/work_precision_full.png",
        pdf="results/benchmark/work_precision_full.pdf",
    log:
        "results/logs/plot_work_precision_full.log",


rule simulate_long_run:
    input:
        code=code("simulate_long_run.py"),
    output:
        nc="results/benchmark/long_run.nc",
        timing="results/benchmark/long_run_timing.csv",
    log:
        "results/logs/simulate_long_run.log",
    benchmark:
        "results/benchmarks/simulate_long_run.tsv"
    priority: 10  # the longest job at the head of a chain (stress table, its figure): started first
    conda:
        "../../environment/environment.yml"
    params:
        scene=scenes.long_run_scene(config),
    script:
        "../scripts/simulate_long_run.py"


rule plot_long_run:
    input:
        nc="results/benchmark/long_run.nc",
        code=code("plot_long_run.py"),
    output:
        png=report(
            "results/figures/long_run.png",
            caption="../report/long_run.rst",
            category="Speed and accuracy",
            labels={"figure": "long run"},
        ),
        pdf="results/figures/long_run.pdf",
    log:
        "results/logs/plot_long_run.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/plot_long_run.py"


rule simulate_escapement_error:
    input:
        code=code("simulate_escapement_error.py"),
    output:
        nc="results/escapement_error/rate.nc",
    log:
        "results/logs/simulate_escapement_error.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        model=scenes.stability_model(config),
        forces=scenes.escapement_error_forces(config),
        zones=config["escapement_error"]["zones"],
    script:
        "../scripts/simulate_escapement_error.py"


rule plot_escapement_error:
    input:
        nc="results/escapement_error/rate.nc",
        code=code("plot_escapement_error.py"),
    output:
        png=report(
            "results/figures/escapement_error.png",
            caption="../report/escapement_error.rst",
            category="Beyond the paper",
            labels={"figure": "escapement error"},
        ),
        pdf="results/figures/escapement_error.pdf",
    log:
        "results/logs/plot_escapement_error.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/plot_escapement_error.py"


rule simulate_stability_chunk:
    input:
        code=code("simulate_stability_chunk.py"),
    output:
        nc="results/stability/chunk_{chunk}.nc",
        timing="results/stability/chunk_{chunk}_timing.csv",
    log:
        "results/logs/simulate_stability_chunk_{chunk}.log",
    benchmark:
        "results/benchmarks/simulate_stability_chunk_{chunk}.tsv"
    wildcard_constraints:
        chunk="[0-9]+",
    conda:
        "../../environment/environment.yml"
    params:
        model=scenes.stability_model(config),
        axes=stability_chunk,
    script:
        "../scripts/simulate_stability_chunk.py"


rule merge_stability:
    input:
        chunks=expand(
            "results/stability/chunk_{chunk}.nc", chunk=scenes.stability_chunks(config)
        ),
        timings=expand(
            "results/stability/chunk_{chunk}_timing.csv",
            chunk=scenes.stability_chunks(config),
        ),
        code=code("merge_stability.py"),
    output:
        nc="results/stability/map.nc",
        timing="results/stability/timing.csv",
    log:
        "results/logs/merge_stability.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/merge_stability.py"


rule plot_stability_map:
    input:
        nc="results/stability/map.nc",
        code=code("plot_stability_map.py"),
    output:
        png=report(
            "results/figures/stability_map.png",
            caption="../report/stability_map.rst",
            category="Speed and accuracy",
            labels={"figure": "stability map"},
        ),
        pdf="results/figures/stability_map.pdf",
    log:
        "results/logs/plot_stability_map.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/plot_stability_map.py"


rule simulate_existence_map:
    input:
        code=code("simulate_existence_map.py"),
    output:
        nc="results/stability/existence.nc",
    log:
        "results/logs/simulate_existence_map.log",
    benchmark:
        "results/benchmarks/simulate_existence_map.tsv"
    conda:
        "../../environment/environment.yml"
    params:
        model=scenes.stability_model(config),
        block=config["existence_map"],
    script:
        "../scripts/simulate_existence_map.py"


rule plot_existence_map:
    input:
        nc="results/stability/existence.nc",
        code=code("plot_existence_map.py"),
    output:
        png=report(
            "results/figures/existence_map.png",
            caption="../report/existence_map.rst",
            category="Beyond the paper",
            labels={"figure": "existence map"},
        ),
        pdf="results/figures/existence_map.pdf",
    log:
        "results/logs/plot_existence_map.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/plot_existence_map.py"


rule run_stress:
    input:
        long_run="results/benchmark/long_run.nc",
        code=code("run_stress.py"),
    output:
        csv=report(
            "results/stress/summary.csv",
            caption="../report/stress.rst",
            category="Speed and accuracy",
            labels={"table": "stress cases"},
        ),
    log:
        "results/logs/run_stress.log",
    benchmark:
        "results/benchmarks/run_stress.tsv"
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/run_stress.py"


rule run_speed:
    input:
        code=code("run_speed.py"),
    output:
        csv="results/benchmark/speed.csv",
        headline="results/benchmark/headline.csv",
    log:
        "results/logs/run_speed.log",
    benchmark:
        "results/benchmarks/run_speed.tsv"
    conda:
        "../../environment/environment.yml"
    threads: 2  # the machine to itself while it times
    params:
        scene=scenes.benchmark_scene(config),
        speed=config["speed"],
    script:
        "../scripts/run_speed.py"


rule benchmark:
    input:
        "results/benchmark/speed.csv",
        "results/benchmark/headline.csv",
        "results/benchmark/work_precision_full.csv",
        "results/benchmark/work_precision_full.png",
        "results/benchmark/work_precision.csv",
        "results/figures/work_precision.png",
        "results/figures/long_run.png",
        "results/figures/stability_map.png",
