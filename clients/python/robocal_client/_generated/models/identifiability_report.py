from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="IdentifiabilityReport")



@_attrs_define
class IdentifiabilityReport:
    """ 
        Attributes:
            parameters (int):
            rank (int):
            condition_number (float):
            observability_index (float):
            fixed (list[str]):
            weak (list[str] | Unset): The parameters this campaign's poses determine poorly or not at
                all: those of `fixed` they did not determine (held at nominal; the
                rest of `fixed` is structurally redundant) and identified ones with
                little excitation (large σ). Vary the poses to identify them well.
     """

    parameters: int
    rank: int
    condition_number: float
    observability_index: float
    fixed: list[str]
    weak: list[str] | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        parameters = self.parameters

        rank = self.rank

        condition_number = self.condition_number

        observability_index = self.observability_index

        fixed = self.fixed



        weak: list[str] | Unset = UNSET
        if not isinstance(self.weak, Unset):
            weak = self.weak




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "parameters": parameters,
            "rank": rank,
            "condition_number": condition_number,
            "observability_index": observability_index,
            "fixed": fixed,
        })
        if weak is not UNSET:
            field_dict["weak"] = weak

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        parameters = d.pop("parameters")

        rank = d.pop("rank")

        condition_number = d.pop("condition_number")

        observability_index = d.pop("observability_index")

        fixed = cast(list[str], d.pop("fixed"))


        weak = cast(list[str], d.pop("weak", UNSET))


        identifiability_report = cls(
            parameters=parameters,
            rank=rank,
            condition_number=condition_number,
            observability_index=observability_index,
            fixed=fixed,
            weak=weak,
        )


        identifiability_report.additional_properties = d
        return identifiability_report

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
