from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.parameter_change import ParameterChange





T = TypeVar("T", bound="HistoryVersion")



@_attrs_define
class HistoryVersion:
    """ One approved version in a history.

        Attributes:
            version (int):
            created_at (str):
            changes (list[ParameterChange]): Each kinematic parameter's change from the previous approved version.
            job_id (None | str | Unset):
            approved_by (None | str | Unset): Who approved it (`gate`, a token, `anonymous`; `null` for sets
                approved by the migration that introduced the gate) and when.
            approved_at (None | str | Unset):
            reason (None | str | Unset):
     """

    version: int
    created_at: str
    changes: list[ParameterChange]
    job_id: None | str | Unset = UNSET
    approved_by: None | str | Unset = UNSET
    approved_at: None | str | Unset = UNSET
    reason: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.parameter_change import ParameterChange # noqa: PLC0415
        version = self.version

        created_at = self.created_at

        changes = []
        for changes_item_data in self.changes:
            changes_item = changes_item_data.to_dict()
            changes.append(changes_item)



        job_id: None | str | Unset
        if isinstance(self.job_id, Unset):
            job_id = UNSET
        else:
            job_id = self.job_id

        approved_by: None | str | Unset
        if isinstance(self.approved_by, Unset):
            approved_by = UNSET
        else:
            approved_by = self.approved_by

        approved_at: None | str | Unset
        if isinstance(self.approved_at, Unset):
            approved_at = UNSET
        else:
            approved_at = self.approved_at

        reason: None | str | Unset
        if isinstance(self.reason, Unset):
            reason = UNSET
        else:
            reason = self.reason


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "version": version,
            "created_at": created_at,
            "changes": changes,
        })
        if job_id is not UNSET:
            field_dict["job_id"] = job_id
        if approved_by is not UNSET:
            field_dict["approved_by"] = approved_by
        if approved_at is not UNSET:
            field_dict["approved_at"] = approved_at
        if reason is not UNSET:
            field_dict["reason"] = reason

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.parameter_change import ParameterChange # noqa: PLC0415
        d = dict(src_dict)
        version = d.pop("version")

        created_at = d.pop("created_at")

        changes = []
        _changes = d.pop("changes")
        for changes_item_data in (_changes):
            changes_item = ParameterChange.from_dict(changes_item_data)



            changes.append(changes_item)


        def _parse_job_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        job_id = _parse_job_id(d.pop("job_id", UNSET))


        def _parse_approved_by(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        approved_by = _parse_approved_by(d.pop("approved_by", UNSET))


        def _parse_approved_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        approved_at = _parse_approved_at(d.pop("approved_at", UNSET))


        def _parse_reason(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        reason = _parse_reason(d.pop("reason", UNSET))


        history_version = cls(
            version=version,
            created_at=created_at,
            changes=changes,
            job_id=job_id,
            approved_by=approved_by,
            approved_at=approved_at,
            reason=reason,
        )


        history_version.additional_properties = d
        return history_version

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
