from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from escapement.pipeline.config import config_error
from escapement.model.parameters import ParameterError
from escapement.pipeline.scene_config import MODEL_KEYS, initial_state_from, parameters_from

_problem = config_error(
    config, Path(workflow.basedir) / "workflow/schemas/config.schema.yaml"
)
if _problem:
    raise WorkflowError(f"invalid configuration: {_problem}")
validate(config, "../schemas/config.schema.yaml")


def _scene(*blocks):
    """Merge the model block with a scene's keys (later blocks win), sorted by key so that
    reordering the configuration file does not make Snakemake see changed params."""
    merged = {}
    for block in blocks:
        merged.update({k: v for k, v in block.items() if not isinstance(v, dict)})
    return dict(sorted(merged.items()))


def fig3_scene(case):
    scene = config["fig3"]
    return _scene(
        config["model"], scene["cases"][case], {"n_cycles": scene["n_cycles"]}
    )


def fig4_scene():
    return _scene(config["model"], config["fig4"])


def fig5_labels():
    """File labels of the Fig. 5 panels, one per spring constant: K_0.1, K_1, K_10."""
    return [f"{k:g}" for k in config["fig5"]["K"]]


def fig5_scene(label):
    scene = {k: v for k, v in config["fig5"].items() if k != "K"}
    stiffness = dict(zip(fig5_labels(), config["fig5"]["K"]))[label]
    return _scene(config["model"], scene, {"K": stiffness})


def check_cases():
    """The runs of the claims register (config: checks), each labelled with its group."""
    checks = config["checks"]
    base = _scene(config["model"], {"F": checks["F"], "x0": checks["x0"]})
    cases = [
        _scene(base, {"group": "paper", "label": f"fig3{c}"}, fig3_scene(c))
        for c in config["fig3"]["cases"]
    ]
    for i, ic in enumerate(checks["initial_conditions"]):
        cases.append(
            _scene(
                base,
                ic,
                {
                    "group": "initial_condition",
                    "label": f"F={ic['F']:g},x0={ic['x0']:g}",
                },
            )
        )
    for b in checks["b"]:
        cases.append(_scene(base, {"b": b, "group": "b", "label": f"b={b:g}"}))
    for group in ("symmetric", "asymmetric"):
        for force in checks[group]["F"]:
            for positions in checks[group]["positions"]:
                keys = dict(zip(("a1", "a2", "a3", "a4"), positions))
                label = f"F={force:g}," + ",".join(
                    f"{k}={v:g}" for k, v in keys.items()
                )
                cases.append(
                    _scene(base, keys, {"F": force, "group": group, "label": label})
                )
    return [{k: v for k, v in case.items() if k != "n_cycles"} for case in cases]


def benchmark_scene():
    scene = {k: v for k, v in config["benchmark"].items() if "settings" not in k}
    return _scene(config["model"], scene)


def benchmark_settings(slow=False):
    """Settings per method: the default ones, and with ``slow`` the slow ones too."""
    settings = {k: list(v) for k, v in config["benchmark"]["settings"].items()}
    if slow:
        for method, values in config["benchmark"]["slow_settings"].items():
            settings[method] = sorted(
                set(settings.get(method, [])) | set(values), reverse=True
            )
    return dict(sorted(settings.items()))


def long_run_scene():
    return _scene(config["model"], config["long_run"])


def stability_axes():
    """Values of b (cell centres of (start, stop)) and of F (start to stop)."""
    b, f = config["stability_map"]["b"], config["stability_map"]["F"]
    step = (b["stop"] - b["start"]) / b["n"]
    b_values = [b["start"] + (i + 0.5) * step for i in range(b["n"])]
    f_values = [
        f["start"] + (f["stop"] - f["start"]) * j / max(f["n"] - 1, 1)
        for j in range(f["n"])
    ]
    return b_values, f_values


def stability_chunks():
    return [str(i) for i in range(config["stability_map"]["chunks"])]


def stability_chunk(chunk):
    """The b values of one chunk, and all F values."""
    b_values, f_values = stability_axes()
    n = config["stability_map"]["chunks"]
    i = int(chunk)
    size = -(-len(b_values) // n)
    return b_values[i * size : (i + 1) * size], f_values


def stability_model():
    return _scene(config["model"], {"F": 0.0})


def _check_scenes():
    """Every scene's parameters must make a valid model before any job runs."""
    scenes = {f"fig3.cases.{c}": fig3_scene(c) for c in config["fig3"]["cases"]}
    scenes["fig4"] = fig4_scene()
    scenes.update({f"fig5 (K = {label})": fig5_scene(label) for label in fig5_labels()})
    scenes.update({f"checks ({case['label']})": case for case in check_cases()})
    scenes["benchmark"] = benchmark_scene()
    scenes["long_run"] = long_run_scene()
    b_values, f_values = stability_axes()
    for b in (b_values[0], b_values[-1]):
        for force in (f_values[0], f_values[-1]):
            scenes[f"stability_map (b = {b:g}, F = {force:g})"] = _scene(
                stability_model(), {"b": b, "F": force, "x0": 1.0}
            )
    if config["stability_map"]["chunks"] > len(b_values):
        raise WorkflowError(
            f"invalid configuration in stability_map: chunks = {config['stability_map']['chunks']} "
            f"is invalid: chunks must be <= b.n = {len(b_values)}"
        )
    for where, scene in scenes.items():
        try:
            parameters_from(scene)
            initial_state_from(scene)
        except ParameterError as err:
            raise WorkflowError(f"invalid configuration in {where}: {err}") from None
    v_window, a_window = (
        config["fig4"]["velocity_window"],
        config["fig4"]["acceleration_window"],
    )
    for name, (lo, hi) in (
        ("velocity_window", v_window),
        ("acceleration_window", a_window),
    ):
        if not lo < hi:
            raise WorkflowError(
                f"invalid configuration in fig4: {name} = {[lo, hi]} is invalid: "
                f"{name} must be [start, end] with start < end (s)"
            )


_check_scenes()


def package_code():
    """The package's source files: every job depends on them, so that a change of the
    code reruns what it affects (Snakemake tracks only the rule's own script)."""
    src = Path(workflow.basedir) / "src" / "escapement"
    return sorted(str(p) for p in src.rglob("*") if p.suffix in (".py", ".mplstyle"))


def all_outputs():
    return [
        *expand("results/fig3/case_{case}.nc", case=config["fig3"]["cases"]),
        "results/fig4/shock.nc",
        *expand("results/fig5/K_{K}.nc", K=fig5_labels()),
        "results/claims/checks.nc",
        *expand(
            "figures/{fig}.{ext}", fig=["fig3", "fig4", "fig5"], ext=["png", "pdf"]
        ),
        "results/claims.csv",
        "results/benchmark/work_precision.csv",
        "results/benchmark/long_run.nc",
        "results/stability/map.nc",
        "results/stress/summary.csv",
        *expand(
            "figures/{fig}.{ext}",
            fig=["work_precision", "long_run", "stability_map"],
            ext=["png", "pdf"],
        ),
        "README.md",
        "REPLICATION.md",
    ]
