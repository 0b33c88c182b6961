from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="TermJointRange")



@_attrs_define
class TermJointRange:
    """ One joint's span over the calibration poses (deg).

        Attributes:
            joint (int): 1-based, as in the parameters' names.
            min_deg (float):
            max_deg (float):
     """

    joint: int
    min_deg: float
    max_deg: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        joint = self.joint

        min_deg = self.min_deg

        max_deg = self.max_deg


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "joint": joint,
            "min_deg": min_deg,
            "max_deg": max_deg,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        joint = d.pop("joint")

        min_deg = d.pop("min_deg")

        max_deg = d.pop("max_deg")

        term_joint_range = cls(
            joint=joint,
            min_deg=min_deg,
            max_deg=max_deg,
        )


        term_joint_range.additional_properties = d
        return term_joint_range

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
