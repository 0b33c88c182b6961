"""The README's examples run as written from an empty directory against a
fresh server, and pass `mypy --strict`."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

from conftest import Server, robocal_bin
from readme_blocks import script

#: Seconds the whole README job may take (simulation, upload, two jobs).
README_TIMEOUT_S = 600


def test_readme_examples_run_against_a_server(server_factory: Callable[[], Server], tmp_path: Path) -> None:
    server = server_factory()  # its own: the last block creates tokens
    example = tmp_path / "example.py"
    example.write_text(script())
    work = tmp_path / "empty"
    work.mkdir()
    env = {
        **os.environ,
        "ROBOCAL_URL": server.url,
        "PATH": os.pathsep.join([str(Path(robocal_bin()).resolve().parent), os.environ.get("PATH", "")]),
    }
    done = subprocess.run(
        [sys.executable, str(example)], cwd=work, env=env, capture_output=True, text=True, timeout=README_TIMEOUT_S
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "mm calibrated" in done.stdout and "422" in done.stdout, done.stdout
    assert (work / "robot.urdf").read_text().lstrip().startswith("<?xml")


def test_readme_examples_pass_mypy_strict(tmp_path: Path) -> None:
    example = tmp_path / "readme_example.py"
    example.write_text(script())
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", str(example)],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert done.returncode == 0, done.stdout + done.stderr
