# The scenes of every study: the replication's (config/paper.yaml) and the user's own (config/config.yaml),
# {study} naming which. Each job writes the dataset of one scene (a kind of several scenes, such as Fig. 3's
# cases, one file per scene in the kind's folder, {label} naming it) and each plotting job the figure of one kind.
# Every file is a target of the default run, so a missing one is made again.


rule poincare_map:
    output:
        nc="results/{study}/poincare_map/case_{label}.nc",
    log:
        "results/logs/{study}/poincare_map/case_{label}.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="poincare_map",
        settings=planned(
            "fig3", "results/{study}/poincare_map/case_{label}.nc", "settings"
        ),
        scene=planned("fig3", "results/{study}/poincare_map/case_{label}.nc", "checked"),
        code=CODE,
    script:
        "../scripts/simulate.py"


rule shock_detail:
    output:
        nc="results/{study}/shock_detail.nc",
    log:
        "results/logs/{study}/shock_detail.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="shock_detail",
        settings=planned("fig4", "results/{study}/shock_detail.nc", "settings"),
        scene=planned("fig4", "results/{study}/shock_detail.nc", "checked"),
        code=CODE,
    script:
        "../scripts/simulate.py"


rule phase_diagrams:
    output:
        nc="results/{study}/phase_diagrams/K_{label}.nc",
    log:
        "results/logs/{study}/phase_diagrams/K_{label}.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="phase_diagram",
        settings=planned(
            "fig5", "results/{study}/phase_diagrams/K_{label}.nc", "settings"
        ),
        scene=planned("fig5", "results/{study}/phase_diagrams/K_{label}.nc", "checked"),
        code=CODE,
    script:
        "../scripts/simulate.py"


rule escapement_error:
    output:
        nc="results/{study}/escapement_error.nc",
    log:
        "results/logs/{study}/escapement_error.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="escapement_error",
        settings=planned(
            "escapement_error", "results/{study}/escapement_error.nc", "settings"
        ),
        scene=planned(
            "escapement_error", "results/{study}/escapement_error.nc", "checked"
        ),
        code=CODE,
    script:
        "../scripts/simulate.py"


# A map runs in the chunks its planning gave it (escapement.pipeline.plan.chunks: the fewest slices of its rows that
# keep each job within its memory budget; one for the replication's maps), each chunk a job of its own, and the map's
# rule joins their files into the map's one dataset.

#: the memory a chunk job asks for (MB): its ensemble, planned within the 2 GB budget, and the interpreter (a chunk of
#: 1.92 GB by the ensemble's estimate peaked at 1.65 GB, one of 1.46 GB at 1.0 GB)
MAP_CHUNK_MB = 2500


rule existence_map_chunk:
    output:
        nc=temp("results/{study}/existence_map/chunk_{chunk}.nc"),
    log:
        "results/logs/{study}/existence_map/chunk_{chunk}.log",
    wildcard_constraints:
        chunk=r"\d+",
    conda:
        "../../environment/environment.yml"
    resources:
        mem_mb=MAP_CHUNK_MB,
    params:
        kind="existence_map",
        settings=planned(
            "existence_map", "results/{study}/existence_map.nc", "settings"
        ),
        chunks=planned("existence_map", "results/{study}/existence_map.nc", "chunks"),
        scene=map_chunk("existence_map"),
        code=CODE,
    script:
        "../scripts/simulate.py"


rule existence_map:
    input:
        parts=map_chunks(
            "existence_map", "results/{study}/existence_map/chunk_{chunk}.nc"
        ),
    output:
        nc="results/{study}/existence_map.nc",
    log:
        "results/logs/{study}/existence_map.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="existence_map",
        code=CODE,
    script:
        "../scripts/simulate.py"


