"""The command line: ``escapement solve`` (or ``python -m escapement solve``) runs the exact solver for
one set of parameters; ``escapement --version`` prints the installed distribution's version.

It prints how the run ended and the per-cycle table of the Poincare map (cycle ``k`` starts at the
``k``-th impact at a1), or writes the run as the CF netCDF file the workflow writes for Fig. 3.
Parameters are given under the paper's symbols, in SI units; names, units and descriptions come
from :mod:`escapement.model.quantities`. The defaults (:data:`DEFAULTS`) are Fig. 3 (a) as the
workflow runs it (``config/config.yaml``: the model block, ``fig3.cases.a`` and ``fig3.amplitude``):
released from rest at x0 = -1 m, the left turning point (the paper's Step 1), with the Step-1
amplitude h0(k); ``escapement solve --netcdf out.nc`` writes what the workflow writes to
``results/fig3/case_a.nc`` for the same number of cycles.

Everything is checked before any work: the parameters, the number of cycles and the output path
(its directory must exist and take a new file; none is made). A refusal is one line on standard
error naming the option as typed, its value and what it must be. The exit statuses
(:data:`EXIT_STATUSES`): 0 the run completed, 1 it left the escapement's regime (its typed outcome
is printed), 2 invalid input, 3 an output that cannot be written.
"""

from __future__ import annotations

import argparse
import errno
import os
import re
import sys
import textwrap
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import NoReturn

from . import __version__
from .model.limits import RunLimits
from .model.parameters import ParameterError, Parameters
from .model.quantities import INITIAL_STATE, PARAMETERS, REQUIRED_KEYS
from .model.printing import exact
from .solvers.exact import solve_exact
from .solvers.result import Solution
from .studies.readings import AMPLITUDES

__all__ = ["EXIT_STATUSES", "main"]

#: the program's name when run as a module; as the console script it is the name typed
MODULE_PROG = "python -m escapement"
#: the exit statuses, documented in ``--help``
EXIT_COMPLETED, EXIT_LEFT_REGIME, EXIT_INVALID_INPUT, EXIT_CANNOT_WRITE = 0, 1, 2, 3
EXIT_STATUSES = {
    EXIT_COMPLETED: "the run completed its cycles",
    EXIT_LEFT_REGIME: "the run left the escapement's regime (stopped, turned back in a zone, chattered); its "
                      "outcome is printed",
    EXIT_INVALID_INPUT: "invalid input, refused before any work",
    EXIT_CANNOT_WRITE: "an output that cannot be written (refused before any work where the file system shows it "
                       "beforehand), or standard output closed",
}

#: Fig. 3 (a) as the workflow runs it (config/config.yaml: the model block, fig3.cases.a, fig3.n_cycles
#: and fig3.amplitude): released from rest at -1 m, the Step-1 amplitude; a3 and a4 default to -a1, -a2
DEFAULTS = {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "x0": -1.0, "v0": 0.0}
DEFAULT_CYCLES = 50
DEFAULT_AMPLITUDE = "amplitude_h0"
COLUMNS = ("cycle", "impact_time", "velocity_before_impact", "period", "largest_displacement")
#: the options whose name differs from the solver's argument it sets
OPTIONS = {"n_cycles": "--cycles"}


class Refusal(Exception):
    """An input or output refused before any work: the exit status and the line to print."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


def _refusal(status: int, option: str, value: object, requirement: str) -> Refusal:
    return Refusal(status, f"{option} {value!r} is invalid: {option} must be {requirement}")


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line, the option first, and exit status 2."""

    def error(self, message: str) -> NoReturn:
        message = re.sub(r"^argument (--\w+): (?=\1 )", "", message)  # the option leads the message already
        self.exit(EXIT_INVALID_INPUT, f"{self.prog}: {message}\n")


def _number(option: str) -> Callable[[str], float]:
    def parse(text: str) -> float:
        try:
            return float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid: {option} must be a number") from None
    return parse


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--cycles {text!r} is invalid: --cycles must be an integer") from None


