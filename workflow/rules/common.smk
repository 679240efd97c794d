from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from escapement.pipeline import config as settings
from escapement.pipeline.publish import PUBLISHED
from escapement.scenes.settings import KINDS


def checked(data, schema, source):
    """Snakemake's validation against the JSON schema, its error in one line naming the key."""
    try:
        validate(data, schema, set_default=False)
    except WorkflowError as err:
        raise WorkflowError(settings.refusal(err.__context__, source)) from None


# Every file read strictly (a key given twice is refused with its line), nested --config values with the
# types a file gives them; then each source against its schema; then every scene built and checked.
try:
    for path in dict.fromkeys([*workflow.configfiles, "config/config.yaml"]):
        settings.read_yaml(path)
    settings.typed_overrides(config, workflow.config_settings.config_args)
    PAPER = settings.read_yaml("config/paper.yaml")
    checked(config, "../schemas/config.schema.yaml", "the configuration")
    checked(PAPER, "../schemas/paper.schema.yaml", "config/paper.yaml")
    NAME = config.get("name", "own")
    STUDIES = {"replication": settings.study_scenes("replication", PAPER)}
    OWN = settings.own_blocks(config, PAPER)
    if len(OWN) > 1:
        STUDIES[NAME] = settings.study_scenes(NAME, OWN)
    RUNS = settings.replication_scenes(PAPER)
except settings.ConfigError as err:
    raise WorkflowError(str(err)) from None


wildcard_constraints:
    study="|".join(STUDIES),


#: the layers of the package each kind of job runs: their sources' digest is a param of its rules, so that an
#: edit reruns the jobs that run the edited code (Snakemake follows a rule's own script only)
LAYERS = {
    "simulate": ["model", "solvers", "integrators", "paper", "studies", "scenes", "io"],
    "plot": ["model", "io", "paper", "plotting"],
    "verdict": [
        "model",
        "solvers",
        "integrators",
        "paper",
        "studies",
        "io",
        "plotting",
    ],
    "docs": ["model", "io", "paper"],
}
CODE = {
    job: settings.code_digest(
        workflow.basedir,
        *(f"src/escapement/{layer}" for layer in layers),
        f"src/escapement/pipeline/{'simulate' if job == 'simulate' else job}.py",
        "src/escapement/pipeline/config.py",
    )
    for job, layers in LAYERS.items()
}


def scenes(block, name=None):
    """The params of the scenes of ``block`` in the job's study, by the file each writes: ``name`` (a pattern
    such as ``case_{}.nc``) for a kind of several scenes, in its folder; the one scene of the others.
    """
    return lambda w: {
        name.format(label) if name else "": settings
        for label, settings in STUDIES[w.study][block].items()
    }


def scene_files(study, block, name):
    """The files of the scenes of ``block`` in ``study``, in its kind's folder, by their labels."""
    return {
        label: f"results/{study}/{KINDS[block].name}/{name.format(label)}"
        for label in STUDIES[study][block]
    }


def files(block, name):
    """:func:`scene_files` of the job's study."""
    return lambda w: scene_files(w.study, block, name)


def study_outputs(study):
    """The figures of one study (each needs its datasets)."""
    return [
        f"results/{study}/figures/{KINDS[block].name}.png" for block in STUDIES[study]
    ]


def all_outputs():
    return [
        *(path for study in STUDIES for path in study_outputs(study)),
        "results/replication/claims.csv",
        "results/replication/stress.csv",
        "results/replication/figures/long_run.png",
        "results/replication/figures/work_precision.png",
        "results/replication/docs/README.md",
    ]


def publish_inputs(wildcards):
    """What publish copies from; refused, before any job, when the configuration holds a study of your own."""
    if len(STUDIES) > 1:
        raise WorkflowError(
            f"publish updates the tracked figures and documents from the replication alone: run it without a "
            f"configuration of your own (this one makes the study '{NAME}' of {', '.join(OWN)})"
        )
    return list(PUBLISHED.values())
