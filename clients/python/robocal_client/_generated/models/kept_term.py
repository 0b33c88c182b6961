from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.kept_term_term import KeptTermTerm





T = TypeVar("T", bound="KeptTerm")



@_attrs_define
class KeptTerm:
    """ One kept term.

        Attributes:
            name (str): `periodic_{joint}.{sin|cos}{harmonic}`, `compliance_{joint}.mass_at_{k}`,
                `compliance_{joint}.mass_at_tool` or `compliance_{joint}.payload` (joints 1-based).
            term (KeptTermTerm): The basis the value multiplies (joints 0-based).
            value (float): The identified value, in `unit`.
            std_dev (float): Its 1σ, in `unit`.
            unit (str): `rad` (periodic), `rad*kg/(N*m)` (a lumped mass's compliance) or
                `rad/(N*m)` (compliance under the given payload).
     """

    name: str
    term: KeptTermTerm
    value: float
    std_dev: float
    unit: str
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.kept_term_term import KeptTermTerm # noqa: PLC0415
        name = self.name

        term = self.term.to_dict()

        value = self.value

        std_dev = self.std_dev

        unit = self.unit


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "name": name,
            "term": term,
            "value": value,
            "std_dev": std_dev,
            "unit": unit,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.kept_term_term import KeptTermTerm # noqa: PLC0415
        d = dict(src_dict)
        name = d.pop("name")

        term = KeptTermTerm.from_dict(d.pop("term"))




        value = d.pop("value")

        std_dev = d.pop("std_dev")

        unit = d.pop("unit")

        kept_term = cls(
            name=name,
            term=term,
            value=value,
            std_dev=std_dev,
            unit=unit,
        )


        kept_term.additional_properties = d
        return kept_term

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
