"""Typed exceptions for the service's problem+json answers (RFC 9457).

Every 4xx/5xx the service sends is `application/problem+json` with a
`title`, `detail` and, for bad input, `errors` naming each offending field;
the client raises them as `ProblemError` so a caller can `except` on status
and read which field was refused.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class FieldProblem:
    """One refused field: its JSON path (`body.joints_deg[2]`) and why."""

    field: str
    message: str


class ProblemError(Exception):
    """An error answer of the service (problem+json), or an answer the
    client did not expect (then `title` is the HTTP reason)."""

    def __init__(
        self,
        status: int,
        title: str,
        detail: str = "",
        errors: list[FieldProblem] | None = None,
        type_: str = "about:blank",
        body: dict[str, Any] | None = None,
    ) -> None:
        self.status = status
        self.title = title
        self.detail = detail
        self.errors: list[FieldProblem] = list(errors or [])
        self.type = type_
        self.body: dict[str, Any] = dict(body or {})
        fields = "; ".join(f"{e.field}: {e.message}" for e in self.errors)
        super().__init__(f"{status} {title}: {detail}" + (f" [{fields}]" if fields else ""))

    def field_names(self) -> list[str]:
        """The refused fields, in the order the service named them."""
        return [e.field for e in self.errors]

    @classmethod
    def from_answer(cls, status: int, content: bytes, reason: str = "") -> ProblemError:
        """Parses a problem+json body; any other body keeps the status and
        its first bytes as detail, so nothing the server said is lost."""
        try:
            parsed = json.loads(content.decode("utf-8")) if content else None
        except (UnicodeDecodeError, json.JSONDecodeError):
            parsed = None
        if not isinstance(parsed, dict):
            text = content[:500].decode("utf-8", "replace")
            return cls(status, reason or "unexpected answer", text)
        raw_errors = parsed.get("errors")
        errors = [
            FieldProblem(str(e.get("field", "")), str(e.get("message", "")))
            for e in (raw_errors if isinstance(raw_errors, list) else [])
            if isinstance(e, dict)
        ]
        return cls(
            status=int(parsed.get("status", status)),
            title=str(parsed.get("title", reason)),
            detail=str(parsed.get("detail", "")),
            errors=errors,
            type_=str(parsed.get("type", "about:blank")),
            body=parsed,
        )


class JobFailed(Exception):
    """`Client.wait` saw the job end other than `succeeded`."""

    def __init__(self, job_id: str, state: str, error: str | None) -> None:
        self.job_id = job_id
        self.state = state
        self.error = error
        super().__init__(f"job {job_id} {state}: {error or 'no error given'}")
