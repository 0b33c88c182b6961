"""Tokens over the client: once tokens exist, anonymous access ends; an
admin token creates, lists and revokes others; a revoked token is refused."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from conftest import Server

from robocal_client import Client, ProblemError


def test_token_lifecycle(server_factory: Callable[[], Server]) -> None:
    server = server_factory()
    admin = Client(server.url, token=server.create_token("admin"))
    with pytest.raises(ProblemError) as anonymous:
        Client(server.url).list_robots()
    assert anonymous.value.status == 401

    created = admin.create_token("reader", "read")
    assert created.token and created.scope == "read"
    reader = Client(server.url, token=created.token)
    assert reader.list_robots().items == []
    with pytest.raises(ProblemError) as refused:
        reader.put_robot("PY-TOK-1", {"model": "PUMA560", "preset": "puma560"})
    assert refused.value.status == 403

    assert created.id in [t.id for t in admin.list_tokens().items]
    admin.revoke_token(created.id)
    with pytest.raises(ProblemError) as revoked:
        reader.list_robots()
    assert revoked.value.status == 401
