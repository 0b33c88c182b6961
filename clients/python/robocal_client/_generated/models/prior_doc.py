from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="PriorDoc")



@_attrs_define
class PriorDoc:
    """ The prior standard deviations of a robot's kinematic deviations from
    its nominal table, per parameter kind.

        Attributes:
            joint_offset_deg (float): Joint zeros `dtheta` (deg), 0 < σ ≤ 10.
            length_mm (float): Lengths and offsets `a`, `d` (mm), 0 < σ ≤ 100.
            twist_deg (float): Twists `alpha` and Hayati tilts `beta` (deg), 0 < σ ≤ 10.
     """

    joint_offset_deg: float
    length_mm: float
    twist_deg: float





    def to_dict(self) -> dict[str, Any]:
        joint_offset_deg = self.joint_offset_deg

        length_mm = self.length_mm

        twist_deg = self.twist_deg


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "joint_offset_deg": joint_offset_deg,
            "length_mm": length_mm,
            "twist_deg": twist_deg,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        joint_offset_deg = d.pop("joint_offset_deg")

        length_mm = d.pop("length_mm")

        twist_deg = d.pop("twist_deg")

        prior_doc = cls(
            joint_offset_deg=joint_offset_deg,
            length_mm=length_mm,
            twist_deg=twist_deg,
        )

        return prior_doc

