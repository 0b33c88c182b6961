from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.frame_pose import FramePose
  from ..models.target_error import TargetError





T = TypeVar("T", bound="FilterResponse")



@_attrs_define
class FilterResponse:
    """ Per target (same order; `null` where `errors` names the index).

        Attributes:
            nominal_targets (list[FramePose | None]): The flange pose in the base frame to send to the nominal controller.
            joints_deg (list[list[float] | None]): The joints the real robot takes for each target (deg).
            residual_mm (list[float | None]): Where the calibrated model puts the tool when the nominal controller
                solves the filtered target from the seed, distance to the target (mm).
            warnings (list[list[str]]): Per target: the real joints outside the span the set's kept terms
                were identified on (they extrapolate there); empty when none or
                where `errors` names the target.
            errors (list[TargetError]):
     """

    nominal_targets: list[FramePose | None]
    joints_deg: list[list[float] | None]
    residual_mm: list[float | None]
    warnings: list[list[str]]
    errors: list[TargetError]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.target_error import TargetError # noqa: PLC0415
        nominal_targets = []
        for nominal_targets_item_data in self.nominal_targets:
            nominal_targets_item: dict[str, Any] | None
            if isinstance(nominal_targets_item_data, FramePose):
                nominal_targets_item = nominal_targets_item_data.to_dict()
            else:
                nominal_targets_item = nominal_targets_item_data
            nominal_targets.append(nominal_targets_item)



        joints_deg = []
        for joints_deg_item_data in self.joints_deg:
            joints_deg_item: list[float] | None
            if isinstance(joints_deg_item_data, list):
                joints_deg_item = joints_deg_item_data


            else:
                joints_deg_item = joints_deg_item_data
            joints_deg.append(joints_deg_item)



        residual_mm = []
        for residual_mm_item_data in self.residual_mm:
            residual_mm_item: float | None
            residual_mm_item = residual_mm_item_data
            residual_mm.append(residual_mm_item)



        warnings = []
        for warnings_item_data in self.warnings:
            warnings_item = warnings_item_data


            warnings.append(warnings_item)



        errors = []
        for errors_item_data in self.errors:
            errors_item = errors_item_data.to_dict()
            errors.append(errors_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "nominal_targets": nominal_targets,
            "joints_deg": joints_deg,
            "residual_mm": residual_mm,
            "warnings": warnings,
            "errors": errors,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.target_error import TargetError # noqa: PLC0415
        d = dict(src_dict)
        nominal_targets = []
        _nominal_targets = d.pop("nominal_targets")
        for nominal_targets_item_data in (_nominal_targets):
            def _parse_nominal_targets_item(data: object) -> FramePose | None:
                if data is None:
                    return data
                try:
                    if not isinstance(data, dict):
                        raise TypeError()
                    nominal_targets_item_type_1 = FramePose.from_dict(data)



                    return nominal_targets_item_type_1
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                return cast(FramePose | None, data)

            nominal_targets_item = _parse_nominal_targets_item(nominal_targets_item_data)

            nominal_targets.append(nominal_targets_item)


        joints_deg = []
        _joints_deg = d.pop("joints_deg")
        for joints_deg_item_data in (_joints_deg):
            def _parse_joints_deg_item(data: object) -> list[float] | None:
                if data is None:
                    return data
                try:
                    if not isinstance(data, list):
                        raise TypeError()
                    joints_deg_item_type_0 = cast(list[float], data)

                    return joints_deg_item_type_0
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                return cast(list[float] | None, data)

            joints_deg_item = _parse_joints_deg_item(joints_deg_item_data)

            joints_deg.append(joints_deg_item)


        residual_mm = []
        _residual_mm = d.pop("residual_mm")
        for residual_mm_item_data in (_residual_mm):
            def _parse_residual_mm_item(data: object) -> float | None:
                if data is None:
                    return data
                return cast(float | None, data)

            residual_mm_item = _parse_residual_mm_item(residual_mm_item_data)

            residual_mm.append(residual_mm_item)


        warnings = []
        _warnings = d.pop("warnings")
        for warnings_item_data in (_warnings):
            warnings_item = cast(list[str], warnings_item_data)

            warnings.append(warnings_item)


        errors = []
        _errors = d.pop("errors")
        for errors_item_data in (_errors):
            errors_item = TargetError.from_dict(errors_item_data)



            errors.append(errors_item)


        filter_response = cls(
            nominal_targets=nominal_targets,
            joints_deg=joints_deg,
            residual_mm=residual_mm,
            warnings=warnings,
            errors=errors,
        )


        filter_response.additional_properties = d
        return filter_response

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
