from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="ErrorStats")



@_attrs_define
class ErrorStats:
    """ Summary of error magnitudes, mm.

        Attributes:
            n (int):
            mean_mm (float):
            median_mm (float):
            std_mm (float): Sample standard deviation (n - 1) of the magnitudes.
            max_mm (float):
            rms_mm (float):
     """

    n: int
    mean_mm: float
    median_mm: float
    std_mm: float
    max_mm: float
    rms_mm: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        n = self.n

        mean_mm = self.mean_mm

        median_mm = self.median_mm

        std_mm = self.std_mm

        max_mm = self.max_mm

        rms_mm = self.rms_mm


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "n": n,
            "mean_mm": mean_mm,
            "median_mm": median_mm,
            "std_mm": std_mm,
            "max_mm": max_mm,
            "rms_mm": rms_mm,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        n = d.pop("n")

        mean_mm = d.pop("mean_mm")

        median_mm = d.pop("median_mm")

        std_mm = d.pop("std_mm")

        max_mm = d.pop("max_mm")

        rms_mm = d.pop("rms_mm")

        error_stats = cls(
            n=n,
            mean_mm=mean_mm,
            median_mm=median_mm,
            std_mm=std_mm,
            max_mm=max_mm,
            rms_mm=rms_mm,
        )


        error_stats.additional_properties = d
        return error_stats

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
