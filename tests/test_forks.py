"""The forks that run the end-to-end tests' commands (tests/forks.py) against new processes: the same path,
directory, arguments, output and exit status, and none of the project's modules loaded before the command."""

from __future__ import annotations

import subprocess
import sys

import forks as forks_module
import pytest
from forks import Forks

SHOW = "import os, sys\nprint(os.getcwd(), sys.argv, sys.path, sep='\\n')\nprint('to stderr', file=sys.stderr)\n"


@pytest.fixture(scope="module")
def forks():
    interpreter = Forks(("json",))
    yield interpreter
    interpreter.close()


def _new_process(cwd, *argv) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *argv], cwd=cwd, capture_output=True, text=True)


def test_code_runs_as_in_a_new_interpreter(forks, tmp_path):
    fork = forks.run(tmp_path, code=SHOW, args=("one", "two"))
    new = _new_process(tmp_path, "-c", SHOW, "one", "two")
    assert (fork.returncode, fork.stdout, fork.stderr) == (new.returncode, new.stdout, new.stderr) == (
        0, new.stdout, "to stderr\n")
    assert str(tmp_path) in fork.stdout and "['-c', 'one', 'two']" in fork.stdout


def test_a_module_runs_as_with_python_m(forks, tmp_path):
    fork = forks.run(tmp_path, module="site")  # prints sys.path, sys.path[0] the directory
    new = _new_process(tmp_path, "-m", "site")
    assert fork.returncode == new.returncode == 0
    assert fork.stdout == new.stdout and repr(str(tmp_path)) in fork.stdout


@pytest.mark.parametrize("code, status, words", [
    ("import sys\nsys.exit(3)", 3, ""),
    ("raise SystemExit('refused')", 1, "refused"),
    ("1 / 0", 1, "ZeroDivisionError: division by zero"),
])
def test_an_exit_status_and_its_message_are_those_of_a_new_process(forks, tmp_path, code, status, words):
    fork, new = forks.run(tmp_path, code=code), _new_process(tmp_path, "-c", code)
    assert fork.returncode == new.returncode == status
    assert words in fork.stderr and words in new.stderr


def test_a_command_killed_after_its_timeout_reports_the_signal(forks, tmp_path):
    assert forks.run(tmp_path, code="import time\ntime.sleep(30)", timeout=1).returncode == -14  # SIGALRM


def test_each_command_starts_from_the_imports_of_the_interpreter_alone(forks, tmp_path):
    """What one command imports or changes is gone for the next; the project's modules are never loaded
    before a command."""
    assert forks.run(tmp_path, code="import escapement, os\nos.environ['LEFT'] = '1'").returncode == 0
    code = "import os, sys\nprint(sorted(n for n in sys.modules if n.startswith('escapement')), 'LEFT' in os.environ,"
    code += " 'json' in sys.modules)"
    assert forks.run(tmp_path, code=code).stdout == "[] False True\n"


@pytest.mark.parametrize("timeout", [0, -1, 1.5, True, "10"])
def test_a_timeout_is_a_whole_number_of_seconds(forks, tmp_path, timeout):
    with pytest.raises(ValueError, match=rf"^timeout = {timeout!r} is invalid: timeout must be an integer >= 1"):
        forks.run(tmp_path, code="pass", timeout=timeout)


def test_a_command_that_ignores_its_alarm_is_killed_with_its_interpreter(tmp_path, monkeypatch):
    monkeypatch.setattr(forks_module, "GRACE_SECONDS", 1)
    interpreter = Forks(("json",))
    code = "import signal, time\nsignal.signal(signal.SIGALRM, signal.SIG_IGN)\ntime.sleep(30)"
    with pytest.raises(TimeoutError, match="outlived its alarm of 1 s by 1 s: killed"):
        interpreter.run(tmp_path, code=code, timeout=1)
    assert interpreter.process.poll() is not None
    interpreter.close()


def test_an_interpreter_whose_imports_load_the_project_refuses_every_command(tmp_path):
    """The files a command is seen to load would miss a module of the project loaded before the fork."""
    interpreter = Forks(("escapement.model",))
    with pytest.raises(RuntimeError, match="ended"):
        interpreter.run(tmp_path, code="pass")
    assert interpreter.process.wait(timeout=60) == 1
    interpreter.close()


def test_a_command_is_exactly_one_of_a_module_or_code(forks, tmp_path):
    for kind in ({}, {"module": "site", "code": "pass"}):
        with pytest.raises(ValueError, match="exactly one of them must be given"):
            forks.run(tmp_path, **kind)
