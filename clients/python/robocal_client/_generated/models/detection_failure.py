from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset






T = TypeVar("T", bound="DetectionFailure")



@_attrs_define
class DetectionFailure:
    """ 
        Attributes:
            pose_id (str):
            reason (str):
            label (str | Unset): The pose's label (see [`PoseReport::label`]).
     """

    pose_id: str
    reason: str
    label: str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        pose_id = self.pose_id

        reason = self.reason

        label = self.label


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "pose_id": pose_id,
            "reason": reason,
        })
        if label is not UNSET:
            field_dict["label"] = label

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        pose_id = d.pop("pose_id")

        reason = d.pop("reason")

        label = d.pop("label", UNSET)

        detection_failure = cls(
            pose_id=pose_id,
            reason=reason,
            label=label,
        )


        detection_failure.additional_properties = d
        return detection_failure

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
