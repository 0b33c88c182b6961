from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="TermLine")



@_attrs_define
class TermLine:
    """ One candidate term's verdict.

        Attributes:
            name (str):
            verdict (str): `kept`, `not_identifiable`, `not_significant`, `does_not_generalise`
                or `no_information_gain`.
            value (float): Value when kept, or when last fitted before it was rejected (0 when
                never fitted), in `unit`.
            std_dev (float): Its 1σ, in `unit` (0 when never fitted).
            unit (str):
            why (str):
     """

    name: str
    verdict: str
    value: float
    std_dev: float
    unit: str
    why: str
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        verdict = self.verdict

        value = self.value

        std_dev = self.std_dev

        unit = self.unit

        why = self.why


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "name": name,
            "verdict": verdict,
            "value": value,
            "std_dev": std_dev,
            "unit": unit,
            "why": why,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        verdict = d.pop("verdict")

        value = d.pop("value")

        std_dev = d.pop("std_dev")

        unit = d.pop("unit")

        why = d.pop("why")

        term_line = cls(
            name=name,
            verdict=verdict,
            value=value,
            std_dev=std_dev,
            unit=unit,
            why=why,
        )


        term_line.additional_properties = d
        return term_line

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
