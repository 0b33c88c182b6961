from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="CameraDoc")



@_attrs_define
class CameraDoc:
    """ 
        Attributes:
            width (int):
            height (int):
            pixel_size_um (float):
            nominal_focal_mm (float):
     """

    width: int
    height: int
    pixel_size_um: float
    nominal_focal_mm: float





    def to_dict(self) -> dict[str, Any]:
        width = self.width

        height = self.height

        pixel_size_um = self.pixel_size_um

        nominal_focal_mm = self.nominal_focal_mm


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "width": width,
            "height": height,
            "pixel_size_um": pixel_size_um,
            "nominal_focal_mm": nominal_focal_mm,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        width = d.pop("width")

        height = d.pop("height")

        pixel_size_um = d.pop("pixel_size_um")

        nominal_focal_mm = d.pop("nominal_focal_mm")

        camera_doc = cls(
            width=width,
            height=height,
            pixel_size_um=pixel_size_um,
            nominal_focal_mm=nominal_focal_mm,
        )

        return camera_doc

