from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.calibration_scope import CalibrationScope
from ..models.measurement import Measurement
from ..models.validation_named import ValidationNamed
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.holdout import Holdout





T = TypeVar("T", bound="CalibrationOptions")



@_attrs_define
class CalibrationOptions:
    """ `POST /v1/sessions/{id}/calibrations` body; every field optional.

        Attributes:
            measurement (Measurement | None | Unset):
            refine_intrinsics (bool | Unset): `false`: the camera intrinsics are the paper's Tsai-sequence
                estimates, not refined (`camera_mode: "paper"` in the parameter set);
                the joint refinement, which would re-fit them, is then skipped.
            joint_refinement (bool | Unset): The final fit of kinematics, hand–eye and intrinsics to the image
                points; skipped when the intrinsics are held (`refine_intrinsics:
                false`, or a session `camera_calibration_id`).
            validation (Holdout | Unset | ValidationNamed): `"val_set"` (the poses uploaded with `set: "val"`) or
                `{"holdout_fraction": f}`.
            scope (CalibrationScope | Unset): What a calibration re-fits.
            non_geometric (bool | None | Unset): Select non-geometric terms (joint compliance, angle-periodic joint
                errors) after the geometric fit and keep those the campaign
                identifies and that lower the held-out error; `false`:
                geometry only. Absent: on for tracker sessions, off for camera
                sessions (see [`CalibrationOptions::non_geometric_for`]).
            sessions (list[str] | Unset): `POST /v1/robots/{serial}/calibrations` only: the
                sessions (board placements, regions) of one robot fitted together:
                one kinematic model and hand–eye, one `target_to_base` per session,
                the camera intrinsics shared. Empty for a one-session job.
     """

    measurement: Measurement | None | Unset = UNSET
    refine_intrinsics: bool | Unset = UNSET
    joint_refinement: bool | Unset = UNSET
    validation: Holdout | Unset | ValidationNamed = UNSET
    scope: CalibrationScope | Unset = UNSET
    non_geometric: bool | None | Unset = UNSET
    sessions: list[str] | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.holdout import Holdout # noqa: PLC0415
        measurement: None | str | Unset
        if isinstance(self.measurement, Unset):
            measurement = UNSET
        elif isinstance(self.measurement, Measurement):
            measurement = self.measurement.value
        else:
            measurement = self.measurement

        refine_intrinsics = self.refine_intrinsics

        joint_refinement = self.joint_refinement

        validation: dict[str, Any] | str | Unset
        if isinstance(self.validation, Unset):
            validation = UNSET
        elif isinstance(self.validation, ValidationNamed):
            validation = self.validation.value
        else:
            validation = self.validation.to_dict()


        scope: str | Unset = UNSET
        if not isinstance(self.scope, Unset):
            scope = self.scope.value


        non_geometric: bool | None | Unset
        if isinstance(self.non_geometric, Unset):
            non_geometric = UNSET
        else:
            non_geometric = self.non_geometric

        sessions: list[str] | Unset = UNSET
        if not isinstance(self.sessions, Unset):
            sessions = self.sessions




        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if measurement is not UNSET:
            field_dict["measurement"] = measurement
        if refine_intrinsics is not UNSET:
            field_dict["refine_intrinsics"] = refine_intrinsics
        if joint_refinement is not UNSET:
            field_dict["joint_refinement"] = joint_refinement
        if validation is not UNSET:
            field_dict["validation"] = validation
        if scope is not UNSET:
            field_dict["scope"] = scope
        if non_geometric is not UNSET:
            field_dict["non_geometric"] = non_geometric
        if sessions is not UNSET:
            field_dict["sessions"] = sessions

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.holdout import Holdout # noqa: PLC0415
        d = dict(src_dict)
        def _parse_measurement(data: object) -> Measurement | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                measurement_type_1 = Measurement(data)



                return measurement_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(Measurement | None | Unset, data)

        measurement = _parse_measurement(d.pop("measurement", UNSET))


        refine_intrinsics = d.pop("refine_intrinsics", UNSET)

        joint_refinement = d.pop("joint_refinement", UNSET)

        def _parse_validation(data: object) -> Holdout | Unset | ValidationNamed:
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                componentsschemas_validation_type_0 = ValidationNamed(data)



                return componentsschemas_validation_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            if not isinstance(data, dict):
                raise TypeError()
            componentsschemas_validation_type_1 = Holdout.from_dict(data)



            return componentsschemas_validation_type_1

        validation = _parse_validation(d.pop("validation", UNSET))


        _scope = d.pop("scope", UNSET)
        scope: CalibrationScope | Unset
        if isinstance(_scope,  Unset):
            scope = UNSET
        else:
            scope = CalibrationScope(_scope)




        def _parse_non_geometric(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        non_geometric = _parse_non_geometric(d.pop("non_geometric", UNSET))


        sessions = cast(list[str], d.pop("sessions", UNSET))


        calibration_options = cls(
            measurement=measurement,
            refine_intrinsics=refine_intrinsics,
            joint_refinement=joint_refinement,
            validation=validation,
            scope=scope,
            non_geometric=non_geometric,
            sessions=sessions,
        )

        return calibration_options