use rule existence_map_chunk as stability_map_chunk with:
    output:
        nc=temp("results/{study}/stability_map/chunk_{chunk}.nc"),
        timing=temp("results/{study}/stability_map/chunk_{chunk}_timing.csv"),
    log:
        "results/logs/{study}/stability_map/chunk_{chunk}.log",
    params:
        kind="stability_map",
        settings=planned(
            "stability_map", "results/{study}/stability_map.nc", "settings"
        ),
        chunks=planned("stability_map", "results/{study}/stability_map.nc", "chunks"),
        scene=map_chunk("stability_map"),
        code=CODE,


rule stability_map:
    input:
        parts=map_chunks(
            "stability_map", "results/{study}/stability_map/chunk_{chunk}.nc"
        ),
        timings=map_chunks(
            "stability_map", "results/{study}/stability_map/chunk_{chunk}_timing.csv"
        ),
    output:
        nc="results/{study}/stability_map.nc",
        timing="results/{study}/stability_map_timing.csv",
    log:
        "results/logs/{study}/stability_map.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="stability_map",
        code=CODE,
    script:
        "../scripts/simulate.py"


# --- the figures: one rule a kind, titled by the study


rule plot_poincare_map:
    input:
        kind_files("fig3"),
    output:
        png=report(
            "results/{study}/figures/poincare_map.png",
            caption="../report/poincare_map.rst",
            category="{study}",
            labels={"figure": "Poincare map"},
        ),
        pdf="results/{study}/figures/poincare_map.pdf",
        svg="results/{study}/figures/poincare_map.svg",
    log:
        "results/logs/{study}/plot_poincare_map.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        files=kind_files("fig3", labelled=True),
        code=CODE,
    script:
        "../scripts/plot.py"


use rule plot_poincare_map as plot_phase_diagrams with:
    input:
        kind_files("fig5"),
    output:
        png=report(
            "results/{study}/figures/phase_diagrams.png",
            caption="../report/phase_diagrams.rst",
            category="{study}",
            labels={"figure": "phase diagrams"},
        ),
        pdf="results/{study}/figures/phase_diagrams.pdf",
        svg="results/{study}/figures/phase_diagrams.svg",
    log:
        "results/logs/{study}/plot_phase_diagrams.log",
    localrule: True
    params:
        files=kind_files("fig5", labelled=True),
        code=CODE,


rule plot_shock_detail:
    input:
        kind_files("fig4"),
    output:
        png=report(
            "results/{study}/figures/shock_detail.png",
            caption="../report/shock_detail.rst",
            category="{study}",
            labels={"figure": "shock detail"},
        ),
        pdf="results/{study}/figures/shock_detail.pdf",
        svg="results/{study}/figures/shock_detail.svg",
    log:
        "results/logs/{study}/plot_shock_detail.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        code=CODE,
    script:
        "../scripts/plot.py"


use rule plot_shock_detail as plot_escapement_error with:
    input:
        kind_files("escapement_error"),
    output:
        png=report(
            "results/{study}/figures/escapement_error.png",
            caption="../report/escapement_error.rst",
            category="{study}",
            labels={"figure": "escapement error"},
        ),
        pdf="results/{study}/figures/escapement_error.pdf",
        svg="results/{study}/figures/escapement_error.svg",
    log:
        "results/logs/{study}/plot_escapement_error.log",
    localrule: True


use rule plot_shock_detail as plot_stability_map with:
    input:
        kind_files("stability_map"),
    output:
        png=report(
            "results/{study}/figures/stability_map.png",
            caption="../report/stability_map.rst",
            category="{study}",
            labels={"figure": "stability map"},
        ),
        pdf="results/{study}/figures/stability_map.pdf",
        svg="results/{study}/figures/stability_map.svg",
    log:
        "results/logs/{study}/plot_stability_map.log",
    localrule: True


use rule plot_shock_detail as plot_existence_map with:
    input:
        kind_files("existence_map"),
    output:
        png=report(
            "results/{study}/figures/existence_map.png",
            caption="../report/existence_map.rst",
            category="{study}",
            labels={"figure": "existence map"},
        ),
        pdf="results/{study}/figures/existence_map.pdf",
        svg="results/{study}/figures/existence_map.svg",
    log:
        "results/logs/{study}/plot_existence_map.log",
    localrule: True
