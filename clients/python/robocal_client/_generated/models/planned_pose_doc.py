from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.pose_set import PoseSet
from typing import cast






T = TypeVar("T", bound="PlannedPoseDoc")



@_attrs_define
class PlannedPoseDoc:
    """ One planned pose: the joints to move to, and the set its image goes in.

        Attributes:
            joints_deg (list[float]):
            set_ (PoseSet):
     """

    joints_deg: list[float]
    set_: PoseSet
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        joints_deg = self.joints_deg



        set_ = self.set_.value


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "joints_deg": joints_deg,
            "set": set_,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        joints_deg = cast(list[float], d.pop("joints_deg"))


        set_ = PoseSet(d.pop("set"))




        planned_pose_doc = cls(
            joints_deg=joints_deg,
            set_=set_,
        )


        planned_pose_doc.additional_properties = d
        return planned_pose_doc

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
