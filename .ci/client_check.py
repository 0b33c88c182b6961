#!/usr/bin/env python3
"""A client generated from openapi/openapi.json (openapi-python-client) uses
the service end to end: creates a robot and a session, uploads one pose as
multipart and the rest of a simulated campaign as a zip, calibrates, then
reads the parameter set, the typed report and the SVG. Every answer must
parse into the generated (typed) models.

usage: client_check.py BASE_URL TOKEN CAMPAIGN_DIR   (run by .ci/openapi.sh)
"""
import io
import json
import sys
import time
import zipfile
from pathlib import Path

from robocal_client import AuthenticatedClient
from robocal_client.api.jobs import get_job, start_calibration
from robocal_client.api.poses import add_pose, upload_dataset
from robocal_client.api.results import get_parameter_set, get_report, get_report_svg
from robocal_client.api.robots import put_robot
from robocal_client.api.sessions import create_session
from robocal_client.models import (
    CalibrationResult,
    DatasetOut,
    JobAccepted,
    JobOut,
    KinematicSetOut,
    PoseImageUpload,
    PoseOut,
    PoseSet,
    Report,
    RobotBody,
    RobotOut,
    SessionBody,
    SessionOut,
)
from robocal_client.types import File

SERIAL = "PY-CLIENT-1"
JOB_TIMEOUT_S = 600


def expect(answer, model):
    """The parsed answer, which must be the documented model."""
    parsed = answer.parsed
    assert isinstance(parsed, model), f"{answer.status_code}: {answer.content[:500]!r}"
    return parsed


def main():
    base, token, campaign = sys.argv[1], sys.argv[2], Path(sys.argv[3])
    client = AuthenticatedClient(base_url=base, token=token, timeout=120)
    files = json.loads((campaign / "campaign.json").read_text())
    entries = json.loads((campaign / "poses.json").read_text())

    robot = expect(
        put_robot.sync_detailed(SERIAL, client=client, body=RobotBody.from_dict(files["robot"])),
        RobotOut,
    )
    assert len(robot.kinematics.joints) == 6
    session = expect(
        create_session.sync_detailed(
            SERIAL, client=client, body=SessionBody.from_dict(files["session"])
        ),
        SessionOut,
    )

    first, rest = entries[0], entries[1:]
    with open(campaign / first["image"], "rb") as image:
        upload = PoseImageUpload(
            joints_deg=json.dumps(first["joints_deg"]),
            image=File(payload=image, file_name=Path(first["image"]).name, mime_type="image/png"),
            set_=PoseSet(first["set"]),
        )
        pose = expect(add_pose.sync_detailed(session.id, client=client, body=upload), PoseOut)
    assert pose.source == "image", pose

    archive = io.BytesIO()
    with zipfile.ZipFile(archive, "w") as z:
        z.writestr("poses.json", json.dumps(rest))
        for entry in rest:
            z.write(campaign / entry["image"], entry["image"])
    archive.seek(0)
    dataset = expect(
        upload_dataset.sync_detailed(
            session.id, client=client, body=File(payload=archive, mime_type="application/zip")
        ),
        DatasetOut,
    )
    assert dataset.poses_created == len(rest), dataset

    accepted = expect(start_calibration.sync_detailed(session.id, client=client), JobAccepted)
    deadline = time.monotonic() + JOB_TIMEOUT_S
    while True:
        job = expect(get_job.sync_detailed(accepted.job_id, client=client), JobOut)
        if job.state in ("succeeded", "failed", "cancelled"):
            break
        assert time.monotonic() < deadline, f"job still {job.state}"
        time.sleep(0.5)
    assert job.state == "succeeded", job.error
    # The result is typed: a calibration's, naming the version it stored.
    assert isinstance(job.result, CalibrationResult), type(job.result)
    assert job.result.version == 1 and job.result.summary.calibration_poses > 0, job.result

    parameters = expect(
        get_parameter_set.sync_detailed(SERIAL, "latest", client=client), KinematicSetOut
    )
    assert parameters.version == 1 and len(parameters.kinematics.joints) == 6
    assert parameters.camera is not None and parameters.camera.fx > 0
    report = expect(get_report.sync_detailed(SERIAL, "latest", client=client), Report)
    assert report.after.mean_mm < report.before.mean_mm, (report.before, report.after)
    assert report.camera is not None and report.camera.fx > 0
    assert report.per_pose and report.parameters
    svg = get_report_svg.sync_detailed(SERIAL, "latest", client=client)
    assert svg.status_code == 200 and isinstance(svg.parsed, str), svg.status_code
    assert svg.parsed.lstrip().startswith("<svg") or "<svg" in svg.parsed[:200]
    print(
        f"client_check: {len(entries)} poses, validation mean "
        f"{report.before.mean_mm:.3f} -> {report.after.mean_mm:.3f} mm"
    )


if __name__ == "__main__":
    main()
