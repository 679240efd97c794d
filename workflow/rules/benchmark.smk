# Speed against accuracy: the work-precision table (an indicative one in every run, the full one and the
# speed table with `snakemake --cores 2 benchmark`), and the long run's figure.


rule work_precision:
    output:
        csv="results/replication/work_precision.csv",
    log:
        "results/logs/replication/work_precision.log",
    priority: 10  # one of the two longest jobs (with the long run): started first, on the other core
    conda:
        "../../environment/environment.yml"
    threads: 1  # an indicative table beside the other jobs; the benchmark target times with the machine to itself
    params:
        scene=RUNS["benchmark"],
        settings=PAPER["benchmark"]["settings"],
        code=CODE,
    script:
        "../scripts/work_precision.py"


use rule work_precision as work_precision_full with:
    output:
        csv="results/replication/benchmark/work_precision_full.csv",
    log:
        "results/logs/replication/work_precision_full.log",
    threads: 2  # the machine to itself while it times
    params:
        scene=RUNS["benchmark"],
        settings={
            method: sorted(
                {*PAPER["benchmark"]["settings"].get(method, []), *values},
                reverse=True,
            )
            for method, values in {
                **PAPER["benchmark"]["settings"],
                **PAPER["benchmark"]["slow_settings"],
            }.items()
        },
        code=CODE,


rule plot_work_precision:
    input:
        csv="results/replication/work_precision.csv",
    output:
        png=report(
            "results/replication/figures/work_precision.png",
            caption="../report/work_precision.rst",
            category="Speed and accuracy",
            labels={"figure": "work-precision"},
        ),
        pdf="results/replication/figures/work_precision.pdf",
        svg="results/replication/figures/work_precision.svg",
    log:
        "results/logs/replication/plot_work_precision.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        code=CODE,
    script:
        "../scripts/plot.py"


use rule plot_work_precision as plot_work_precision_full with:
    input:
        csv="results/replication/benchmark/work_precision_full.csv",
    output:
        png="results/replication/benchmark/work_precision_full.png",
        pdf="results/replication/benchmark/work_precision_full.pdf",
        svg="results/replication/benchmark/work_precision_full.svg",
    log:
        "results/logs/replication/plot_work_precision_full.log",
    localrule: True
    params:
        figure="work_precision",  # the figure's name, which its file's name is not
        code=CODE,


rule plot_long_run:
    input:
        nc="results/replication/long_run.nc",
    output:
        png=report(
            "results/replication/figures/long_run.png",
            caption="../report/long_run.rst",
            category="Speed and accuracy",
            labels={"figure": "long run"},
        ),
        pdf="results/replication/figures/long_run.pdf",
        svg="results/replication/figures/long_run.svg",
    log:
        "results/logs/replication/plot_long_run.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        code=CODE,
    script:
        "../scripts/plot.py"


rule speed:
    output:
        csv="results/replication/benchmark/speed.csv",
        headline="results/replication/benchmark/headline.csv",
    log:
        "results/logs/replication/speed.log",
    conda:
        "../../environment/environment.yml"
    threads: 2  # the machine to itself while it times
    params:
        scene=RUNS["benchmark"],
        speed=PAPER["speed"],
        code=CODE,
    script:
        "../scripts/speed.py"


rule benchmark:
    input:
        "results/replication/benchmark/speed.csv",
        "results/replication/benchmark/headline.csv",
        "results/replication/benchmark/work_precision_full.csv",
        "results/replication/benchmark/work_precision_full.png",
