from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.preset import Preset
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.controller_identity import ControllerIdentity
  from ..models.kinematics_doc import KinematicsDoc
  from ..models.prior_doc import PriorDoc





T = TypeVar("T", bound="RobotOut")



@_attrs_define
class RobotOut:
    """ A robot as served: the joint table actually used (conventions chosen).

        Attributes:
            serial (str):
            model (str):
            kinematics (KinematicsDoc):
            created_at (str):
            updated_at (str):
            preset (None | Preset | Unset):
            controller (ControllerIdentity | None | Unset):
            prior (None | PriorDoc | Unset):
     """

    serial: str
    model: str
    kinematics: KinematicsDoc
    created_at: str
    updated_at: str
    preset: None | Preset | Unset = UNSET
    controller: ControllerIdentity | None | Unset = UNSET
    prior: None | PriorDoc | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.kinematics_doc import KinematicsDoc # noqa: PLC0415
        from ..models.prior_doc import PriorDoc # noqa: PLC0415
        serial = self.serial

        model = self.model

        kinematics = self.kinematics.to_dict()

        created_at = self.created_at

        updated_at = self.updated_at

        preset: None | str | Unset
        if isinstance(self.preset, Unset):
            preset = UNSET
        elif isinstance(self.preset, Preset):
            preset = self.preset.value
        else:
            preset = self.preset

        controller: dict[str, Any] | None | Unset
        if isinstance(self.controller, Unset):
            controller = UNSET
        elif isinstance(self.controller, ControllerIdentity):
            controller = self.controller.to_dict()
        else:
            controller = self.controller

        prior: dict[str, Any] | None | Unset
        if isinstance(self.prior, Unset):
            prior = UNSET
        elif isinstance(self.prior, PriorDoc):
            prior = self.prior.to_dict()
        else:
            prior = self.prior


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "serial": serial,
            "model": model,
            "kinematics": kinematics,
            "created_at": created_at,
            "updated_at": updated_at,
        })
        if preset is not UNSET:
            field_dict["preset"] = preset
        if controller is not UNSET:
            field_dict["controller"] = controller
        if prior is not UNSET:
            field_dict["prior"] = prior

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.kinematics_doc import KinematicsDoc # noqa: PLC0415
        from ..models.prior_doc import PriorDoc # noqa: PLC0415
        d = dict(src_dict)
        serial = d.pop("serial")

        model = d.pop("model")

        kinematics = KinematicsDoc.from_dict(d.pop("kinematics"))




        created_at = d.pop("created_at")

        updated_at = d.pop("updated_at")

        def _parse_preset(data: object) -> None | Preset | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                preset_type_1 = Preset(data)



                return preset_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | Preset | Unset, data)

        preset = _parse_preset(d.pop("preset", UNSET))


        def _parse_controller(data: object) -> ControllerIdentity | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                controller_type_1 = ControllerIdentity.from_dict(data)



                return controller_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ControllerIdentity | None | Unset, data)

        controller = _parse_controller(d.pop("controller", UNSET))


        def _parse_prior(data: object) -> None | PriorDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                prior_type_1 = PriorDoc.from_dict(data)



                return prior_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PriorDoc | Unset, data)

        prior = _parse_prior(d.pop("prior", UNSET))


        robot_out = cls(
            serial=serial,
            model=model,
            kinematics=kinematics,
            created_at=created_at,
            updated_at=updated_at,
            preset=preset,
            controller=controller,
            prior=prior,
        )


        robot_out.additional_properties = d
        return robot_out

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
