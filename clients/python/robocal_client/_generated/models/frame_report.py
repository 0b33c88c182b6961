from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="FrameReport")



@_attrs_define
class FrameReport:
    """ A fitted rigid transform: translation (mm), fixed-axis X-Y-Z angles
    (deg, `R = Rz Ry Rx`), the 4x4 row-major matrix, and its standard
    deviations (mm; small-angle rotation in deg about the outer frame's
    axes).

        Attributes:
            translation_mm (list[float]):
            rotation_deg (list[float]):
            matrix (list[list[float]]):
            std_translation_mm (list[float]): The standard deviations the report stands by: the jackknife's (leave
                one pose out, refit), which include the controller poses' own
                errors, when there were enough poses, else the formal ones; the
                rotations widened by the held camera's principal-point uncertainty
                (`sigma_c / f`), which neither sees.
            std_rotation_deg (list[float]):
            formal_std_translation_mm (list[float]): The formal standard deviations (white pixel noise, exact flange
                poses): too small when the controller poses carry errors.
            formal_std_rotation_deg (list[float]):
     """

    translation_mm: list[float]
    rotation_deg: list[float]
    matrix: list[list[float]]
    std_translation_mm: list[float]
    std_rotation_deg: list[float]
    formal_std_translation_mm: list[float]
    formal_std_rotation_deg: list[float]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        translation_mm = self.translation_mm



        rotation_deg = self.rotation_deg



        matrix = []
        for matrix_item_data in self.matrix:
            matrix_item = matrix_item_data


            matrix.append(matrix_item)



        std_translation_mm = self.std_translation_mm



        std_rotation_deg = self.std_rotation_deg



        formal_std_translation_mm = self.formal_std_translation_mm



        formal_std_rotation_deg = self.formal_std_rotation_deg




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "translation_mm": translation_mm,
            "rotation_deg": rotation_deg,
            "matrix": matrix,
            "std_translation_mm": std_translation_mm,
            "std_rotation_deg": std_rotation_deg,
            "formal_std_translation_mm": formal_std_translation_mm,
            "formal_std_rotation_deg": formal_std_rotation_deg,
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


        std_translation_mm = cast(list[float], d.pop("std_translation_mm"))


        std_rotation_deg = cast(list[float], d.pop("std_rotation_deg"))


        formal_std_translation_mm = cast(list[float], d.pop("formal_std_translation_mm"))


        formal_std_rotation_deg = cast(list[float], d.pop("formal_std_rotation_deg"))


        frame_report = cls(
            translation_mm=translation_mm,
            rotation_deg=rotation_deg,
            matrix=matrix,
            std_translation_mm=std_translation_mm,
            std_rotation_deg=std_rotation_deg,
            formal_std_translation_mm=formal_std_translation_mm,
            formal_std_rotation_deg=formal_std_rotation_deg,
        )


        frame_report.additional_properties = d
        return frame_report

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
