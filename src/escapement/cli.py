"""The command line: ``python -m escapement solve`` runs the exact solver for one set of parameters.

It prints how the run ended and the per-cycle table of the Poincare map (cycle ``k`` starts at the
``k``-th impact at a1), or writes the run as the CF netCDF file the workflow writes for Fig. 3.
Parameters are given under the paper's symbols, in SI units; names, units and descriptions come
from :mod:`escapement.model.quantities`. Invalid input is refused before any work with the
parameter's name, its value and what it must be (exit status 2); a run that leaves the
escapement's regime ends with its typed outcome (exit status 1).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .model.parameters import ParameterError, Parameters
from .model.quantities import INITIAL_STATE, PARAMETERS, REQUIRED_KEYS
from .solvers.exact import solve_exact

__all__ = ["main"]

#: the paper's Sec. 4 (Fig. 3, case (a)) as the defaults
DEFAULTS = {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "x0": 1.0, "v0": 0.0}
COLUMNS = ("cycle", "impact_time", "velocity_before_impact", "period", "amplitude")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m escapement",
        description="Exact event-driven solution of the escapement model of Mao, Fu & Li (2013).",
    )
    commands = parser.add_subparsers(dest="command", required=True)
    solve = commands.add_parser(
        "solve",
        help="solve one run and print its per-cycle table",
        description="Release the mass at x0 with velocity v0 (t = 0+) and follow it for n cycles with the "
        "exact solver; print the outcome and the per-cycle table, or write a netCDF file.",
        epilog="Example: python -m escapement solve --F 0.5 --x0 3 --cycles 10",
    )
    for name, q in {**PARAMETERS, **INITIAL_STATE}.items():
        default = DEFAULTS.get(name)
        if name in REQUIRED_KEYS or name in INITIAL_STATE:
            shown = f"default {default:g}"
        else:
            shown = "default: -a1" if name == "a3" else "default: -a2"
        solve.add_argument(f"--{name}", type=float, default=default, metavar="VALUE",
                           help=f"{q.long_name}, {q.unit_label} ({shown})")
    solve.add_argument("--cycles", type=int, default=50, metavar="N", help="number of complete cycles (default 50)")
    solve.add_argument("--netcdf", metavar="PATH", help="write the run as CF netCDF (the Fig. 3 dataset) to PATH")
    return parser


def _table(run) -> str:
    c = run.cycles
    lines = ["\t".join(COLUMNS)]
    for k in range(len(c)):
        values = (c.impact_time[k], c.velocity_before_impact[k], c.period[k], c.amplitude[k])
        lines.append("\t".join([str(k + 1), *(repr(float(v)) for v in values)]))
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    values = {name: getattr(args, name) for name in PARAMETERS}
    try:
        params = Parameters(**{k: v for k, v in values.items() if v is not None})
        if args.netcdf and args.v0 != 0.0:
            raise ParameterError("v0", args.v0, "0 with --netcdf (the Fig. 3 dataset starts from rest)")
        run = solve_exact(params, args.x0, args.v0, n_cycles=args.cycles, record_trajectory=False)
    except ParameterError as err:
        print(f"python -m escapement solve: {err}", file=sys.stderr)
        return 2
    if args.netcdf:
        from .io.netcdf import write_netcdf
        from .pipeline.simulate import poincare_scene

        write_netcdf(poincare_scene(params, args.x0, args.cycles), args.netcdf)
        print(f"# {run.status.value}: {run.message}; wrote {args.netcdf}")
    else:
        print(f"# {run.status.value}: {run.message}")
        print(_table(run))
    return 0 if run.success else 1
