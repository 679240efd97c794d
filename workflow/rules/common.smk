import sys
from pathlib import Path

from escapement.pipeline import config as settings
from escapement.pipeline import outputs
from escapement.pipeline.publish import PUBLISHED
from escapement.pipeline.outputs import ARTICLE_FIGURES
from escapement.scenes.settings import KINDS


def checked(data, schema, source):
    """``data`` against the JSON schema ``schema`` of workflow/schemas by Snakemake's validate, its first violation
    in one line naming the key (an unknown key with the closest valid one)."""
    settings.validated(
        data, Path(workflow.basedir, "workflow", "schemas", schema), source
    )


# A refusal is one line on the console, before any job: a SystemExit's message (Snakemake prints a WorkflowError
# with the Snakefile's line and a traceback). The user's sources (config/config.yaml unless
# --replace-workflow-config, then --configfile and --config) read again by the project's one reader: bounded in
# size, depth and items, no anchors or aliases, a key given twice refused, numbers the same from a file and from
# --config; then each source against its schema; then every scene built and checked.
try:
    replaced = (
        workflow.config_settings.replace_workflow_config
        and workflow.config_settings.overwrite_config
    )
    own = settings.user_config(
        [
            *([] if replaced else ["config/config.yaml"]),
            *workflow.config_settings.configfiles,
        ],
        workflow.config_settings.config_args,
    )
    config.clear()  # every source as the project reads it, in place of Snakemake's reading
    config.update(own)
    PAPER = settings.read_yaml("config/paper.yaml")
    checked(config, "config.schema.yaml", "the configuration")
    checked(PAPER, "paper.schema.yaml", "config/paper.yaml")
    settings.check_model(PAPER["model"], "config/paper.yaml")
    settings.check_model(
        {**PAPER["model"], **config.get("model", {})}, "the configuration"
    )
    NAME = config.get("name", "own")
    STUDIES = {"replication": settings.study_scenes("replication", PAPER)}
    OWN = settings.own_blocks(config, PAPER)
    # each kind the user's changes do not reach, and why
    for note in settings.study_notes(config, PAPER):
        print(note, file=sys.stderr)
    # the paper's bounds hold on the study, the user's cases and zones joined to the paper's
    if len(OWN) > 1:
        checked(
            settings.laid_over(config, PAPER),
            "paper.schema.yaml",
            f"your study '{NAME}'",
        )
        STUDIES[NAME] = settings.study_scenes(NAME, OWN)
    RUNS = settings.replication_scenes(PAPER)
except settings.ConfigError as err:
    sys.exit(str(err))


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


def settings_of(block, path):
    """The settings of the scene of ``block`` that writes ``path`` (its label a wildcard, for the kinds of several
    scenes), as the rule's params; one line if the study or its scene does not exist."""

    def params(w):
        labelled = STUDIES.get(w.study, {}).get(block, {})
        label = w.get("label", "")
        if label not in labelled:
            refuse(path.format(**w))
        return labelled[label]

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
