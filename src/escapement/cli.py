"""The command line: ``escapement solve`` runs the exact solver for one set of parameters (the paper's symbols, SI
units), prints how the run ended and its per-cycle table, and writes the run as CF netCDF or its cycles as CSV.
Everything is checked before any work; a refusal is one line on standard error naming the option as typed, its
value and what it must be, and the exit status says which (:data:`EXIT_STATUSES`).
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

from . import __version__
from .model.limits import RunLimits
from .model.parameters import ParameterError, Parameters, check_initial_state
from .model.printing import exact
from .model.quantities import INITIAL_STATE, PARAMETERS, REQUIRED_KEYS
from .solvers.exact import solve_exact

__all__ = ["DEFAULTS", "EXIT_STATUSES", "main"]

#: the program's name when run as a module; as the console script it is the name typed
MODULE_PROG = "python -m escapement"
EXIT_COMPLETED, EXIT_LEFT_REGIME, EXIT_INVALID_INPUT, EXIT_CANNOT_WRITE = 0, 1, 2, 3
EXIT_STATUSES = {
    EXIT_COMPLETED: "the run completed its cycles",
    EXIT_LEFT_REGIME: "the run left the escapement's regime (stopped, turned back in a zone, chattered); its "
                      "outcome is printed",
    EXIT_INVALID_INPUT: "invalid input, refused before any work",
    EXIT_CANNOT_WRITE: "an output that cannot be written (refused before any work where the file system shows it "
                       "beforehand), or standard output closed",
}
#: Fig. 3 (a) as the workflow runs it (config/paper.yaml); a3 and a4 default to -a1, -a2
DEFAULTS = {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "x0": -1.0, "v0": 0.0}
DEFAULT_CYCLES = 50


class Refusal(Exception):
    """An input or output refused before any work: the exit status and the line to print."""

    def __init__(self, status: int, option: str, value: object, requirement: str) -> None:
        super().__init__(f"{option} {value!r} is invalid: {option} must be {requirement}")
        self.status = status


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line, the option first, and exit status 2."""

    def error(self, message: str) -> NoReturn:
        message = re.sub(r"^argument (--\w+): (?=\1 )", "", message)  # the option leads the message already
        self.exit(EXIT_INVALID_INPUT, f"{self.prog}: {message}\n")


def _typed(option: str, kind: type):
    def parse(text: str):
        try:
            return kind(text)
        except ValueError:
            what = "an integer" if kind is int else "a number"
            raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid: {option} must be {what}") from None
    return parse


def _invoked_as() -> str:
    """``python -m escapement`` for the module, else the name of the console script as typed."""
    name = os.path.basename(sys.argv[0]) if sys.argv else ""
    return MODULE_PROG if name == "__main__.py" else "escapement" if name in ("", "-c") else name


