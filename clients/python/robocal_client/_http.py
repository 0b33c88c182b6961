"""Turning generated answers into models or `ProblemError`, and the
streamed bodies (NDJSON lines, Server-Sent Events) the generator reads
whole."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from typing import Any, TypeVar

import httpx

from ._generated.types import Response
from .errors import ProblemError

T = TypeVar("T")

#: First status of an error answer.
FIRST_ERROR_STATUS = 400


def unwrap(answer: Response[Any], model: type[T]) -> T:
    """The parsed answer when it is `model`; otherwise the answer's problem
    raised as `ProblemError` (also for a success status the document does
    not list, so a schema drift is never silently a `None`)."""
    parsed = answer.parsed
    if int(answer.status_code) < FIRST_ERROR_STATUS and isinstance(parsed, model):
        return parsed
    raise ProblemError.from_answer(int(answer.status_code), answer.content, answer.status_code.phrase)


def expect_no_content(answer: Response[Any]) -> None:
    """A 2xx without a body (deletes, revocations), else `ProblemError`."""
    if int(answer.status_code) >= FIRST_ERROR_STATUS:
        raise ProblemError.from_answer(int(answer.status_code), answer.content, answer.status_code.phrase)


def raise_for_problem(response: httpx.Response) -> None:
    """`ProblemError` for a streamed error answer (its body read first)."""
    if response.status_code >= FIRST_ERROR_STATUS:
        response.read()
        raise ProblemError.from_answer(response.status_code, response.content, response.reason_phrase)


def ndjson_lines(
    http: httpx.Client, kwargs: dict[str, Any], parse: Callable[[dict[str, Any]], T]
) -> Iterator[T]:
    """Sends the generated request with `Accept: application/x-ndjson` and
    yields one parsed model per line as the server writes it."""
    headers = {**kwargs.pop("headers", {}), "Accept": "application/x-ndjson"}
    with http.stream(**kwargs, headers=headers) as response:
        raise_for_problem(response)
        for line in response.iter_lines():
            if line.strip():
                yield parse(json.loads(line))


def sse_events(http: httpx.Client, url: str) -> Iterator[tuple[str, str]]:
    """`(event, data)` pairs of a Server-Sent Events stream, until it closes."""
    with http.stream("GET", url, headers={"Accept": "text/event-stream"}) as response:
        raise_for_problem(response)
        event, data = "message", list[str]()
        for line in response.iter_lines():
            if not line:
                if data:
                    yield event, "\n".join(data)
                event, data = "message", []
            elif line.startswith(":"):
                continue
            else:
                name, _, value = line.partition(":")
                value = value[1:] if value.startswith(" ") else value
                if name == "event":
                    event = value
                elif name == "data":
                    data.append(value)
        if data:
            yield event, "\n".join(data)


class ProgressReader:
    """A file read in chunks for an upload, reporting `(sent, total)` bytes
    after each chunk so a caller can show progress of a large archive."""

    CHUNK_BYTES = 1 << 20

    def __init__(self, path: str, progress: Callable[[int, int], None] | None) -> None:
        self.path = path
        self.progress = progress
        with open(path, "rb") as f:
            self.total = f.seek(0, 2)

    def __iter__(self) -> Iterator[bytes]:
        sent = 0
        with open(self.path, "rb") as f:
            while chunk := f.read(self.CHUNK_BYTES):
                sent += len(chunk)
                yield chunk
                if self.progress is not None:
                    self.progress(sent, self.total)
