from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="KeepOutDoc")



@_attrs_define
class KeepOutDoc:
    """ A box in the robot's base frame the flange and the camera must stay out of.

        Attributes:
            min_mm (list[float]):
            max_mm (list[float]):
     """

    min_mm: list[float]
    max_mm: list[float]





    def to_dict(self) -> dict[str, Any]:
        min_mm = self.min_mm



        max_mm = self.max_mm




        field_dict: dict[str, Any] = {}

        field_dict.update({
            "min_mm": min_mm,
            "max_mm": max_mm,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        min_mm = cast(list[float], d.pop("min_mm"))


        max_mm = cast(list[float], d.pop("max_mm"))


        keep_out_doc = cls(
            min_mm=min_mm,
            max_mm=max_mm,
        )

        return keep_out_doc

