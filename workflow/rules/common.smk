import os
from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from escapement.pipeline import config as scenes
from escapement.pipeline.config import ConfigError, check_config

# The package's check first, for one clear line naming the key (the schema, the rules a schema
# cannot state, every scene's parameters); then Snakemake's own validation against the schema.
try:
    check_config(config, Path(workflow.basedir) / "workflow/schemas/config.schema.yaml")
except ConfigError as err:
    raise WorkflowError(str(err)) from None
validate(config, "../schemas/config.schema.yaml")


def fig3_scene(case):
    return scenes.fig3_scene(config, case)


def fig5_labels():
    return scenes.fig5_labels(config)


def fig5_scene(label):
    return scenes.fig5_scene(config, label)


def stability_chunk(chunk):
    return scenes.stability_chunk(config, chunk)


def package_code(*parts):
    """Source files of the package that a rule's script imports: the top-level ``__init__.py`` and
    ``_lazy.py`` (which every import runs) and the named parts, each a subpackage (``"model"``) or a module
    (``"io/netcdf.py"``); with no parts, every file. Snakemake tracks only the rule's own script:
    these inputs make an edit of the code rerun the jobs that import it, and only those. The paths are
    relative to the working directory, as Snakemake records them: a clone that is moved or copied
    keeps its outputs up to date.
    """
    src = Path(workflow.basedir) / "src" / "escapement"
    if not parts:
        files = list(src.rglob("*"))
    else:
        files = [src / "__init__.py", src / "_lazy.py"]  # every import runs these
        for part in parts:
            path = src / part
            if not path.exists():
                raise WorkflowError(f"package_code: {path} does not exist")
            files += list(path.rglob("*")) if path.is_dir() else [path]
    return sorted(
        {os.path.relpath(p) for p in files if p.suffix in (".py", ".mplstyle")}
    )


# What each kind of job imports (read the imports of the pipeline module its script calls,
# and of the layers below it). io: the files without solvers (dataset.py and scenes.py run them).
IO = ("io/__init__.py", "io/atomic.py", "io/netcdf.py", "io/provenance.py")
PIPELINE = ("pipeline/__init__.py", "pipeline/logs.py", "pipeline/tables.py")
#: pipeline/simulate.py: io.scenes, so every layer below plotting
SIMULATE_CODE = package_code(
    "model",
    "solvers",
    "paper",
    "studies",
    "io",
    "pipeline/__init__.py",
    "pipeline/logs.py",
    "pipeline/tables.py",
    "pipeline/simulate.py",
)
#: pipeline/studies.py: the benchmark and the stress cases
STUDIES_CODE = package_code(
    "model",
    "solvers",
    "paper",
    "studies",
    *IO,
    *PIPELINE,
    "pipeline/config.py",
    "pipeline/edge_cases.py",
    "pipeline/studies.py",
)
#: pipeline/tables.py: netCDF files only
MERGE_CODE = package_code(*IO, *PIPELINE)
#: pipeline/plot.py: netCDF files, the figures and the quantities' labels; no solver
PLOT_CODE = package_code("model", "plotting", *IO, *PIPELINE, "pipeline/plot.py")
#: pipeline/render.py: the claims table (pipeline/verdict.py), the facts and the templates
RENDER_CODE = package_code(
    "model",
    "solvers",
    "paper",
    *IO,
    *PIPELINE,
    "pipeline/claims_csv.py",
    "pipeline/docs.py",
    "pipeline/facts.py",
    "pipeline/render.py",
    "pipeline/scores.py",
)


#: pipeline/publish.py: files only
PUBLISH_CODE = package_code(
    *IO, "pipeline/__init__.py", "pipeline/logs.py", "pipeline/publish.py"
)

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
