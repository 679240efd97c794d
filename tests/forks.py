"""Commands of the end-to-end tests run in forks of an interpreter that has imported their heavy modules once.

Each Snakemake command (a dry run above all) spends about half its time importing Snakemake and its plugins,
and each script whose imports are listed spends most of its time importing NumPy, xarray and Matplotlib. A
:class:`Forks` is one interpreter, started with the environment of the commands it runs, that imports the
modules it is given, then runs each command in a fork of itself: ``python -m module args`` or ``python -c
code`` in a directory, with the same ``sys.path`` as a new interpreter, its own output and exit status, so that
a command behaves as in a new process except for the time its imports take. The modules imported once are
never the project's: the modules a command loads from ``escapement`` are loaded in its fork.

Run as a program, this file is that interpreter: its arguments are the modules to import; it reads one command
a line (JSON) on its standard input and answers each with one line (JSON) on the descriptor it was given.
"""

from __future__ import annotations

import atexit
import gc
import importlib
import json
import os
import runpy
import select
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

__all__ = ["Forks"]

#: how long a command may outlive its alarm (one it ignores) before its interpreter is killed (s)
GRACE_SECONDS = 60


class Forks:
    """An interpreter that imports ``modules`` once and runs commands in forks of itself (see the module)."""

    def __init__(self, modules: tuple[str, ...], env: dict[str, str] | None = None):
        read, self._answers_fd = os.pipe()
        # a session of its own: a command that outlives its deadline is killed with every process it started
        self.process = subprocess.Popen([sys.executable, __file__, str(self._answers_fd), *modules],
                                        stdin=subprocess.PIPE, env=env, text=True, pass_fds=(self._answers_fd,),
                                        start_new_session=True)
        os.close(self._answers_fd)
        self._answers = os.fdopen(read)
        atexit.register(self.close)

    def close(self) -> None:
        """Ends the interpreter (at the end of its last command)."""
        if self.process.poll() is None:
            self.process.stdin.close()
            self.process.wait()
        self._answers.close()

    def run(self, cwd: Path, *, module: str | None = None, code: str | None = None, args: tuple[str, ...] = (),
            timeout: int = 600) -> subprocess.CompletedProcess:
        """What ``python -m module *args`` (or ``python -c code *args``) in ``cwd`` gives: its exit status and
        output, as :func:`subprocess.run` with ``capture_output=True, text=True`` would; killed after
        ``timeout`` seconds (by an alarm in the fork; should the command outlive that by :data:`GRACE_SECONDS`, by
        killing the interpreter and everything it started, and raising :class:`TimeoutError`)."""
        if (module is None) == (code is None):
            raise ValueError(f"module = {module!r}, code = {code!r}: exactly one of them must be given")
        if isinstance(timeout, bool) or not isinstance(timeout, int) or timeout < 1:
            raise ValueError(f"timeout = {timeout!r} is invalid: timeout must be an integer >= 1 (s)")
        if self.process.poll() is not None:
            raise RuntimeError(f"the interpreter of the forks has ended with status {self.process.returncode}")
        command = {"cwd": str(cwd), "module": module, "code": code, "args": list(args), "timeout": timeout}
        self.process.stdin.write(json.dumps(command) + "\n")
        self.process.stdin.flush()
        if not select.select([self._answers], [], [], timeout + GRACE_SECONDS)[0]:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait()
            raise TimeoutError(f"{command} outlived its alarm of {timeout} s by {GRACE_SECONDS} s: killed")
        answer = json.loads(self._answers.readline() or "null")
        if answer is None:
            raise RuntimeError(f"the interpreter of the forks ended while running {command}")
        argv = [sys.executable, *(["-m", module] if module else ["-c", code]), *args]
        return subprocess.CompletedProcess(argv, answer["returncode"], answer["stdout"], answer["stderr"])


# --- the interpreter, run as a program -------------------------------------------------------------------


def _command(command: dict, stdout: int, stderr: int) -> None:
    """In the fork: what ``python -m module`` or ``python -c code`` does, in the command's directory, with
    its own standard streams; an exception ends the fork as it ends an interpreter."""
    os.chdir(command["cwd"])
    devnull = os.open(os.devnull, os.O_RDONLY)
    for fd, target in ((devnull, 0), (stdout, 1), (stderr, 2)):
        os.dup2(fd, target)
    signal.alarm(command["timeout"])  # the default action of SIGALRM ends the fork
    if command["module"]:
        sys.path[0] = os.getcwd()  # as -m does
        sys.argv = [None, *command["args"]]
        runpy.run_module(command["module"], run_name="__main__", alter_sys=True)
    else:
        sys.path[0] = ""  # as -c does
        sys.argv = ["-c", *command["args"]]
        exec(compile(command["code"], "<string>", "exec"), {"__name__": "__main__", "__builtins__": __builtins__})
    sys.exit(0)


def _serve(answers_fd: int, modules: list[str]) -> None:
    for name in modules:
        importlib.import_module(name)
    # a module of the project loaded here would be missing from the files a command is seen to load
    project = sorted(name for name in sys.modules if name.partition(".")[0] in ("escapement", "benchmarks"))
    if project:
        raise SystemExit(f"importing {modules} loaded modules of the project, {project}: they must load in a fork")
    gc.freeze()  # the imported objects: never collected, never copied into a fork by the collector
    answers = os.fdopen(answers_fd, "w")
    for line in sys.stdin:
        command = json.loads(line)
        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            sys.stdout.flush()
            sys.stderr.flush()
            pid = os.fork()
            if pid == 0:
                answers.close()
                _command(command, out.fileno(), err.fileno())
            status = os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])
            answer = {"returncode": status}
            for name, stream in (("stdout", out), ("stderr", err)):
                stream.seek(0)
                answer[name] = stream.read().decode(errors="replace")
        answers.write(json.dumps(answer) + "\n")
        answers.flush()


if __name__ == "__main__":
    _serve(int(sys.argv[1]), sys.argv[2:])
