"""Fixtures starting the real robocal server (binary from `ROBOCAL_BIN`,
else `robocal` on PATH) on a free loopback port with a fresh SQLite
database, and a small simulated campaign calibrated once per run."""

from __future__ import annotations

import json
import os
import shutil
import socket
import subprocess
import time
import zipfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest

from robocal_client import Client

#: The smallest simulated campaign that still calibrates (PUMA-560: six
#: calibration and two validation poses; the fit takes about 2 s).
CAMPAIGN_ARGS = ["--robot", "puma560", "--cal", "6", "--val", "2", "--seed", "21"]
STARTUP_TIMEOUT_S = 30.0
SERIAL = "PY-TEST-1"


def robocal_bin() -> str:
    found = os.environ.get("ROBOCAL_BIN") or shutil.which("robocal")
    if not found:
        pytest.fail("no robocal binary: set ROBOCAL_BIN or put robocal on PATH")
    return found


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


@dataclass
class Server:
    url: str
    database_url: str
    process: subprocess.Popen[bytes]

    def create_token(self, scope: str) -> str:
        """A token made with the CLI, directly in the server's database."""
        out = subprocess.run(
            [robocal_bin(), "token", "create", "--scope", scope, "--name", f"test-{scope}",
             "--database-url", self.database_url],
            check=True, capture_output=True, text=True,
        )
        return out.stdout.strip().splitlines()[-1]


def start_server(work: Path) -> Server:
    port = free_port()
    database_url = f"sqlite://{work / 'robocal.db'}"
    log = open(work / "server.log", "wb")
    process = subprocess.Popen(
        [robocal_bin(), "serve", "--bind", f"127.0.0.1:{port}", "--database-url", database_url,
         "--workers", "1"],
        stdout=log, stderr=subprocess.STDOUT,
    )
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + STARTUP_TIMEOUT_S
    while True:
        try:
            if httpx.get(f"{url}/healthz", timeout=1.0).status_code == 200:
                return Server(url, database_url, process)
        except httpx.TransportError:
            pass
        if process.poll() is not None or time.monotonic() > deadline:
            process.kill()
            pytest.fail(f"server did not start: {(work / 'server.log').read_text()[-2000:]}")
        time.sleep(0.1)


def stop_server(server: Server) -> None:
    server.process.terminate()
    try:
        server.process.wait(timeout=10)
    except subprocess.TimeoutExpired:
        server.process.kill()


@pytest.fixture
def server_factory(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Callable[[], Server]]:
    """Starts servers of its own (a test that creates tokens ends anonymous
    access, so it must not share the session's server)."""
    started: list[Server] = []

    def start() -> Server:
        server = start_server(tmp_path_factory.mktemp("server"))
        started.append(server)
        return server

    yield start
    for server in started:
        stop_server(server)


@pytest.fixture(scope="session")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    started = start_server(tmp_path_factory.mktemp("server"))
    yield started
    stop_server(started)


@pytest.fixture(scope="session")
def campaign(tmp_path_factory: pytest.TempPathFactory) -> Path:
    directory = tmp_path_factory.mktemp("campaign") / "campaign"
    subprocess.run([robocal_bin(), "simulate", *CAMPAIGN_ARGS, str(directory)], check=True, capture_output=True)
    return directory


def campaign_files(campaign: Path) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    files: dict[str, Any] = json.loads((campaign / "campaign.json").read_text())
    poses: list[dict[str, Any]] = json.loads((campaign / "poses.json").read_text())
    return files, poses


def zip_poses(campaign: Path, poses: list[dict[str, Any]], archive: Path) -> Path:
    with zipfile.ZipFile(archive, "w") as z:
        z.writestr("poses.json", json.dumps(poses))
        for entry in poses:
            z.write(campaign / entry["image"], entry["image"])
    return archive


@dataclass
class Calibrated:
    client: Client
    serial: str
    session_id: str
    job_id: str
    progress_seen: list[float]
    upload_progress: list[tuple[int, int]]
    campaign: Path


@pytest.fixture(scope="session")
def calibrated(server: Server, campaign: Path, tmp_path_factory: pytest.TempPathFactory) -> Calibrated:
    """One pose uploaded as multipart, the rest as a zip (with progress),
    calibrated and waited for over the event stream."""
    client = Client(server.url)
    files, poses = campaign_files(campaign)
    client.put_robot(SERIAL, files["robot"])
    session = client.create_session(SERIAL, files["session"])
    first = poses[0]
    pose = client.add_pose_image(session.id, campaign / first["image"], first["joints_deg"], first["set"])
    assert pose.source == "image"
    archive = zip_poses(campaign, poses[1:], tmp_path_factory.mktemp("zip") / "dataset.zip")
    upload_progress: list[tuple[int, int]] = []
    dataset = client.upload_dataset(session.id, archive, progress=lambda sent, total: upload_progress.append((sent, total)))
    assert dataset.poses_created == len(poses) - 1
    accepted = client.calibrate(session.id)
    progress_seen: list[float] = []
    job = client.wait(accepted.job_id, on_progress=lambda p: progress_seen.append(p.progress))
    assert job.state == "succeeded"
    return Calibrated(client, SERIAL, session.id, accepted.job_id, progress_seen, upload_progress, campaign)
