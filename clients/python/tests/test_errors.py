"""problem+json answers raised as `ProblemError` naming the field."""

from __future__ import annotations

import pytest
from conftest import Server

from robocal_client import Client, ProblemError


def test_unknown_preset_is_a_422_naming_the_field(server: Server) -> None:
    client = Client(server.url)
    with pytest.raises(ProblemError) as raised:
        client.put_robot("PY-BAD-1", {"model": "PUMA560", "preset": "no-such-arm"})
    assert raised.value.status == 422
    assert raised.value.title
    assert "preset" in raised.value.field_names(), raised.value.errors


def test_bad_export_format_names_format(server: Server, calibrated: object) -> None:
    client = Client(server.url)
    with pytest.raises(ProblemError) as raised:
        client.export("PY-TEST-1", format="no-such-format")
    assert raised.value.status == 422 and "format" in raised.value.field_names()


def test_missing_robot_is_a_404(server: Server) -> None:
    with pytest.raises(ProblemError) as raised:
        Client(server.url).get_robot("PY-NOBODY")
    assert raised.value.status == 404 and raised.value.errors == []