def _parser(prog: str) -> argparse.ArgumentParser:
    parser = _Parser(prog=prog, description="Exact event-driven solution of the escapement model of Mao, Fu & Li "
                                            "(2013).")
    parser.add_argument("--version", action="version", version=f"escapement {__version__}",
                        help="print the installed version of escapement and exit")
    commands = parser.add_subparsers(dest="command", required=True)
    statuses = "\n".join(textwrap.fill(text, 79, initial_indent=f"  {code}  ", subsequent_indent=" " * 5)
                         for code, text in EXIT_STATUSES.items())
    solve = commands.add_parser(
        "solve", help="solve one run and print its per-cycle table",
        description="Release the mass at x0 with velocity v0 (t = 0+) and follow it for n cycles with the exact "
        "solver; print the outcome and the per-cycle table, and write the run as netCDF or its cycles as CSV if "
        "asked. Every input and output path is checked before any work. The defaults are Fig. 3 (a) as the "
        "workflow runs it: released from rest at x0 = -1 m (the left turning point, the paper's Step 1), 50 "
        "cycles.",
        epilog=f"exit status:\n{statuses}\n\nExample: {prog} solve --F 0.5 --x0 -3 --cycles 10 --csv cycles.csv",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    for name, q in {**PARAMETERS, **INITIAL_STATE}.items():
        default = DEFAULTS.get(name)
        shown = f"default {exact(default)}" if name in REQUIRED_KEYS or name in INITIAL_STATE else \
            f"default: -{ {'a3': 'a1', 'a4': 'a2'}[name] }"
        solve.add_argument(f"--{name}", type=_typed(f"--{name}", float), default=default, metavar="VALUE",
                           help=f"{q.long_name}, {q.unit_label} ({shown})")
    solve.add_argument("--cycles", type=_typed("--cycles", int), default=DEFAULT_CYCLES, metavar="N",
                       help=f"number of complete cycles (default {DEFAULT_CYCLES})")
    solve.add_argument("--netcdf", metavar="PATH", help="write the run (cycles, events, parameters, outcome) as CF "
                       "netCDF to PATH, a file in an existing directory")
    solve.add_argument("--csv", metavar="PATH", help="write the per-cycle table as CSV to PATH")
    return parser


def _check_output(option: str, text: str) -> Path:
    """The file ``text`` names (its symbolic links resolved), or a refusal of a path that names no file or where none
    can be written."""
    from .io.netcdf import writable_target

    if not text or "\0" in text:
        raise Refusal(EXIT_INVALID_INPUT, option, text, "the path of a file to write, not empty")
    directory = Refusal(EXIT_INVALID_INPUT, option, text, "the path of a file to write, not of a directory")
    if text.endswith((os.sep, "/")) or Path(text).name in ("", ".", ".."):
        raise directory
    try:
        target = writable_target(text)
        read_only = target.exists() and not os.access(target, os.W_OK)
    except IsADirectoryError as err:
        raise directory from err
    except FileExistsError as err:  # a device, a pipe, a socket
        raise Refusal(EXIT_INVALID_INPUT, option, text, "the path of a regular file or of a new one, not of a "
                      "device, pipe or socket") from err
    except (FileNotFoundError, NotADirectoryError) as err:
        raise Refusal(EXIT_CANNOT_WRITE, option, text, "a file in an existing directory") from err
    except OSError as err:  # no permission, a read-only file system, a loop of links, a name too long
        raise Refusal(EXIT_CANNOT_WRITE, option, text, f"writable ({err.strerror})") from err
    if read_only:
        raise Refusal(EXIT_CANNOT_WRITE, option, text, "writable (the file is read-only)")
    return target


def _run(args: argparse.Namespace, command: str) -> tuple[int, str]:
    """Check the inputs and outputs, solve, write the files asked for; the exit status and the text to print."""
    try:
        params = Parameters(**{k: v for k in PARAMETERS if (v := getattr(args, k)) is not None})
        check_initial_state(args.x0, args.v0)
        RunLimits(n_cycles=args.cycles)
    except ParameterError as err:  # the solver's n_cycles is the option --cycles
        option = "--cycles" if err.name == "n_cycles" else f"--{err.name}"
        requirement = re.sub(r"\bn_cycles\b", "--cycles", err.requirement)
        raise Refusal(EXIT_INVALID_INPUT, option, err.value, requirement) from err
    seen: dict[Path, str] = {}  # each output checked, and no two of them the same file
    for option in ("--netcdf", "--csv"):
        if (text := getattr(args, option.removeprefix("--"))) is not None:
            if (target := _check_output(option, text)) in seen:
                other = seen[target]
                raise Refusal(EXIT_INVALID_INPUT, option, text, f"another file than {other} "
                              f"{getattr(args, other.removeprefix('--'))!r}: both name {target}")
            seen[target] = option
    try:
        run = solve_exact(params, args.x0, args.v0, n_cycles=args.cycles, record_trajectory=False)
    except ParameterError as err:  # the initial state, the run's memory estimate
        raise Refusal(EXIT_INVALID_INPUT, f"--{err.name}" if err.name in INITIAL_STATE else "--cycles", err.value,
                      err.requirement) from err
    table = run.to_dataframe("cycles")
    written = []
    for option, path in (("--netcdf", args.netcdf), ("--csv", args.csv)):
        if path is None:
            continue
        from .io.netcdf import DatasetError, replaced, write_netcdf  # xarray only where a netCDF file is written

        try:
            if option == "--netcdf":
                from .scenes.cf import run_dataset

                write_netcdf(run_dataset(run), path, history=command)
            else:
                with replaced(path) as tmp:
                    table.to_csv(tmp, float_format="%.17g")
        except (DatasetError, OSError) as err:  # what the file system says once the run is solved
            raise Refusal(EXIT_CANNOT_WRITE, option, path, f"writable ({err})") from err
        written.append(path)
    head = f"# {run.status.value}: {run.message}" + (f"; wrote {', '.join(written)}" if written else "")
    body = table.to_csv(sep="\t", float_format="%.17g", lineterminator="\n").rstrip("\n")
    return (EXIT_COMPLETED if run.success else EXIT_LEFT_REGIME), f"{head}\n{body}"


def main(argv: Sequence[str] | None = None, prog: str | None = None) -> int:
    """Run the command line on ``argv`` (by default the process's arguments) as program ``prog``: the exit status."""
    prog = _invoked_as() if prog is None else prog
    argv = sys.argv[1:] if argv is None else list(argv)
    if sys.stdout is None:  # started with standard output closed (``>&-``): refused before any work
        print(f"{prog}: cannot write standard output: it is closed (redirect it to a file or /dev/null)",
              file=sys.stderr)
        return EXIT_CANNOT_WRITE
    try:
        args = _parser(prog).parse_args(argv)
    except SystemExit as stop:  # --help, or a refusal of the parser, already printed
        return EXIT_COMPLETED if stop.code is None else stop.code if isinstance(stop.code, int) else EXIT_INVALID_INPUT
    try:
        status, text = _run(args, " ".join([prog, *argv]))
    except Refusal as refusal:
        print(f"{prog} {args.command}: {refusal}", file=sys.stderr)
        return refusal.status
    try:
        print(text)
        sys.stdout.flush()
    except OSError as err:  # the reader has gone (a pager closed, ``| head``), a full disk
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # the interpreter's last flush then raises nothing at exit
        os.close(devnull)
        if not isinstance(err, BrokenPipeError):
            print(f"{prog} {args.command}: cannot write standard output: {err.strerror}", file=sys.stderr)
        return EXIT_CANNOT_WRITE
    return status
