"""Release decisions over the client: a second calibration of the same
session is a new version; rejecting it leaves `latest` on the first."""

from __future__ import annotations

import pytest
from conftest import Calibrated

from robocal_client import ProblemError


def test_reject_a_new_version_keeps_latest(calibrated: Calibrated) -> None:
    client = calibrated.client
    job = client.wait(client.calibrate(calibrated.session_id).job_id)
    assert job.state == "succeeded"
    versions = sorted(item.version for item in client.list_parameter_sets(calibrated.serial).items)
    newest = versions[-1]
    assert newest >= 2, versions
    rejected = client.reject(calibrated.serial, newest, "second run of the same data")
    assert rejected.status == "rejected" and rejected.version == newest
    assert client.get_parameter_set(calibrated.serial).version < newest
    with pytest.raises(ProblemError) as raised:
        client.approve(calibrated.serial, 999)
    assert raised.value.status == 404
