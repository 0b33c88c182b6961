"""Parameter sets and what is done with them: the typed report, exports,
forward kinematics, compensation and filtering (streamed as NDJSON), and
the release decisions (approve / reject)."""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

from ._base import Base, as_model
from ._generated.api.results import (
    approve,
    compensate,
    export_parameter_set,
    filter_targets,
    forward,
    get_parameter_set,
    get_report,
    get_report_svg,
    history,
    list_parameter_sets,
    reject,
)
from ._generated.models import (
    CompensateLine,
    CompensateRequest,
    CompensateResponse,
    DecisionBody,
    FilterLine,
    FilterRequest,
    ForwardRequest,
    ForwardResponse,
    History,
    HandEyeSetOut,
    KinematicSetOut,
    ParameterSetList,
    Report,
    StageCameraSetOut,
)
from ._generated.types import UNSET, Response
from ._http import FIRST_ERROR_STATUS, ndjson_lines, unwrap
from .errors import ProblemError

ParameterSetOut = KinematicSetOut | HandEyeSetOut | StageCameraSetOut
"""A served parameter set: its `kind` (`kinematic`, `hand_eye`,
`stage_camera`) says which."""



def _parameter_set(answer: Response[Any]) -> ParameterSetOut:
    """The served set (one of the three kinds), else `ProblemError`."""
    parsed = answer.parsed
    ok = int(answer.status_code) < FIRST_ERROR_STATUS
    if ok and isinstance(parsed, (KinematicSetOut, HandEyeSetOut, StageCameraSetOut)):
        return parsed
    raise ProblemError.from_answer(int(answer.status_code), answer.content, answer.status_code.phrase)

Version = int | str
"""A parameter-set version: a number or `"latest"`."""


class ResultsMixin(Base):
    def list_parameter_sets(self, serial: str, limit: int | None = None) -> ParameterSetList:
        answer = list_parameter_sets.sync_detailed(serial, client=self.api, limit=UNSET if limit is None else limit)
        return unwrap(answer, ParameterSetList)

    def get_parameter_set(self, serial: str, version: Version = "latest") -> ParameterSetOut:
        return _parameter_set(get_parameter_set.sync_detailed(serial, str(version), client=self.api))

    def report(self, serial: str, version: Version = "latest", compare: Version | None = None) -> Report:
        """The accuracy report: `before`/`after` validation errors (mm),
        per-pose residuals, parameters with their uncertainty."""
        answer = get_report.sync_detailed(
            serial, str(version), client=self.api, compare=UNSET if compare is None else str(compare)
        )
        return unwrap(answer, Report)

    def report_svg(self, serial: str, version: Version = "latest") -> str:
        return unwrap(get_report_svg.sync_detailed(serial, str(version), client=self.api), str)

    def export(
        self, serial: str, version: Version = "latest", format: str = "urdf", controller_serial: str | None = None
    ) -> str:
        """The set in a controller's or tool's format (`urdf`, `dh-json`,
        `csv`, `ur-kinematics`, `dh-table`, `krl-frames`, `rapid-frames`)."""
        answer = export_parameter_set.sync_detailed(
            serial,
            str(version),
            client=self.api,
            format_=format,
            controller_serial=UNSET if controller_serial is None else controller_serial,
        )
        return unwrap(answer, str)

    def history(self, serial: str) -> History:
        return unwrap(history.sync_detailed(serial, client=self.api), History)

    def forward(
        self, serial: str, body: ForwardRequest | Mapping[str, Any], version: Version = "latest"
    ) -> ForwardResponse:
        """Calibrated tool poses of joint vectors."""
        answer = forward.sync_detailed(serial, str(version), client=self.api, body=as_model(ForwardRequest, body))
        return unwrap(answer, ForwardResponse)

    def compensate(
        self, serial: str, body: CompensateRequest | Mapping[str, Any], version: Version = "latest"
    ) -> CompensateResponse:
        """Joints that reach each target under the calibrated model (whole)."""
        answer = compensate.sync_detailed(serial, str(version), client=self.api, body=as_model(CompensateRequest, body))
        return unwrap(answer, CompensateResponse)

    def compensate_stream(
        self, serial: str, body: CompensateRequest | Mapping[str, Any], version: Version = "latest"
    ) -> Iterator[CompensateLine]:
        """As `compensate`, one `CompensateLine` per target as the server
        solves it (NDJSON), for target lists too long to hold at once."""
        kwargs = compensate._get_kwargs(serial, str(version), body=as_model(CompensateRequest, body))
        return ndjson_lines(self.http, kwargs, CompensateLine.from_dict)

    def filter_stream(
        self, serial: str, body: FilterRequest | Mapping[str, Any], version: Version = "latest"
    ) -> Iterator[FilterLine]:
        """Nominal targets a controller should be sent so the tool lands on
        the given ones, streamed one `FilterLine` per target."""
        kwargs = filter_targets._get_kwargs(serial, str(version), body=as_model(FilterRequest, body))
        return ndjson_lines(self.http, kwargs, FilterLine.from_dict)

    def approve(self, serial: str, version: Version, reason: str | None = None) -> ParameterSetOut:
        """Release the set for production (a `release` scope)."""
        body = DecisionBody(reason=UNSET if reason is None else reason)
        return _parameter_set(approve.sync_detailed(serial, str(version), client=self.api, body=body))

    def reject(self, serial: str, version: Version, reason: str) -> ParameterSetOut:
        body = DecisionBody(reason=reason)
        return _parameter_set(reject.sync_detailed(serial, str(version), client=self.api, body=body))
