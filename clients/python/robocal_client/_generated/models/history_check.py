from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.check_doc import CheckDoc





T = TypeVar("T", bound="HistoryCheck")



@_attrs_define
class HistoryCheck:
    """ A finished re-check in a history.

        Attributes:
            job_id (str):
            session_id (str):
            check (CheckDoc): The re-check job's `result`.
            finished_at (None | str | Unset):
     """

    job_id: str
    session_id: str
    check: CheckDoc
    finished_at: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.check_doc import CheckDoc # noqa: PLC0415
        job_id = self.job_id

        session_id = self.session_id

        check = self.check.to_dict()

        finished_at: None | str | Unset
        if isinstance(self.finished_at, Unset):
            finished_at = UNSET
        else:
            finished_at = self.finished_at


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "job_id": job_id,
            "session_id": session_id,
            "check": check,
        })
        if finished_at is not UNSET:
            field_dict["finished_at"] = finished_at

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.check_doc import CheckDoc # noqa: PLC0415
        d = dict(src_dict)
        job_id = d.pop("job_id")

        session_id = d.pop("session_id")

        check = CheckDoc.from_dict(d.pop("check"))




        def _parse_finished_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        finished_at = _parse_finished_at(d.pop("finished_at", UNSET))


        history_check = cls(
            job_id=job_id,
            session_id=session_id,
            check=check,
            finished_at=finished_at,
        )


        history_check.additional_properties = d
        return history_check

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
