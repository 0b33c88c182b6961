from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.solver_start import SolverStart
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.configuration import Configuration





T = TypeVar("T", bound="CompensateLine")



@_attrs_define
class CompensateLine:
    """ One line of the `application/x-ndjson` answer (a schema only: the lines
    are `TargetLine<CompensatedTarget>`): `index`, then either the target's
    answer or `error`.

        Attributes:
            index (int): Index into `targets`; lines come in this order.
            joints_deg (list[float] | None | Unset):
            residual_mm (float | None | Unset):
            start (None | SolverStart | Unset):
            configuration (Configuration | None | Unset):
            warnings (list[str] | None | Unset):
            error (None | str | Unset): Why this target has no joints (out of reach, beyond the limits).
     """

    index: int
    joints_deg: list[float] | None | Unset = UNSET
    residual_mm: float | None | Unset = UNSET
    start: None | SolverStart | Unset = UNSET
    configuration: Configuration | None | Unset = UNSET
    warnings: list[str] | None | Unset = UNSET
    error: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.configuration import Configuration # noqa: PLC0415
        index = self.index

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

        start: None | str | Unset
        if isinstance(self.start, Unset):
            start = UNSET
        elif isinstance(self.start, SolverStart):
            start = self.start.value
        else:
            start = self.start

        configuration: dict[str, Any] | None | Unset
        if isinstance(self.configuration, Unset):
            configuration = UNSET
        elif isinstance(self.configuration, Configuration):
            configuration = self.configuration.to_dict()
        else:
            configuration = self.configuration

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
        if joints_deg is not UNSET:
            field_dict["joints_deg"] = joints_deg
        if residual_mm is not UNSET:
            field_dict["residual_mm"] = residual_mm
        if start is not UNSET:
            field_dict["start"] = start
        if configuration is not UNSET:
            field_dict["configuration"] = configuration
        if warnings is not UNSET:
            field_dict["warnings"] = warnings
        if error is not UNSET:
            field_dict["error"] = error

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.configuration import Configuration # noqa: PLC0415
        d = dict(src_dict)
        index = d.pop("index")

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


        def _parse_start(data: object) -> None | SolverStart | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                start_type_1 = SolverStart(data)



                return start_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | SolverStart | Unset, data)

        start = _parse_start(d.pop("start", UNSET))


        def _parse_configuration(data: object) -> Configuration | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                configuration_type_1 = Configuration.from_dict(data)



                return configuration_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(Configuration | None | Unset, data)

        configuration = _parse_configuration(d.pop("configuration", UNSET))


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


        compensate_line = cls(
            index=index,
            joints_deg=joints_deg,
            residual_mm=residual_mm,
            start=start,
            configuration=configuration,
            warnings=warnings,
            error=error,
        )


        compensate_line.additional_properties = d
        return compensate_line

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
