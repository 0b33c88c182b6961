from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.frame_pose import FramePose





T = TypeVar("T", bound="FilterLine")



@_attrs_define
class FilterLine:
    """ One line of the `application/x-ndjson` answer (a schema only: the lines
    are `TargetLine<FilteredTarget>`): `index`, then either the target's
    answer or `error`.

        Attributes:
            index (int): Index into `targets`; lines come in this order.
            nominal_target (FramePose | None | Unset):
            joints_deg (list[float] | None | Unset):
            residual_mm (float | None | Unset):
            warnings (list[str] | None | Unset):
            error (None | str | Unset): Why this target has no filtered pose (out of reach, beyond the limits).
     """

    index: int
    nominal_target: FramePose | None | Unset = UNSET
    joints_deg: list[float] | None | Unset = UNSET
    residual_mm: float | None | Unset = UNSET
    warnings: list[str] | None | Unset = UNSET
    error: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        index = self.index

        nominal_target: dict[str, Any] | None | Unset
        if isinstance(self.nominal_target, Unset):
            nominal_target = UNSET
        elif isinstance(self.nominal_target, FramePose):
            nominal_target = self.nominal_target.to_dict()
        else:
            nominal_target = self.nominal_target

        joints_deg: list[float] | None | Unset
        if isinstance(self.joints_deg, Unset):
            joints_deg = UNSET
        elif isinstance(self.joints_deg, list):
            joints_deg = self.joints_deg


        else:
            joints_deg = self.joints_deg

        residual_mm: float | None | Unset
        if isinstance(self.residual_mm, Unset):
            residual_mm = UNSET
        else:
            residual_mm = self.residual_mm

        warnings: list[str] | None | Unset
        if isinstance(self.warnings, Unset):
            warnings = UNSET
        elif isinstance(self.warnings, list):
            warnings = self.warnings


        else:
            warnings = self.warnings

        error: None | str | Unset
        if isinstance(self.error, Unset):
            error = UNSET
        else:
            error = self.error


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "index": index,
        })
        if nominal_target is not UNSET:
            field_dict["nominal_target"] = nominal_target
        if joints_deg is not UNSET:
            field_dict["joints_deg"] = joints_deg
        if residual_mm is not UNSET:
            field_dict["residual_mm"] = residual_mm
        if warnings is not UNSET:
            field_dict["warnings"] = warnings
        if error is not UNSET:
            field_dict["error"] = error

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        d = dict(src_dict)
        index = d.pop("index")

        def _parse_nominal_target(data: object) -> FramePose | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                nominal_target_type_1 = FramePose.from_dict(data)



                return nominal_target_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FramePose | None | Unset, data)

        nominal_target = _parse_nominal_target(d.pop("nominal_target", UNSET))


        def _parse_joints_deg(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                joints_deg_type_0 = cast(list[float], data)

                return joints_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        joints_deg = _parse_joints_deg(d.pop("joints_deg", UNSET))


        def _parse_residual_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        residual_mm = _parse_residual_mm(d.pop("residual_mm", UNSET))


        def _parse_warnings(data: object) -> list[str] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                warnings_type_0 = cast(list[str], data)

                return warnings_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[str] | None | Unset, data)

        warnings = _parse_warnings(d.pop("warnings", UNSET))


        def _parse_error(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        error = _parse_error(d.pop("error", UNSET))


        filter_line = cls(
            index=index,
            nominal_target=nominal_target,
            joints_deg=joints_deg,
            residual_mm=residual_mm,
            warnings=warnings,
            error=error,
        )


        filter_line.additional_properties = d
        return filter_line

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
