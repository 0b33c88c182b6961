from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.error_stats import ErrorStats





T = TypeVar("T", bound="AccuracySummary")



@_attrs_define
class AccuracySummary:
    """ 3-D position-error statistics (the `ErrorStats` fields of the error
    norm) plus the same per axis (`|e_x|`, `|e_y|`, `|e_z|`), world frame.

        Attributes:
            n (int):
            mean_mm (float):
            median_mm (float):
            std_mm (float):
            max_mm (float):
            rms_mm (float):
            x (ErrorStats): Summary of error magnitudes, mm.
            y (ErrorStats): Summary of error magnitudes, mm.
            z (ErrorStats): Summary of error magnitudes, mm.
     """

    n: int
    mean_mm: float
    median_mm: float
    std_mm: float
    max_mm: float
    rms_mm: float
    x: ErrorStats
    y: ErrorStats
    z: ErrorStats
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.error_stats import ErrorStats # noqa: PLC0415
        n = self.n

        mean_mm = self.mean_mm

        median_mm = self.median_mm

        std_mm = self.std_mm

        max_mm = self.max_mm

        rms_mm = self.rms_mm

        x = self.x.to_dict()

        y = self.y.to_dict()

        z = self.z.to_dict()


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "n": n,
            "mean_mm": mean_mm,
            "median_mm": median_mm,
            "std_mm": std_mm,
            "max_mm": max_mm,
            "rms_mm": rms_mm,
            "x": x,
            "y": y,
            "z": z,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.error_stats import ErrorStats # noqa: PLC0415
        d = dict(src_dict)
        n = d.pop("n")

        mean_mm = d.pop("mean_mm")

        median_mm = d.pop("median_mm")

        std_mm = d.pop("std_mm")

        max_mm = d.pop("max_mm")

        rms_mm = d.pop("rms_mm")

        x = ErrorStats.from_dict(d.pop("x"))




        y = ErrorStats.from_dict(d.pop("y"))




        z = ErrorStats.from_dict(d.pop("z"))




        accuracy_summary = cls(
            n=n,
            mean_mm=mean_mm,
            median_mm=median_mm,
            std_mm=std_mm,
            max_mm=max_mm,
            rms_mm=rms_mm,
            x=x,
            y=y,
            z=z,
        )


        accuracy_summary.additional_properties = d
        return accuracy_summary

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
