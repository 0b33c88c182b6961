from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="JobEventFrame")



@_attrs_define
class JobEventFrame:
    """ One Server-Sent Event of `GET /v1/jobs/{id}/events`, as a client's SSE
    parser sees it: its name and its `data` line (a JSON document).

        Attributes:
            event (str): `stage` (`data`: `{"stage", "progress"}`) when the job enters a
                stage, `progress` (same `data`) as it advances, `end` (`data`: the
                job, as `GET /v1/jobs/{id}` answers) when it ended; the stream then
                closes.
            data (str): The event's JSON document, as text.
     """

    event: str
    data: str
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        event = self.event

        data = self.data


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "event": event,
            "data": data,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        event = d.pop("event")

        data = d.pop("data")

        job_event_frame = cls(
            event=event,
            data=data,
        )


        job_event_frame.additional_properties = d
        return job_event_frame

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
