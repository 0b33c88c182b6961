"""The whole job through the client against the real server: upload,
calibrate, wait, the typed report, compensate (streamed), export."""

from __future__ import annotations

import math

from conftest import Calibrated, campaign_files

from robocal_client import FINAL_STATES, models


def test_upload_reports_progress_to_the_full_size(calibrated: Calibrated) -> None:
    sent = [s for s, _ in calibrated.upload_progress]
    total = calibrated.upload_progress[-1][1]
    assert sent == sorted(sent) and sent[-1] == total > 0


def test_wait_followed_the_event_stream(calibrated: Calibrated) -> None:
    assert calibrated.progress_seen, "no progress event before the end"
    assert all(0.0 <= p <= 1.0 for p in calibrated.progress_seen)
    job = calibrated.client.get_job(calibrated.job_id)
    assert job.state in FINAL_STATES and job.progress == 1.0


def test_report_is_typed_and_calibration_improves(calibrated: Calibrated) -> None:
    report = calibrated.client.report(calibrated.serial)
    assert isinstance(report, models.Report)
    assert isinstance(report.after, models.AccuracySummary)
    assert report.after.mean_mm < report.before.mean_mm
    assert report.after.n > 0 and report.per_pose


def test_parameter_set_and_list(calibrated: Calibrated) -> None:
    latest = calibrated.client.get_parameter_set(calibrated.serial)
    assert isinstance(latest, models.KinematicSetOut)
    assert latest.version == 1
    assert isinstance(latest.kinematics, models.KinematicsDoc) and len(latest.kinematics.joints) == 6
    listed = calibrated.client.list_parameter_sets(calibrated.serial)
    assert 1 in [item.version for item in listed.items]


def test_compensate_streams_one_line_per_target(calibrated: Calibrated) -> None:
    client = calibrated.client
    _, poses = campaign_files(calibrated.campaign)
    joints = [p["joints_deg"] for p in poses[:3]]
    # Targets the arm reaches: where the calibrated model puts the flange
    # camera at known joints (the camera is the tool, in the board frame).
    served = client.get_parameter_set(calibrated.serial)
    assert isinstance(served, models.KinematicSetOut)
    camera = served.flange_to_camera
    assert isinstance(camera, models.FramePose)
    tool = {"translation_mm": camera.translation_mm, "rotation_deg": camera.rotation_deg}
    forward = client.forward(calibrated.serial, {"joints_deg": joints, "tool": tool})
    targets = [{"translation_mm": p.camera_in_target.translation_mm, "rotation_deg": p.camera_in_target.rotation_deg}
               for p in forward.poses]
    request = {"targets": targets, "tool": tool, "seed_joints_deg": joints}
    lines = list(client.compensate_stream(calibrated.serial, request))
    assert [line.index for line in lines] == [0, 1, 2]
    for line in lines:
        assert isinstance(line, models.CompensateLine)
        assert isinstance(line.residual_mm, float) and line.residual_mm < 0.01, line
        assert isinstance(line.joints_deg, list) and len(line.joints_deg) == 6
        assert all(math.isfinite(j) for j in line.joints_deg)
    whole = client.compensate(calibrated.serial, request)
    assert len(whole.joints_deg) == len(lines) and whole.errors == []
    filtered = list(client.filter_stream(calibrated.serial, {**request, "seed_joints_deg": joints[0]}))
    assert [line.index for line in filtered] == [0, 1, 2]
    assert all(isinstance(line.nominal_target, models.FramePose) for line in filtered), filtered


def test_exports(calibrated: Calibrated) -> None:
    urdf = calibrated.client.export(calibrated.serial, format="urdf")
    assert "<robot" in urdf and "joint" in urdf
    csv = calibrated.client.export(calibrated.serial, format="csv")
    assert len(csv.strip().splitlines()) == 7  # header and six joints
