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





T = TypeVar("T", bound="RobotBody")



@_attrs_define
class RobotBody:
    """ `PUT /v1/robots/{serial}` body: a joint table or a preset name.

        Attributes:
            model (str): The robot model's name, 1 to 200 characters, not only spaces.
            kinematics (KinematicsDoc | None | Unset):
            preset (None | Preset | Unset):
            controller (ControllerIdentity | None | Unset):
            prior (None | PriorDoc | Unset):
     """

    model: str
    kinematics: KinematicsDoc | None | Unset = UNSET
    preset: None | Preset | Unset = UNSET
    controller: ControllerIdentity | None | Unset = UNSET
    prior: None | PriorDoc | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.kinematics_doc import KinematicsDoc # noqa: PLC0415
        from ..models.prior_doc import PriorDoc # noqa: PLC0415
        model = self.model

        kinematics: dict[str, Any] | None | Unset
        if isinstance(self.kinematics, Unset):
            kinematics = UNSET
        elif isinstance(self.kinematics, KinematicsDoc):
            kinematics = self.kinematics.to_dict()
        else:
            kinematics = self.kinematics

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

        field_dict.update({
            "model": model,
        })
        if kinematics is not UNSET:
            field_dict["kinematics"] = kinematics
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
        model = d.pop("model")

        def _parse_kinematics(data: object) -> KinematicsDoc | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                kinematics_type_1 = KinematicsDoc.from_dict(data)



                return kinematics_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(KinematicsDoc | None | Unset, data)

        kinematics = _parse_kinematics(d.pop("kinematics", UNSET))


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


        robot_body = cls(
            model=model,
            kinematics=kinematics,
            preset=preset,
            controller=controller,
            prior=prior,
        )

        return robot_body

