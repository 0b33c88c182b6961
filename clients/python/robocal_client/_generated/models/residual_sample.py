from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="ResidualSample")



@_attrs_define
class ResidualSample:
    """ A reprojection residual at an image point (observed minus predicted),
    for the residual-field plot.

        Attributes:
            x_px (float):
            y_px (float):
            dx_px (float):
            dy_px (float):
     """

    x_px: float
    y_px: float
    dx_px: float
    dy_px: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        x_px = self.x_px

        y_px = self.y_px

        dx_px = self.dx_px

        dy_px = self.dy_px


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "x_px": x_px,
            "y_px": y_px,
            "dx_px": dx_px,
            "dy_px": dy_px,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        x_px = d.pop("x_px")

        y_px = d.pop("y_px")

        dx_px = d.pop("dx_px")

        dy_px = d.pop("dy_px")

        residual_sample = cls(
            x_px=x_px,
            y_px=y_px,
            dx_px=dx_px,
            dy_px=dy_px,
        )


        residual_sample.additional_properties = d
        return residual_sample

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
