from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="UncertaintyCell")



@_attrs_define
class UncertaintyCell:
    """ One point of [`UncertaintyMapReport`].

        Attributes:
            x_mm (float):
            y_mm (float):
            position_std_mm (float): `sqrt(trace)` of the tool position's 3x3 covariance in the target
                (or tracker) frame: the RMS length of its 3-D error (mm).
     """

    x_mm: float
    y_mm: float
    position_std_mm: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        x_mm = self.x_mm

        y_mm = self.y_mm

        position_std_mm = self.position_std_mm


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "x_mm": x_mm,
            "y_mm": y_mm,
            "position_std_mm": position_std_mm,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        x_mm = d.pop("x_mm")

        y_mm = d.pop("y_mm")

        position_std_mm = d.pop("position_std_mm")

        uncertainty_cell = cls(
            x_mm=x_mm,
            y_mm=y_mm,
            position_std_mm=position_std_mm,
        )


        uncertainty_cell.additional_properties = d
        return uncertainty_cell

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
