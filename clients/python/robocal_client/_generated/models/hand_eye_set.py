from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.hand_eye_set_kind import HandEyeSetKind
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.frame_pose import FramePose
  from ..models.intrinsics import Intrinsics
  from ..models.parameter_report import ParameterReport





T = TypeVar("T", bound="HandEyeSet")



@_attrs_define
class HandEyeSet:
    """ A hand–eye set (`kind` `hand_eye`), from a session of controller flange
    poses.

        Attributes:
            instrument (str): Always `camera`.
            session_id (str): The session the set was calibrated from.
            target_to_base (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
            flange_to_camera (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
            base_to_target (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
            board_scale (float): True board coordinates / configured ones.
            camera (Intrinsics): Pinhole intrinsics (px) and Brown–Conrady distortion.
            camera_mode (str): How `camera` was obtained: `refined`, `paper` or `fixed`.
            fixed (list[str]): Parameters held fixed (none for a hand–eye fit).
            parameters (list[ParameterReport]): Each frame's six parameters and the board scale, guess against fit.
            kind (HandEyeSetKind): What the set identified (the variant's tag).
            camera_calibration_id (None | str | Unset): The calibration (`"{serial}/{version}"`) whose intrinsics were held
                fixed.
     """

    instrument: str
    session_id: str
    target_to_base: FramePose
    flange_to_camera: FramePose
    base_to_target: FramePose
    board_scale: float
    camera: Intrinsics
    camera_mode: str
    fixed: list[str]
    parameters: list[ParameterReport]
    kind: HandEyeSetKind
    camera_calibration_id: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        instrument = self.instrument

        session_id = self.session_id

        target_to_base = self.target_to_base.to_dict()

        flange_to_camera = self.flange_to_camera.to_dict()

        base_to_target = self.base_to_target.to_dict()

        board_scale = self.board_scale

        camera = self.camera.to_dict()

        camera_mode = self.camera_mode

        fixed = self.fixed



        parameters = []
        for parameters_item_data in self.parameters:
            parameters_item = parameters_item_data.to_dict()
            parameters.append(parameters_item)



        kind = self.kind.value

        camera_calibration_id: None | str | Unset
        if isinstance(self.camera_calibration_id, Unset):
            camera_calibration_id = UNSET
        else:
            camera_calibration_id = self.camera_calibration_id


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "instrument": instrument,
            "session_id": session_id,
            "target_to_base": target_to_base,
            "flange_to_camera": flange_to_camera,
            "base_to_target": base_to_target,
            "board_scale": board_scale,
            "camera": camera,
            "camera_mode": camera_mode,
            "fixed": fixed,
            "parameters": parameters,
            "kind": kind,
        })
        if camera_calibration_id is not UNSET:
            field_dict["camera_calibration_id"] = camera_calibration_id

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        d = dict(src_dict)
        instrument = d.pop("instrument")

        session_id = d.pop("session_id")

        target_to_base = FramePose.from_dict(d.pop("target_to_base"))




        flange_to_camera = FramePose.from_dict(d.pop("flange_to_camera"))




        base_to_target = FramePose.from_dict(d.pop("base_to_target"))




        board_scale = d.pop("board_scale")

        camera = Intrinsics.from_dict(d.pop("camera"))




        camera_mode = d.pop("camera_mode")

        fixed = cast(list[str], d.pop("fixed"))


        parameters = []
        _parameters = d.pop("parameters")
        for parameters_item_data in (_parameters):
            parameters_item = ParameterReport.from_dict(parameters_item_data)



            parameters.append(parameters_item)


        kind = HandEyeSetKind(d.pop("kind"))




        def _parse_camera_calibration_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        camera_calibration_id = _parse_camera_calibration_id(d.pop("camera_calibration_id", UNSET))


        hand_eye_set = cls(
            instrument=instrument,
            session_id=session_id,
            target_to_base=target_to_base,
            flange_to_camera=flange_to_camera,
            base_to_target=base_to_target,
            board_scale=board_scale,
            camera=camera,
            camera_mode=camera_mode,
            fixed=fixed,
            parameters=parameters,
            kind=kind,
            camera_calibration_id=camera_calibration_id,
        )


        hand_eye_set.additional_properties = d
        return hand_eye_set

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
