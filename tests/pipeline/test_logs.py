"""A job's log and how it fails: one line when the machine refuses a file, the traceback for a fault of the code."""

from __future__ import annotations

from pathlib import Path

import pytest

from escapement.pipeline.logs import logged
from escapement.pipeline.publish import publish


def test_a_file_the_machine_refuses_fails_the_job_in_one_line_naming_it(tmp_path, monkeypatch, capsys):
    """publish into a tracked folder that cannot be written (here its path runs through a file: the refusal root
    gets too, where a read-only folder does not stop root)."""
    monkeypatch.chdir(tmp_path)
    Path("figures").write_text("a file where the folder should be\n")
    Path("drawn.md").write_text("text\n")
    with pytest.raises(SystemExit) as failed:
        publish({"figures/README.md": "drawn.md"}, "publish.log")
    message = str(failed.value.code)
    assert message.startswith("publish failed: [Errno 17] File exists") and "\n" not in message
    assert message.endswith("/figures'")  # the file that stands where the folder should be
    log = Path("publish.log").read_text()
    assert "Traceback" not in log and log.splitlines()[-1].endswith(message.removeprefix("publish failed: "))


def test_a_fault_of_the_code_keeps_its_traceback_in_the_log(tmp_path):
    with pytest.raises(ZeroDivisionError):
        with logged(tmp_path / "job.log", "job"):
            1 / 0
    assert "Traceback" in (tmp_path / "job.log").read_text()
