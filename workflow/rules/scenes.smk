# The scenes of every study: the replication's (config/paper.yaml) and the user's own (config/config.yaml),
# {study} naming which; each job writes one dataset (or one figure) from its scene's settings.


rule poincare_map:
    output:
        nc="results/{study}/poincare_map/case_{case}.nc",
    log:
        "results/logs/{study}/poincare_map_{case}.log",
    wildcard_constraints:
        case="[a-z]",
    params:
        kind="poincare_map",
        scene=scene("fig3", "case"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule shock_detail:
    output:
        nc="results/{study}/shock_detail.nc",
    log:
        "results/logs/{study}/shock_detail.log",
    params:
        kind="shock_detail",
        scene=scene("fig4"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule phase_diagram:
    output:
        nc="results/{study}/phase_diagrams/K_{K}.nc",
    log:
        "results/logs/{study}/phase_diagram_K_{K}.log",
    wildcard_constraints:
        K="[0-9.e+-]+",
    params:
        kind="phase_diagram",
        scene=scene("fig5", "K"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule escapement_error:
    output:
        nc="results/{study}/escapement_error.nc",
    log:
        "results/logs/{study}/escapement_error.log",
    params:
        kind="escapement_error",
        scene=scene("escapement_error"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule existence_map:
    output:
        nc="results/{study}/existence_map.nc",
    log:
        "results/logs/{study}/existence_map.log",
    params:
        kind="existence_map",
        scene=scene("existence_map"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule stability_chunk:
    output:
        nc="results/{study}/stability_map/chunk_{chunk}.nc",
        timing="results/{study}/stability_map/chunk_{chunk}_timing.csv",
    log:
        "results/logs/{study}/stability_chunk_{chunk}.log",
    wildcard_constraints:
        chunk="[0-9]+",
    params:
        kind="stability_chunk",
        scene=scene("stability_map", "chunk"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule stability_map:
    input:
        chunks=lambda w: expand(
            "results/{study}/stability_map/chunk_{chunk}.nc",
            study=w.study,
            chunk=STUDIES[w.study]["stability_map"],
        ),
    output:
        nc="results/{study}/stability_map.nc",
        timing="results/{study}/stability_map_timing.csv",
    log:
        "results/logs/{study}/stability_map.log",
    localrule: True
    params:
        code=CODE["simulate"],
    script:
        "../scripts/merge_stability.py"


# --- the figures: one rule a kind, titled by the study


rule plot_poincare_map:
    input:
        nc=lambda w: expand(
            "results/{study}/poincare_map/case_{case}.nc",
            study=w.study,
            case=STUDIES[w.study]["fig3"],
        ),
    output:
        png=report(
            "results/{study}/figures/poincare_map.png",
            caption="../report/poincare_map.rst",
            category="{study}",
            labels={"figure": "Poincare map"},
        ),
        pdf="results/{study}/figures/poincare_map.pdf",
    log:
        "results/logs/{study}/plot_poincare_map.log",
    localrule: True
    params:
        labels=lambda w: list(STUDIES[w.study]["fig3"]),
        code=CODE["plot"],
    script:
        "../scripts/plot.py"


rule plot_shock_detail:
    input:
        nc="results/{study}/shock_detail.nc",
    output:
        png=report(
            "results/{study}/figures/shock_detail.png",
            caption="../report/shock_detail.rst",
            category="{study}",
            labels={"figure": "shock detail"},
        ),
        pdf="results/{study}/figures/shock_detail.pdf",
    log:
        "results/logs/{study}/plot_shock_detail.log",
    localrule: True
    params:
        labels=[""],
        code=CODE["plot"],
    script:
        "../scripts/plot.py"


rule plot_phase_diagrams:
    input:
        nc=lambda w: expand(
            "results/{study}/phase_diagrams/K_{K}.nc",
            study=w.study,
            K=STUDIES[w.study]["fig5"],
        ),
    output:
        png=report(
            "results/{study}/figures/phase_diagrams.png",
            caption="../report/phase_diagrams.rst",
            category="{study}",
            labels={"figure": "phase diagrams"},
        ),
        pdf="results/{study}/figures/phase_diagrams.pdf",
    log:
        "results/logs/{study}/plot_phase_diagrams.log",
    localrule: True
    params:
        labels=lambda w: list(STUDIES[w.study]["fig5"]),
        code=CODE["plot"],
    script:
        "../scripts/plot.py"


use rule plot_shock_detail as plot_escapement_error with:
    input:
        nc="results/{study}/escapement_error.nc",
    output:
        png=report(
            "results/{study}/figures/escapement_error.png",
            caption="../report/escapement_error.rst",
            category="{study}",
            labels={"figure": "escapement error"},
        ),
        pdf="results/{study}/figures/escapement_error.pdf",
    log:
        "results/logs/{study}/plot_escapement_error.log",


use rule plot_shock_detail as plot_stability_map with:
    input:
        nc="results/{study}/stability_map.nc",
    output:
        png=report(
            "results/{study}/figures/stability_map.png",
            caption="../report/stability_map.rst",
            category="{study}",
            labels={"figure": "stability map"},
        ),
        pdf="results/{study}/figures/stability_map.pdf",
    log:
        "results/logs/{study}/plot_stability_map.log",


use rule plot_shock_detail as plot_existence_map with:
    input:
        nc="results/{study}/existence_map.nc",
    output:
        png=report(
            "results/{study}/figures/existence_map.png",
            caption="../report/existence_map.rst",
            category="{study}",
            labels={"figure": "existence map"},
        ),
        pdf="results/{study}/figures/existence_map.pdf",
    log:
        "results/logs/{study}/plot_existence_map.log",
