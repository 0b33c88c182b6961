from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="ParameterReport")



@_attrs_define
class ParameterReport:
    """ One identified parameter against its nominal value.

        Attributes:
            name (str): E.g. "joint2.a_mm", "joint3.beta_deg", "target_to_base.tx_mm".
            unit (str):
            nominal (float):
            identified (float):
            std (float):
            fixed (bool): Held fixed as unidentifiable (redundant with another parameter).
     """

    name: str
    unit: str
    nominal: float
    identified: float
    std: float
    fixed: bool
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        unit = self.unit

        nominal = self.nominal

        identified = self.identified

        std = self.std

        fixed = self.fixed


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "name": name,
            "unit": unit,
            "nominal": nominal,
            "identified": identified,
            "std": std,
            "fixed": fixed,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        unit = d.pop("unit")

        nominal = d.pop("nominal")

        identified = d.pop("identified")

        std = d.pop("std")

        fixed = d.pop("fixed")

        parameter_report = cls(
            name=name,
            unit=unit,
            nominal=nominal,
            identified=identified,
            std=std,
            fixed=fixed,
        )


        parameter_report.additional_properties = d
        return parameter_report

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
