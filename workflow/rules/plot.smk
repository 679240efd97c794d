rule plot_fig3:
    input:
        nc=expand("results/fig3/case_{case}.nc", case=config["fig3"]["cases"]),
        scores="results/readings/axis_scores.csv",
        code=code("plot_fig3.py"),
    output:
        png=report(
            "results/figures/fig3.png",
            caption="../report/fig3.rst",
            category="Figures",
            labels={"figure": "Fig. 3", "content": "Poincare map"},
        ),
        pdf="results/figures/fig3.pdf",
    log:
        "results/logs/plot_fig3.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        labels=list(config["fig3"]["cases"]),
    script:
        "../scripts/plot_fig3.py"


rule plot_fig4:
    input:
        nc="results/fig4/shock.nc",
        scores="results/readings/axis_scores.csv",
        code=code("plot_fig4.py"),
    output:
        png=report(
            "results/figures/fig4.png",
            caption="../report/fig4.rst",
            category="Figures",
            labels={"figure": "Fig. 4", "content": "shock detail"},
        ),
        pdf="results/figures/fig4.pdf",
    log:
        "results/logs/plot_fig4.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    script:
        "../scripts/plot_fig4.py"


rule plot_fig5:
    input:
        nc=expand("results/fig5/K_{K}.nc", K=fig5_labels()),
        scores="results/readings/axis_scores.csv",
        code=code("plot_fig5.py"),
    output:
        png=report(
            "results/figures/fig5.png",
            caption="../report/fig5.rst",
            category="Figures",
            labels={"figure": "Fig. 5", "content": "phase diagrams"},
        ),
        pdf="results/figures/fig5.pdf",
    log:
        "results/logs/plot_fig5.log",
    localrule: True
    conda:
        "../../environment/environment.yml"
    params:
        labels=fig5_labels(),
    script:
        "../scripts/plot_fig5.py"