def _invoked_as() -> str:
    """The name the program was started by: ``python -m escapement`` for the module, else the name of the
    console script as typed (``escapement`` when called from code)."""
    name = os.path.basename(sys.argv[0]) if sys.argv else ""
    if name == "__main__.py":
        return MODULE_PROG
    return "escapement" if name in ("", "-c") else name


def _parser(prog: str) -> argparse.ArgumentParser:
    parser = _Parser(
        prog=prog,
        description="Exact event-driven solution of the escapement model of Mao, Fu & Li (2013).",
    )
    parser.add_argument("--version", action="version", version=f"escapement {__version__}",
                        help="print the installed version of escapement and exit")
    commands = parser.add_subparsers(dest="command", required=True)
    statuses = "\n".join(textwrap.fill(text, 79, initial_indent=f"  {code}  ", subsequent_indent=" " * 5)
                         for code, text in EXIT_STATUSES.items())
    solve = commands.add_parser(
        "solve",
        help="solve one run and print its per-cycle table",
        description="Release the mass at x0 with velocity v0 (t = 0+) and follow it for n cycles with the "
        "exact solver; print the outcome and the per-cycle table, or write a netCDF file. Every input and the "
        "output path are checked before any work. The defaults are Fig. 3 (a) as the workflow runs it: "
        "released from rest at x0 = -1 m (the left turning point, the paper's Step 1), 50 cycles, the "
        "Step-1 amplitude h0(k) in the netCDF file.",
        epilog=f"exit status:\n{statuses}\n\nExample: {prog} solve --F 0.5 --x0 -3 --cycles 10",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    for name, q in {**PARAMETERS, **INITIAL_STATE}.items():
        default = DEFAULTS.get(name)
        if name in REQUIRED_KEYS or name in INITIAL_STATE:
            shown = f"default {exact(default)}"
        else:
            shown = "default: -a1" if name == "a3" else "default: -a2"
        solve.add_argument(f"--{name}", type=_number(f"--{name}"), default=default, metavar="VALUE",
                           help=f"{q.long_name}, {q.unit_label} ({shown})")
    solve.add_argument("--cycles", type=_integer, default=DEFAULT_CYCLES, metavar="N",
                       help=f"number of complete cycles (default {DEFAULT_CYCLES})")
    solve.add_argument("--netcdf", metavar="PATH", help="write the run as CF netCDF to PATH, a file in an existing "
                       "directory: the dataset of Fig. 3 (a) as the workflow runs it, with this run's inputs")
    solve.add_argument("--amplitude", choices=list(AMPLITUDES), default=DEFAULT_AMPLITUDE,
                       help=f"the amplitude the netCDF file holds (default {DEFAULT_AMPLITUDE}, the Step-1 amplitude "
                       "h0(k), as the workflow's Fig. 3); the table prints the largest displacement per cycle")
    return parser


def _table(run: Solution) -> str:
    c = run.cycles
    lines = ["\t".join(COLUMNS)]
    for k in range(len(c)):
        values = (c.impact_time[k], c.velocity_before_impact[k], c.period[k], c.largest_displacement[k])
        lines.append("\t".join([str(k + 1), *(repr(float(v)) for v in values)]))
    return "\n".join(lines)


def _parameter_refusal(err: ParameterError) -> Refusal:
    """The solver's refusal of an argument, told under the option that sets it."""
    option = OPTIONS.get(err.name, f"--{err.name}")
    requirement = err.requirement
    for name, other in OPTIONS.items():
        requirement = re.sub(rf"\b{name}\b", other, requirement)
    return _refusal(EXIT_INVALID_INPUT, option, err.value, requirement)


def _check_output(option: str, text: str) -> None:
    """Refuse an output path that names no file, or whose file cannot be made where it is named."""
    from .io.atomic import WriteError, check_target

    file = "the path of a file to write"
    if not text or "\0" in text:
        raise _refusal(EXIT_INVALID_INPUT, option, text, file + " (not empty, no NUL character)")
    separators = tuple(s for s in (os.sep, os.altsep) if s)
    if text.endswith(separators) or Path(text).name in ("", ".", ".."):
        raise _refusal(EXIT_INVALID_INPUT, option, text, file + ", not of a directory")
    try:
        check_target(text)
    except WriteError as err:
        if err.errno in (errno.EISDIR, errno.EINVAL):  # a directory, a device: a path that names no file to write
            raise _refusal(EXIT_INVALID_INPUT, option, text, f"the path of a regular file; {err.strerror}") from err
        raise _refusal(EXIT_CANNOT_WRITE, option, text, f"{file} in an existing directory that takes a new file; "
                       f"{err.strerror}") from err


def _run(args: argparse.Namespace) -> tuple[int, str]:
    """Check the inputs and the output, solve, write the netCDF file if asked; the exit status and the
    text for standard output."""
    values = {name: getattr(args, name) for name in PARAMETERS}
    try:
        params = Parameters(**{k: v for k, v in values.items() if v is not None})
        if args.netcdf is not None and args.v0 != 0.0:
            raise ParameterError("v0", args.v0, "0 with --netcdf (the Fig. 3 dataset starts from rest)")
        RunLimits(n_cycles=args.cycles)
    except ParameterError as err:
        raise _parameter_refusal(err) from err
    if args.netcdf is not None:
        _check_output("--netcdf", args.netcdf)  # the netCDF layer (xarray) is loaded only for a netCDF file
    try:
        run = solve_exact(params, args.x0, args.v0, n_cycles=args.cycles, record_trajectory=False)
    except ParameterError as err:  # the run's memory estimate
        raise _parameter_refusal(err) from err
    if args.netcdf is not None:
        from .io.atomic import WriteError
        from .io.netcdf import DatasetError, write_netcdf
        from .pipeline.simulate import poincare_scene

        try:
            write_netcdf(poincare_scene(params, args.x0, args.cycles, args.amplitude), args.netcdf)
        except (WriteError, DatasetError) as err:
            raise Refusal(EXIT_CANNOT_WRITE, f"--netcdf {args.netcdf!r}: {err}") from err
        text = f"# {run.status.value}: {run.message}; wrote {args.netcdf}"
    else:
        text = f"# {run.status.value}: {run.message}\n{_table(run)}"
    return (EXIT_COMPLETED if run.success else EXIT_LEFT_REGIME), text


def main(argv: Sequence[str] | None = None, prog: str | None = None) -> int:
    """Run the command line on ``argv`` (the process's arguments by default) as program ``prog`` (the name
    it was started by by default); return the exit status."""
    prog = _invoked_as() if prog is None else prog
    try:
        args = _parser(prog).parse_args(argv)
    except SystemExit as stop:  # --help, or a refusal of the parser, already printed
        return EXIT_COMPLETED if stop.code is None else stop.code if isinstance(stop.code, int) else EXIT_INVALID_INPUT
    try:
        status, text = _run(args)
    except Refusal as refusal:
        print(f"{prog} {args.command}: {refusal}", file=sys.stderr)
        return refusal.status
    try:
        print(text)
        sys.stdout.flush()
    except BrokenPipeError:  # the reader of standard output has gone (a pager closed, ``| head``)
        _quiet_stdout()
        return EXIT_CANNOT_WRITE
    except OSError as err:  # standard output on a full disk, a closed descriptor
        _quiet_stdout()
        print(f"{prog} {args.command}: cannot write standard output: {err.strerror}", file=sys.stderr)
        return EXIT_CANNOT_WRITE
    return status


def _quiet_stdout() -> None:
    """Point standard output at the null device, so that the interpreter's last flush of what could not
    be written raises nothing at exit."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # replaced by an object without a descriptor (a test's)
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, fd)
    os.close(devnull)
