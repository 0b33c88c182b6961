from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.job_kind import JobKind
from ..models.job_state import JobState
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.calibration_options import CalibrationOptions
  from ..models.calibration_result import CalibrationResult
  from ..models.check_options import CheckOptions
  from ..models.check_result import CheckResult





T = TypeVar("T", bound="JobAccepted")



@_attrs_define
class JobAccepted:
    """ 
        Attributes:
            id (str):
            kind (JobKind): What a job does: `calibration` (identify a parameter set) or `check`
                (judge a short session against the latest approved set).
            session_id (str):
            serial (str):
            state (JobState):
            progress (float): 0..1 over the whole job.
            attempts (int):
            max_attempts (int):
            options (CalibrationOptions | CheckOptions): A job's `options`, by its `kind`: a calibration's request body, or
                a re-check's (empty).
            created_at (str):
            job_id (str):
            stage (None | str | Unset):
            error (None | str | Unset):
            result (CalibrationResult | CheckResult | None | Unset):
            started_at (None | str | Unset):
            finished_at (None | str | Unset):
     """

    id: str
    kind: JobKind
    session_id: str
    serial: str
    state: JobState
    progress: float
    attempts: int
    max_attempts: int
    options: CalibrationOptions | CheckOptions
    created_at: str
    job_id: str
    stage: None | str | Unset = UNSET
    error: None | str | Unset = UNSET
    result: CalibrationResult | CheckResult | None | Unset = UNSET
    started_at: None | str | Unset = UNSET
    finished_at: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.calibration_options import CalibrationOptions # noqa: PLC0415
        from ..models.calibration_result import CalibrationResult # noqa: PLC0415
        from ..models.check_options import CheckOptions # noqa: PLC0415
        from ..models.check_result import CheckResult # noqa: PLC0415
        id = self.id

        kind = self.kind.value

        session_id = self.session_id

        serial = self.serial

        state = self.state.value

        progress = self.progress

        attempts = self.attempts

        max_attempts = self.max_attempts

        options: dict[str, Any]
        if isinstance(self.options, CalibrationOptions):
            options = self.options.to_dict()
        else:
            options = self.options.to_dict()


        created_at = self.created_at

        job_id = self.job_id

        stage: None | str | Unset
        if isinstance(self.stage, Unset):
            stage = UNSET
        else:
            stage = self.stage

        error: None | str | Unset
        if isinstance(self.error, Unset):
            error = UNSET
        else:
            error = self.error

        result: dict[str, Any] | None | Unset
        if isinstance(self.result, Unset):
            result = UNSET
        elif isinstance(self.result, CheckResult):
            result = self.result.to_dict()
        elif isinstance(self.result, CalibrationResult):
            result = self.result.to_dict()
        else:
            result = self.result

        started_at: None | str | Unset
        if isinstance(self.started_at, Unset):
            started_at = UNSET
        else:
            started_at = self.started_at

        finished_at: None | str | Unset
        if isinstance(self.finished_at, Unset):
            finished_at = UNSET
        else:
            finished_at = self.finished_at


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "id": id,
            "kind": kind,
            "session_id": session_id,
            "serial": serial,
            "state": state,
            "progress": progress,
            "attempts": attempts,
            "max_attempts": max_attempts,
            "options": options,
            "created_at": created_at,
            "job_id": job_id,
        })
        if stage is not UNSET:
            field_dict["stage"] = stage
        if error is not UNSET:
            field_dict["error"] = error
        if result is not UNSET:
            field_dict["result"] = result
        if started_at is not UNSET:
            field_dict["started_at"] = started_at
        if finished_at is not UNSET:
            field_dict["finished_at"] = finished_at

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.calibration_options import CalibrationOptions # noqa: PLC0415
        from ..models.calibration_result import CalibrationResult # noqa: PLC0415
        from ..models.check_options import CheckOptions # noqa: PLC0415
        from ..models.check_result import CheckResult # noqa: PLC0415
        d = dict(src_dict)
        id = d.pop("id")

        kind = JobKind(d.pop("kind"))




        session_id = d.pop("session_id")

        serial = d.pop("serial")

        state = JobState(d.pop("state"))




        progress = d.pop("progress")

        attempts = d.pop("attempts")

        max_attempts = d.pop("max_attempts")

        def _parse_options(data: object) -> CalibrationOptions | CheckOptions:
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                componentsschemas_job_options_type_0 = CalibrationOptions.from_dict(data)



                return componentsschemas_job_options_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            if not isinstance(data, dict):
                raise TypeError()
            componentsschemas_job_options_type_1 = CheckOptions.from_dict(data)



            return componentsschemas_job_options_type_1

        options = _parse_options(d.pop("options"))


        created_at = d.pop("created_at")

        job_id = d.pop("job_id")

        def _parse_stage(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        stage = _parse_stage(d.pop("stage", UNSET))


        def _parse_error(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        error = _parse_error(d.pop("error", UNSET))


        def _parse_result(data: object) -> CalibrationResult | CheckResult | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                componentsschemas_job_result_type_0 = CheckResult.from_dict(data)



                return componentsschemas_job_result_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                componentsschemas_job_result_type_1 = CalibrationResult.from_dict(data)



                return componentsschemas_job_result_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(CalibrationResult | CheckResult | None | Unset, data)

        result = _parse_result(d.pop("result", UNSET))


        def _parse_started_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        started_at = _parse_started_at(d.pop("started_at", UNSET))


        def _parse_finished_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        finished_at = _parse_finished_at(d.pop("finished_at", UNSET))


        job_accepted = cls(
            id=id,
            kind=kind,
            session_id=session_id,
            serial=serial,
            state=state,
            progress=progress,
            attempts=attempts,
            max_attempts=max_attempts,
            options=options,
            created_at=created_at,
            job_id=job_id,
            stage=stage,
            error=error,
            result=result,
            started_at=started_at,
            finished_at=finished_at,
        )


        job_accepted.additional_properties = d
        return job_accepted

    @property
    def additional_keys(self) -> list[str]:
        return list(self.additional_properties.keys())

    def __getitem__(self, key: str) -> Any:
        return self.additional_properties[key]

    def __setitem__(self, key: str, value: Any) -> None:
        self.additional_properties[key] = value

    def __delitem__(self, key: str) -> None:
        del self.additional_properties[key]

    def __contains__(self, key: str) -> bool:
        return key in self.additional_properties
