from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.release_status import ReleaseStatus
from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ParameterSetIdentity")



@_attrs_define
class ParameterSetIdentity:
    """ Where a served parameter set stands: its robot, version, job and
    release status.

        Attributes:
            serial (str):
            version (int):
            created_at (str):
            status (ReleaseStatus):
            job_id (None | str | Unset):
            status_reason (None | str | Unset): Why it has its status (the gate's comparison, or a person's reason).
            status_by (None | str | Unset): Who gave it (`gate`, `token:{id} ({name})`, `anonymous`; `null` for
                sets approved when the gate was introduced) and when.
            status_at (None | str | Unset):
     """

    serial: str
    version: int
    created_at: str
    status: ReleaseStatus
    job_id: None | str | Unset = UNSET
    status_reason: None | str | Unset = UNSET
    status_by: None | str | Unset = UNSET
    status_at: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        serial = self.serial

        version = self.version

        created_at = self.created_at

        status = self.status.value

        job_id: None | str | Unset
        if isinstance(self.job_id, Unset):
            job_id = UNSET
        else:
            job_id = self.job_id

        status_reason: None | str | Unset
        if isinstance(self.status_reason, Unset):
            status_reason = UNSET
        else:
            status_reason = self.status_reason

        status_by: None | str | Unset
        if isinstance(self.status_by, Unset):
            status_by = UNSET
        else:
            status_by = self.status_by

        status_at: None | str | Unset
        if isinstance(self.status_at, Unset):
            status_at = UNSET
        else:
            status_at = self.status_at


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "serial": serial,
            "version": version,
            "created_at": created_at,
            "status": status,
        })
        if job_id is not UNSET:
            field_dict["job_id"] = job_id
        if status_reason is not UNSET:
            field_dict["status_reason"] = status_reason
        if status_by is not UNSET:
            field_dict["status_by"] = status_by
        if status_at is not UNSET:
            field_dict["status_at"] = status_at

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        serial = d.pop("serial")

        version = d.pop("version")

        created_at = d.pop("created_at")

        status = ReleaseStatus(d.pop("status"))




        def _parse_job_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        job_id = _parse_job_id(d.pop("job_id", UNSET))


        def _parse_status_reason(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_reason = _parse_status_reason(d.pop("status_reason", UNSET))


        def _parse_status_by(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_by = _parse_status_by(d.pop("status_by", UNSET))


        def _parse_status_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_at = _parse_status_at(d.pop("status_at", UNSET))


        parameter_set_identity = cls(
            serial=serial,
            version=version,
            created_at=created_at,
            status=status,
            job_id=job_id,
            status_reason=status_reason,
            status_by=status_by,
            status_at=status_at,
        )


        parameter_set_identity.additional_properties = d
        return parameter_set_identity

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
