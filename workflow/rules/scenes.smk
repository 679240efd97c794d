# The scenes of every study: the replication's (config/paper.yaml) and the user's own (config/config.yaml),
# {study} naming which. Each job writes the datasets of one kind of scene (a kind of several scenes, such as
# Fig. 3's cases, into its folder, one file per scene) and each plotting job the figure of one kind.


rule poincare_map:
    output:
        folder=directory("results/{study}/poincare_map"),
    log:
        "results/logs/{study}/poincare_map.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="poincare_map",
        scenes=scenes("fig3", "case_{}.nc"),
        code=CODE["simulate"],
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
        scenes=scenes("fig4"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule phase_diagrams:
    output:
        folder=directory("results/{study}/phase_diagrams"),
    log:
        "results/logs/{study}/phase_diagrams.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="phase_diagram",
        scenes=scenes("fig5", "K_{}.nc"),
        code=CODE["simulate"],
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
        scenes=scenes("escapement_error"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule existence_map:
    output:
        nc="results/{study}/existence_map.nc",
    log:
        "results/logs/{study}/existence_map.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="existence_map",
        scenes=scenes("existence_map"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


rule stability_map:
    output:
        nc="results/{study}/stability_map.nc",
        timing="results/{study}/stability_map_timing.csv",
    log:
        "results/logs/{study}/stability_map.log",
    conda:
        "../../environment/environment.yml"
    params:
        kind="stability_map",
        scenes=scenes("stability_map"),
        code=CODE["simulate"],
    script:
        "../scripts/simulate.py"


# --- the figures: one rule a kind, titled by the study


rule plot_poincare_map:
    input:
        folder="results/{study}/poincare_map",
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
    conda:
        "../../environment/environment.yml"
    params:
        files=files("fig3", "case_{}.nc"),
        code=CODE["plot"],
    script:
        "../scripts/plot.py"


use rule plot_poincare_map as plot_phase_diagrams with:
    input:
        folder="results/{study}/phase_diagrams",
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
        files=files("fig5", "K_{}.nc"),
        code=CODE["plot"],


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
    conda:
        "../../environment/environment.yml"
    params:
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
    localrule: True


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
    localrule: True


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
    localrule: True
