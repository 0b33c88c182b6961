"""The connection shared by `Client` and its mixins."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol, TypeVar

import httpx

from ._generated.client import AuthenticatedClient
from ._generated.client import Client as AnonymousClient

#: Seconds a request may take (a dataset upload or a large compensate
#: stream included); calibrations run as jobs, not inside a request.
DEFAULT_TIMEOUT_S = 300.0


class FromDict(Protocol):
    @classmethod
    def from_dict(cls: type[M], src_dict: Mapping[str, Any]) -> M: ...


M = TypeVar("M", bound=FromDict)


def as_model(model: type[M], body: M | Mapping[str, Any]) -> M:
    """A request body given as the generated model or as plain JSON data
    (as `campaign.json` holds it), checked into the model."""
    if isinstance(body, Mapping):
        return model.from_dict(body)
    return body


class Base:
    """Holds the generated client (typed endpoints) and its httpx client
    (for streamed requests the generator reads whole)."""

    def __init__(self, base_url: str, token: str | None = None, timeout_s: float = DEFAULT_TIMEOUT_S) -> None:
        timeout = httpx.Timeout(timeout_s)
        self.api: AuthenticatedClient | AnonymousClient
        if token is None:
            self.api = AnonymousClient(base_url=base_url.rstrip("/"), timeout=timeout)
        else:
            self.api = AuthenticatedClient(base_url=base_url.rstrip("/"), token=token, timeout=timeout)

    @property
    def http(self) -> httpx.Client:
        return self.api.get_httpx_client()

    def close(self) -> None:
        self.http.close()

    def __enter__(self: B) -> B:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


B = TypeVar("B", bound=Base)
