from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from escapement.pipeline import config as scenes
from escapement.pipeline.code_inputs import code_inputs
from escapement.pipeline.config import ConfigError, check_config
from escapement.pipeline.config_files import apply_config_overrides

# A nested --config value (fig3="{n_cycles: 40}") is read by Snakemake with every scalar as text:
# read again as YAML, it has the types a configuration file would give it. Then the package's
# check, for one clear line naming the key (the schema, the rules a schema cannot state, every
# scene's parameters); then Snakemake's own validation against the schema.
try:
    apply_config_overrides(
        config, workflow.config_settings.config_args, workflow.config_settings.config
    )
    check_config(config, Path(workflow.basedir) / "workflow/schemas/config.schema.yaml")
except ConfigError as err:
    raise WorkflowError(str(err)) from None
validate(config, "../schemas/config.schema.yaml")


def fig3_scene(wildcards):
    """The scene of Fig. 3's case ``{case}``."""
    return scenes.fig3_scene(config, wildcards.case)


def fig5_labels():
    return scenes.fig5_labels(config)


def fig5_scene(wildcards):
    """The scene of Fig. 5's panel ``{K}``."""
    return scenes.fig5_scene(config, wildcards.K)


def stability_chunk(wildcards):
    """The (b, F) values of the stability map's chunk ``{chunk}``."""
    return scenes.stability_chunk(config, wildcards.chunk)


def code(script):
    """The source files that ``script`` (under workflow/scripts/) imports, transitively: the package's
    modules, the benchmarks' and the data files they load (escapement.pipeline.code_inputs reads the
    import statements). Snakemake tracks only the rule's own script: these inputs make an edit of the
    code rerun the jobs that run it, and only those. The paths are relative to the working directory,
    as Snakemake records them: a clone that is moved or copied keeps its outputs up to date.
    """
    return code_inputs(f"workflow/scripts/{script}", base=workflow.basedir)


#: the figures and documents git tracks, each with the file under results/ it is copied from. The
#: work-precision figure is not among them: it is drawn from wall times, which vary from run to run.
PUBLISHED = {
    **{
        f"figures/{fig}.{ext}": f"results/figures/{fig}.{ext}"
        for fig in (
            "fig3",
            "fig4",
            "fig5",
            "long_run",
            "stability_map",
            "escapement_error",
            "existence_map",
        )
        for ext in ("png", "pdf")
    },
    "README.md": "results/docs/README.md",
    "REPLICATION.md": "results/docs/REPLICATION.md",
}


def all_outputs():
    return [
        *expand("results/fig3/case_{case}.nc", case=config["fig3"]["cases"]),
        "results/fig4/shock.nc",
        *expand("results/fig5/K_{K}.nc", K=fig5_labels()),
        "results/claims/checks.nc",
        "results/claims.csv",
        "results/benchmark/work_precision.csv",
        "results/benchmark/long_run.nc",
        "results/stability/map.nc",
        "results/escapement_error/rate.nc",
        "results/stability/existence.nc",
        "results/stress/summary.csv",
        "results/figures/work_precision.png",
        "results/docs/timings.md",
        "results/readings/axis_scores.csv",
        *PUBLISHED,
    ]


onstart:
    # A run killed outright leaves the temporaries of its atomic writes: those of ended writers go.
    from escapement.io.atomic import remove_stale_temporaries

    remove_stale_temporaries(".")
    remove_stale_temporaries("figures")
    remove_stale_temporaries("results", recursive=True)


onerror:
    # A failed job may leave a tracked file restored by Snakemake with a new modification time:
    # dated back, it is published again by the next run.
    from escapement.pipeline.publish import mark_stale

    mark_stale(list(PUBLISHED))
