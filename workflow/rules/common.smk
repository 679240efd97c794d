import sys
from pathlib import Path

from snakemake.common.configfile import load_configfile

from escapement.pipeline import config as settings
from escapement.pipeline import plan
from escapement.pipeline import outputs
from escapement.pipeline.publish import PUBLISHED
from escapement.pipeline.outputs import ARTICLE_FIGURES
from escapement.scenes.settings import KINDS

# The configuration: the replication (config/paper.yaml), the user's own (config/config.yaml), then Snakemake's
# --configfile and --config laid over them; checked once against the schema, then every scene built and checked by
# the model's rules before any job (escapement.pipeline.config, .plan). A refusal is one line on the console: a
# SystemExit's message (Snakemake prints a WorkflowError with a traceback).
try:
    settings.refuse_aliases("config/config.yaml")
except settings.ConfigError as err:
    sys.exit(str(err))


configfile: "config/paper.yaml"
configfile: "config/config.yaml"


PAPER = load_configfile("config/paper.yaml")
SCHEMA = Path(workflow.basedir, "workflow/schemas/config.schema.yaml")
try:
    settings.typed_config(config, workflow.config_settings.config_args)
    settings.validated(PAPER, SCHEMA, "config/paper.yaml")
    settings.validated(config, SCHEMA, "the configuration")
    STUDIES, notes = plan.plan(config, PAPER)
    RUNS = plan.replication_scenes(PAPER)
except settings.ConfigError as err:
    sys.exit(str(err))
for note in notes:  # what the user's study changed, and each kind it does not reach
    print(note, file=sys.stderr)
NAME = config.get("name", "own")
OWN = list(STUDIES.get(NAME, {}))


wildcard_constraints:
    study="[^/]+",
    label="[^/]+",


#: the digest of the code every job runs (the package, the scripts, the dependencies' versions): a param of every
#: rule, so that any edit reruns every job (escapement.pipeline.outputs)
CODE = outputs.code_digest(workflow.basedir)


def refuse(path):
    """Stop before any job with one line: ``path`` is not made by this configuration (Snakemake prints a
    WorkflowError raised here with its traceback; a SystemExit's message alone)."""
    sys.exit(outputs.not_a_target(path, STUDIES))


def planned(block, path, part):
    """The ``part`` of the planned scene of ``block`` that writes ``path`` (its label a wildcard, for the kinds of
    several scenes): its ``settings`` (which Snakemake compares to rerun the job) or its ``checked`` settings object
    (which the job runs); one line if the study or its scene does not exist."""

    def params(w):
        labelled = STUDIES.get(w.study, {}).get(block, {})
        label = w.get("label", "")
        if label not in labelled:
            refuse(path.format(**w))
        return getattr(labelled[label], part)

    return params


def kind_files(block, labelled=False):
    """The data files of the kind ``block`` in the job's study (its figure's inputs), or with ``labelled`` by their
    labels (its params); one line if the study has no such kind."""

    def files(w):
        if block not in STUDIES.get(w.study, {}):
            refuse(f"results/{w.study}/figures/{KINDS[block].name}.png")
        found = outputs.data_files(w.study, block, STUDIES[w.study][block])
        return found if labelled else list(found.values())

    return files


def all_outputs():
    return outputs.targets(STUDIES)


def publish_inputs(wildcards):
    """What publish copies from; refused, before any job, when the configuration holds a study of your own."""
    if len(STUDIES) > 1:
        sys.exit(
            f"publish updates the tracked figures and documents from the replication alone: run it without a "
            f"configuration of your own (this one makes the study '{NAME}' of {', '.join(OWN)})"
        )
    return list(PUBLISHED.values())


def map_chunk(block):
    """The checked settings of the chunk of the map ``block`` the job makes (its study and chunk wildcards); one line
    if the study has no such map or chunk."""

    def params(w):
        found = STUDIES.get(w.study, {}).get(block, {}).get("")
        if found is None or int(w.chunk) >= found.chunks:
            refuse(f"results/{w.study}/{KINDS[block].name}/chunk_{w.chunk}.nc")
        return found.chunk(int(w.chunk))

    return params


def map_chunks(block, pattern):
    """The files ``pattern`` of every chunk of the map ``block`` in the job's study, in order."""

    def files(w):
        found = STUDIES.get(w.study, {}).get(block, {}).get("")
        if found is None:
            refuse(f"results/{w.study}/{KINDS[block].name}.nc")
        return [pattern.format(study=w.study, chunk=i) for i in range(found.chunks)]

    return files


onsuccess:
    # a study folder holds only what its configuration makes: after a run that ended well, the datasets and figures
    # an earlier configuration of the same study made and this one does not (escapement.pipeline.outputs)
    for study, scenes in STUDIES.items():
        for path in outputs.stale_files(study, scenes):
            path.unlink()
            print(
                f"removed {path}: the study '{study}' no longer makes it",
                file=sys.stderr,
            )
