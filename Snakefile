# Replication of Mao, Fu & Li (2013), "Dynamics of periodic impulsive collision in escapement
# mechanism", Shock and Vibration 20, 1001-1010, doi:10.3233/SAV-130800.
from snakemake.utils import min_version

min_version("8.0")


# The replication's scenes are config/paper.yaml, your own config/config.yaml (with --configfile and --config laid
# over it): both read by workflow/rules/common.smk's configfile directives, and checked there before any job.


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/scenes.smk"
include: "workflow/rules/replication.smk"
include: "workflow/rules/benchmark.smk"


rule all:
    default_target: True
    input:
        all_outputs(),
