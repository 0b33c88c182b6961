from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.solver_start import SolverStart
from typing import cast

if TYPE_CHECKING:
  from ..models.configuration import Configuration
  from ..models.target_error import TargetError





T = TypeVar("T", bound="CompensateResponse")



@_attrs_define
class CompensateResponse:
    """ Per target, in the order of `targets`; `null` where `errors` names the
    target's index.

        Attributes:
            joints_deg (list[list[float] | None]): Per target: the in-limit joints nearest the seed (deg).
            residual_mm (list[float | None]):
            start (list[None | SolverStart]): Per target: where the run that found the joints started.
            configuration (list[Configuration | None]): Per target: the configuration of the joints, null for arms without
                a spherical wrist.
            warnings (list[list[str]]): Per target: as [`CompensatedTarget::warnings`] (empty where `errors`
                names the target).
            errors (list[TargetError]): Targets out of reach or beyond the joint limits, by index.
     """

    joints_deg: list[list[float] | None]
    residual_mm: list[float | None]
    start: list[None | SolverStart]
    configuration: list[Configuration | None]
    warnings: list[list[str]]
    errors: list[TargetError]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.configuration import Configuration # noqa: PLC0415
        from ..models.target_error import TargetError # noqa: PLC0415
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



        start = []
        for start_item_data in self.start:
            start_item: None | str
            if isinstance(start_item_data, SolverStart):
                start_item = start_item_data.value
            else:
                start_item = start_item_data
            start.append(start_item)



        configuration = []
        for configuration_item_data in self.configuration:
            configuration_item: dict[str, Any] | None
            if isinstance(configuration_item_data, Configuration):
                configuration_item = configuration_item_data.to_dict()
            else:
                configuration_item = configuration_item_data
            configuration.append(configuration_item)



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
            "joints_deg": joints_deg,
            "residual_mm": residual_mm,
            "start": start,
            "configuration": configuration,
            "warnings": warnings,
            "errors": errors,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.configuration import Configuration # noqa: PLC0415
        from ..models.target_error import TargetError # noqa: PLC0415
        d = dict(src_dict)
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


        start = []
        _start = d.pop("start")
        for start_item_data in (_start):
            def _parse_start_item(data: object) -> None | SolverStart:
                if data is None:
                    return data
                try:
                    if not isinstance(data, str):
                        raise TypeError()
                    start_item_type_1 = SolverStart(data)



                    return start_item_type_1
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                return cast(None | SolverStart, data)

            start_item = _parse_start_item(start_item_data)

            start.append(start_item)


        configuration = []
        _configuration = d.pop("configuration")
        for configuration_item_data in (_configuration):
            def _parse_configuration_item(data: object) -> Configuration | None:
                if data is None:
                    return data
                try:
                    if not isinstance(data, dict):
                        raise TypeError()
                    configuration_item_type_1 = Configuration.from_dict(data)



                    return configuration_item_type_1
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                return cast(Configuration | None, data)

            configuration_item = _parse_configuration_item(configuration_item_data)

            configuration.append(configuration_item)


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


        compensate_response = cls(
            joints_deg=joints_deg,
            residual_mm=residual_mm,
            start=start,
            configuration=configuration,
            warnings=warnings,
            errors=errors,
        )


        compensate_response.additional_properties = d
        return compensate_response

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
