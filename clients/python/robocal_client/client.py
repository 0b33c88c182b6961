"""`Client`: the service's resources as methods returning the generated
(typed) models and raising `ProblemError` for problem+json answers.

Requests are built by the generated endpoint modules (`_generated/api`),
so paths, parameters and bodies follow the OpenAPI document; this layer
only unwraps answers, accepts plain dicts where the document has a body
model, and streams what the generator reads whole (NDJSON, SSE, large
uploads). Results, checks, plans, webhooks and tokens live in mixins
(`_results.py`, `_admin.py`) to keep one concept a file.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx

from ._admin import AdminMixin
from ._base import Base, as_model
from ._generated.api.jobs import cancel_job, get_job, list_jobs, start_calibration
from ._generated.api.poses import add_pose, list_poses, upload_dataset
from ._generated.api.robots import delete_robot, get_robot, list_robots, put_robot
from ._generated.api.sessions import create_session, get_session, list_sessions
from ._generated.models import (
    CalibrationOptions,
    DatasetOut,
    JobAccepted,
    JobList,
    JobOut,
    PoseImageUpload,
    PoseJsonBody,
    PoseList,
    PoseOut,
    PoseSet,
    RobotBody,
    RobotList,
    RobotOut,
    SessionBody,
    SessionList,
    SessionOut,
)
from ._generated.types import UNSET, File
from ._http import ProgressReader, expect_no_content, raise_for_problem, sse_events, unwrap
from ._results import ResultsMixin
from .errors import JobFailed

#: States after which a job never changes again.
FINAL_STATES = frozenset({"succeeded", "failed", "cancelled"})
#: Seconds between polls when the event stream is not used.
POLL_INTERVAL_S = 0.5


@dataclass(frozen=True)
class JobProgress:
    """A `stage` or `progress` event of a job: its stage and 0..1 overall.
    (The document types the frame only as `{event, data}`, so this shape
    is the one the events' description gives.)"""

    stage: str | None
    progress: float


class Client(ResultsMixin, AdminMixin, Base):
    """A robocal service at `base_url`, with a bearer `token` when the
    service has tokens (anonymous access is allowed only on loopback)."""

    # Robots -----------------------------------------------------------
    def put_robot(self, serial: str, body: RobotBody | Mapping[str, Any]) -> RobotOut:
        """Create or replace a robot (its model, preset or kinematics)."""
        return unwrap(put_robot.sync_detailed(serial, client=self.api, body=as_model(RobotBody, body)), RobotOut)

    def get_robot(self, serial: str) -> RobotOut:
        return unwrap(get_robot.sync_detailed(serial, client=self.api), RobotOut)

    def list_robots(self, limit: int | None = None, cursor: str | None = None) -> RobotList:
        answer = list_robots.sync_detailed(client=self.api, limit=opt(limit), cursor=opt(cursor))
        return unwrap(answer, RobotList)

    def delete_robot(self, serial: str) -> None:
        expect_no_content(delete_robot.sync_detailed(serial, client=self.api))

    # Sessions ---------------------------------------------------------
    def create_session(self, serial: str, body: SessionBody | Mapping[str, Any]) -> SessionOut:
        """A measurement session of the robot (instrument, target, camera)."""
        answer = create_session.sync_detailed(serial, client=self.api, body=as_model(SessionBody, body))
        return unwrap(answer, SessionOut)

    def get_session(self, session_id: str) -> SessionOut:
        return unwrap(get_session.sync_detailed(session_id, client=self.api), SessionOut)

    def list_sessions(self, serial: str, limit: int | None = None, cursor: str | None = None) -> SessionList:
        answer = list_sessions.sync_detailed(serial, client=self.api, limit=opt(limit), cursor=opt(cursor))
        return unwrap(answer, SessionList)

    # Poses and datasets -----------------------------------------------
    def add_pose_image(
        self,
        session_id: str,
        image: str | Path,
        joints_deg: list[float],
        pose_set: str = "cal",
    ) -> PoseOut:
        """One pose as multipart: the joint angles and the camera image."""
        with open(image, "rb") as payload:
            body = PoseImageUpload(
                image=File(payload=payload, file_name=Path(image).name, mime_type="image/png"),
                joints_deg=json.dumps(joints_deg),
                set_=PoseSet(pose_set),
            )
            return unwrap(add_pose.sync_detailed(session_id, client=self.api, body=body), PoseOut)

    def add_pose(self, session_id: str, body: PoseJsonBody | Mapping[str, Any]) -> PoseOut:
        """One pose as JSON (detected image points or a tracker measurement)."""
        answer = add_pose.sync_detailed(session_id, client=self.api, body=as_model(PoseJsonBody, body))
        return unwrap(answer, PoseOut)

    def list_poses(self, session_id: str, limit: int | None = None, cursor: str | None = None) -> PoseList:
        answer = list_poses.sync_detailed(session_id, client=self.api, limit=opt(limit), cursor=opt(cursor))
        return unwrap(answer, PoseList)

    def upload_dataset(
        self,
        session_id: str,
        archive: str | Path,
        progress: Callable[[int, int], None] | None = None,
    ) -> DatasetOut:
        """A zip (`poses.json` and images) streamed from disk in chunks;
        `progress(sent_bytes, total_bytes)` is called after each chunk."""
        reader = ProgressReader(str(archive), progress)
        # The generated request (path, content type), with a streamed body.
        kwargs = upload_dataset._get_kwargs(session_id, body=File(payload=open(archive, "rb")))
        kwargs["content"].close()
        kwargs["content"] = iter(reader)
        kwargs["headers"] = {**kwargs["headers"], "Content-Length": str(reader.total)}
        response = self.http.request(**kwargs)
        raise_for_problem(response)
        return DatasetOut.from_dict(response.json())

    # Jobs -------------------------------------------------------------
    def calibrate(self, session_id: str, options: CalibrationOptions | Mapping[str, Any] | None = None) -> JobAccepted:
        """Queue a calibration of the session; `wait` for it."""
        body = UNSET if options is None else as_model(CalibrationOptions, options)
        return unwrap(start_calibration.sync_detailed(session_id, client=self.api, body=body), JobAccepted)

    def get_job(self, job_id: str) -> JobOut:
        return unwrap(get_job.sync_detailed(job_id, client=self.api), JobOut)

    def list_jobs(
        self, state: str | None = None, serial: str | None = None, kind: str | None = None, limit: int | None = None
    ) -> JobList:
        answer = list_jobs.sync_detailed(
            client=self.api, state=opt(state), serial=opt(serial), kind=opt(kind), limit=opt(limit)
        )
        return unwrap(answer, JobList)

    def cancel_job(self, job_id: str) -> JobOut:
        return unwrap(cancel_job.sync_detailed(job_id, client=self.api), JobOut)

    def job_events(self, job_id: str) -> Iterator[JobProgress | JobOut]:
        """The job's Server-Sent Events: `JobProgress` while it runs, then
        the finished `JobOut` (the stream closes after it)."""
        for event, data in sse_events(self.http, f"/v1/jobs/{job_id}/events"):
            parsed = json.loads(data)
            if event == "end":
                yield JobOut.from_dict(parsed)
                return
            if event in ("stage", "progress"):
                yield JobProgress(parsed.get("stage"), float(parsed.get("progress", 0.0)))

    def wait(
        self,
        job_id: str,
        timeout_s: float = 600.0,
        on_progress: Callable[[JobProgress], None] | None = None,
        stream: bool = True,
    ) -> JobOut:
        """The job once finished; `JobFailed` unless it succeeded. Follows
        the event stream (`stream=True`) or polls, calling `on_progress`."""
        deadline = time.monotonic() + timeout_s
        if stream:
            try:
                for item in self.job_events(job_id):
                    if isinstance(item, JobOut):
                        return finished(item)
                    if on_progress is not None:
                        on_progress(item)
                    if time.monotonic() > deadline:
                        break
            except httpx.TransportError:
                pass  # a dropped stream: fall back to polling below
        while True:
            job = self.get_job(job_id)
            if job.state in FINAL_STATES:
                return finished(job)
            if on_progress is not None:
                on_progress(JobProgress(opt_str(job.stage), job.progress))
            if time.monotonic() > deadline:
                raise TimeoutError(f"job {job_id} still {job.state} after {timeout_s} s")
            time.sleep(POLL_INTERVAL_S)


def finished(job: JobOut) -> JobOut:
    if job.state != "succeeded":
        raise JobFailed(job.id, job.state, opt_str(job.error))
    return job


def opt(value: Any) -> Any:
    """`None` as the generator's `UNSET` (an absent query parameter)."""
    return UNSET if value is None else value


def opt_str(value: object) -> str | None:
    return value if isinstance(value, str) else None
