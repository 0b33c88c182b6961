from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="FramePose")



@_attrs_define
class FramePose:
    """ A pose in the contract's form plus its exact matrix: translation in mm,
    fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.

        Attributes:
            translation_mm (list[float]):
            rotation_deg (list[float]):
            matrix (list[list[float]]):
     """

    translation_mm: list[float]
    rotation_deg: list[float]
    matrix: list[list[float]]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        translation_mm = self.translation_mm



        rotation_deg = self.rotation_deg



        matrix = []
        for matrix_item_data in self.matrix:
            matrix_item = matrix_item_data


            matrix.append(matrix_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "translation_mm": translation_mm,
            "rotation_deg": rotation_deg,
            "matrix": matrix,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        translation_mm = cast(list[float], d.pop("translation_mm"))


        rotation_deg = cast(list[float], d.pop("rotation_deg"))


        matrix = []
        _matrix = d.pop("matrix")
        for matrix_item_data in (_matrix):
            matrix_item = cast(list[float], matrix_item_data)

            matrix.append(matrix_item)


        frame_pose = cls(
            translation_mm=translation_mm,
            rotation_deg=rotation_deg,
            matrix=matrix,
        )


        frame_pose.additional_properties = d
        return frame_pose

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
