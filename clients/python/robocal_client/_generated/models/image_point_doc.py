from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="ImagePointDoc")



@_attrs_define
class ImagePointDoc:
    """ A dot's board index and its image position in pixels.

        Attributes:
            row (int):
            col (int):
            x (float):
            y (float):
     """

    row: int
    col: int
    x: float
    y: float





    def to_dict(self) -> dict[str, Any]:
        row = self.row

        col = self.col

        x = self.x

        y = self.y


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "row": row,
            "col": col,
            "x": x,
            "y": y,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        row = d.pop("row")

        col = d.pop("col")

        x = d.pop("x")

        y = d.pop("y")

        image_point_doc = cls(
            row=row,
            col=col,
            x=x,
            y=y,
        )

        return image_point_doc

