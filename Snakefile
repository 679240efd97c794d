# Replication of Mao, Fu & Li (2013), "Dynamics of periodic impulsive collision in escapement
# mechanism", Shock and Vibration 20, 1001-1010, doi:10.3233/SAV-130800.
from snakemake.exceptions import WorkflowError
from snakemake.utils import min_version

from escapement.pipeline.config_files import ConfigError, check_config_files

min_version("8.0")

# Snakemake's loader names neither the line of a YAML error nor a key given twice: every
# configuration file, each given with --configfile (workflow.configfiles, which Snakemake has read
# already) and the default one, is read again strictly, before any of them is used.
try:
    check_config_files([*workflow.configfiles, "config/config.yaml"])
except ConfigError as err:
    raise WorkflowError(str(err)) from None


configfile: "config/config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/plot.smk"
include: "workflow/rules/verdict.smk"
include: "workflow/rules/benchmark.smk"


rule all:
    default_target: True
    input:
        all_outputs(),
