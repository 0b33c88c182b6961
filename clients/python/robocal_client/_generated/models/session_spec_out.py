from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.instrument import Instrument
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.camera_doc import CameraDoc
  from ..models.controller_identity import ControllerIdentity
  from ..models.pose_doc import PoseDoc
  from ..models.target_doc import TargetDoc





T = TypeVar("T", bound="SessionSpecOut")



@_attrs_define
class SessionSpecOut:
    """ The fields of [`SessionBody`] as they appear in a served session (its
    response schema: open to the session's identity fields).

        Attributes:
            instrument (Instrument): The session's instrument.
            target (None | TargetDoc | Unset):
            camera (CameraDoc | None | Unset):
            flange_to_camera_guess (None | PoseDoc | Unset):
            camera_calibration_id (None | str | Unset): The reused camera calibration, `latest` resolved to its version.
            region (None | str | Unset): Where the board was placed in the workspace (free text).
            volume (None | str | Unset): The measurement volume the poses span (free text).
            payload_kg (float | None | Unset): Payload at the tool during the campaign (kg).
            controller (ControllerIdentity | None | Unset):
     """

    instrument: Instrument
    target: None | TargetDoc | Unset = UNSET
    camera: CameraDoc | None | Unset = UNSET
    flange_to_camera_guess: None | PoseDoc | Unset = UNSET
    camera_calibration_id: None | str | Unset = UNSET
    region: None | str | Unset = UNSET
    volume: None | str | Unset = UNSET
    payload_kg: float | None | Unset = UNSET
    controller: ControllerIdentity | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.camera_doc import CameraDoc # noqa: PLC0415
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        from ..models.target_doc import TargetDoc # noqa: PLC0415
        instrument = self.instrument.value

        target: dict[str, Any] | None | Unset
        if isinstance(self.target, Unset):
            target = UNSET
        elif isinstance(self.target, TargetDoc):
            target = self.target.to_dict()
        else:
            target = self.target

        camera: dict[str, Any] | None | Unset
        if isinstance(self.camera, Unset):
            camera = UNSET
        elif isinstance(self.camera, CameraDoc):
            camera = self.camera.to_dict()
        else:
            camera = self.camera

        flange_to_camera_guess: dict[str, Any] | None | Unset
        if isinstance(self.flange_to_camera_guess, Unset):
            flange_to_camera_guess = UNSET
        elif isinstance(self.flange_to_camera_guess, PoseDoc):
            flange_to_camera_guess = self.flange_to_camera_guess.to_dict()
        else:
            flange_to_camera_guess = self.flange_to_camera_guess

        camera_calibration_id: None | str | Unset
        if isinstance(self.camera_calibration_id, Unset):
            camera_calibration_id = UNSET
        else:
            camera_calibration_id = self.camera_calibration_id

        region: None | str | Unset
        if isinstance(self.region, Unset):
            region = UNSET
        else:
            region = self.region

        volume: None | str | Unset
        if isinstance(self.volume, Unset):
            volume = UNSET
        else:
            volume = self.volume

        payload_kg: float | None | Unset
        if isinstance(self.payload_kg, Unset):
            payload_kg = UNSET
        else:
            payload_kg = self.payload_kg

        controller: dict[str, Any] | None | Unset
        if isinstance(self.controller, Unset):
            controller = UNSET
        elif isinstance(self.controller, ControllerIdentity):
            controller = self.controller.to_dict()
        else:
            controller = self.controller


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "instrument": instrument,
        })
        if target is not UNSET:
            field_dict["target"] = target
        if camera is not UNSET:
            field_dict["camera"] = camera
        if flange_to_camera_guess is not UNSET:
            field_dict["flange_to_camera_guess"] = flange_to_camera_guess
        if camera_calibration_id is not UNSET:
            field_dict["camera_calibration_id"] = camera_calibration_id
        if region is not UNSET:
            field_dict["region"] = region
        if volume is not UNSET:
            field_dict["volume"] = volume
        if payload_kg is not UNSET:
            field_dict["payload_kg"] = payload_kg
        if controller is not UNSET:
            field_dict["controller"] = controller

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.camera_doc import CameraDoc # noqa: PLC0415
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        from ..models.target_doc import TargetDoc # noqa: PLC0415
        d = dict(src_dict)
        instrument = Instrument(d.pop("instrument"))




        def _parse_target(data: object) -> None | TargetDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                target_type_1 = TargetDoc.from_dict(data)



                return target_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | TargetDoc | Unset, data)

        target = _parse_target(d.pop("target", UNSET))


        def _parse_camera(data: object) -> CameraDoc | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                camera_type_1 = CameraDoc.from_dict(data)



                return camera_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(CameraDoc | None | Unset, data)

        camera = _parse_camera(d.pop("camera", UNSET))


        def _parse_flange_to_camera_guess(data: object) -> None | PoseDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                flange_to_camera_guess_type_1 = PoseDoc.from_dict(data)



                return flange_to_camera_guess_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PoseDoc | Unset, data)

        flange_to_camera_guess = _parse_flange_to_camera_guess(d.pop("flange_to_camera_guess", UNSET))


        def _parse_camera_calibration_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        camera_calibration_id = _parse_camera_calibration_id(d.pop("camera_calibration_id", UNSET))


        def _parse_region(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        region = _parse_region(d.pop("region", UNSET))


        def _parse_volume(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        volume = _parse_volume(d.pop("volume", UNSET))


        def _parse_payload_kg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        payload_kg = _parse_payload_kg(d.pop("payload_kg", UNSET))


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


        session_spec_out = cls(
            instrument=instrument,
            target=target,
            camera=camera,
            flange_to_camera_guess=flange_to_camera_guess,
            camera_calibration_id=camera_calibration_id,
            region=region,
            volume=volume,
            payload_kg=payload_kg,
            controller=controller,
        )


        session_spec_out.additional_properties = d
        return session_spec_out

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
