from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.axis_stats_report import AxisStatsReport
  from ..models.travel_error_report import TravelErrorReport





T = TypeVar("T", bound="SequenceAccuracyReport")



@_attrs_define
class SequenceAccuracyReport:
    """ Table 1's row of one sequence.

        Attributes:
            sequence (int):
            distance_mm (float): Mean distance from the camera to the board's centre (mm).
            images (int):
            mean_mm (list[float]): Per target axis `[x, y, z]`: statistics of the absolute position
                error (mm) by the average-rotation method.
            median_mm (list[float]):
            std_mm (list[float]):
            max_mm (list[float]):
            max_3d_mm (float): Largest 3-D position error of the sequence (mm).
            travelled_distance_error_mm (TravelErrorReport):
            stage_referenced_mm (AxisStatsReport | None | Unset):
            offset_sd_mm (list[float] | None | Unset): σ per target axis (mm) of the offset common to every image of the
                sequence, propagated from the dots' errors through the intrinsics
                and each image's pose fit: the part of the error neither table
                sees. Absent in reports made before it existed.
     """

    sequence: int
    distance_mm: float
    images: int
    mean_mm: list[float]
    median_mm: list[float]
    std_mm: list[float]
    max_mm: list[float]
    max_3d_mm: float
    travelled_distance_error_mm: TravelErrorReport
    stage_referenced_mm: AxisStatsReport | None | Unset = UNSET
    offset_sd_mm: list[float] | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.axis_stats_report import AxisStatsReport # noqa: PLC0415
        from ..models.travel_error_report import TravelErrorReport # noqa: PLC0415
        sequence = self.sequence

        distance_mm = self.distance_mm

        images = self.images

        mean_mm = self.mean_mm



        median_mm = self.median_mm



        std_mm = self.std_mm



        max_mm = self.max_mm



        max_3d_mm = self.max_3d_mm

        travelled_distance_error_mm = self.travelled_distance_error_mm.to_dict()

        stage_referenced_mm: dict[str, Any] | None | Unset
        if isinstance(self.stage_referenced_mm, Unset):
            stage_referenced_mm = UNSET
        elif isinstance(self.stage_referenced_mm, AxisStatsReport):
            stage_referenced_mm = self.stage_referenced_mm.to_dict()
        else:
            stage_referenced_mm = self.stage_referenced_mm

        offset_sd_mm: list[float] | None | Unset
        if isinstance(self.offset_sd_mm, Unset):
            offset_sd_mm = UNSET
        elif isinstance(self.offset_sd_mm, list):
            offset_sd_mm = self.offset_sd_mm


        else:
            offset_sd_mm = self.offset_sd_mm


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "sequence": sequence,
            "distance_mm": distance_mm,
            "images": images,
            "mean_mm": mean_mm,
            "median_mm": median_mm,
            "std_mm": std_mm,
            "max_mm": max_mm,
            "max_3d_mm": max_3d_mm,
            "travelled_distance_error_mm": travelled_distance_error_mm,
        })
        if stage_referenced_mm is not UNSET:
            field_dict["stage_referenced_mm"] = stage_referenced_mm
        if offset_sd_mm is not UNSET:
            field_dict["offset_sd_mm"] = offset_sd_mm

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.axis_stats_report import AxisStatsReport # noqa: PLC0415
        from ..models.travel_error_report import TravelErrorReport # noqa: PLC0415
        d = dict(src_dict)
        sequence = d.pop("sequence")

        distance_mm = d.pop("distance_mm")

        images = d.pop("images")

        mean_mm = cast(list[float], d.pop("mean_mm"))


        median_mm = cast(list[float], d.pop("median_mm"))


        std_mm = cast(list[float], d.pop("std_mm"))


        max_mm = cast(list[float], d.pop("max_mm"))


        max_3d_mm = d.pop("max_3d_mm")

        travelled_distance_error_mm = TravelErrorReport.from_dict(d.pop("travelled_distance_error_mm"))




        def _parse_stage_referenced_mm(data: object) -> AxisStatsReport | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                stage_referenced_mm_type_1 = AxisStatsReport.from_dict(data)



                return stage_referenced_mm_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(AxisStatsReport | None | Unset, data)

        stage_referenced_mm = _parse_stage_referenced_mm(d.pop("stage_referenced_mm", UNSET))


        def _parse_offset_sd_mm(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                offset_sd_mm_type_0 = cast(list[float], data)

                return offset_sd_mm_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        offset_sd_mm = _parse_offset_sd_mm(d.pop("offset_sd_mm", UNSET))


        sequence_accuracy_report = cls(
            sequence=sequence,
            distance_mm=distance_mm,
            images=images,
            mean_mm=mean_mm,
            median_mm=median_mm,
            std_mm=std_mm,
            max_mm=max_mm,
            max_3d_mm=max_3d_mm,
            travelled_distance_error_mm=travelled_distance_error_mm,
            stage_referenced_mm=stage_referenced_mm,
            offset_sd_mm=offset_sd_mm,
        )


        sequence_accuracy_report.additional_properties = d
        return sequence_accuracy_report

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
