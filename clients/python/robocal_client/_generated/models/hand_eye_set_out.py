from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.hand_eye_set_kind import HandEyeSetKind
from ..models.release_status import ReleaseStatus
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.frame_pose import FramePose
  from ..models.intrinsics import Intrinsics
  from ..models.parameter_report import ParameterReport





T = TypeVar("T", bound="HandEyeSetOut")



@_attrs_define
class HandEyeSetOut:
    """ 
        Attributes:
            serial (str):
            version (int):
            created_at (str):
            status (ReleaseStatus):
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
            job_id (None | str | Unset):
            status_reason (None | str | Unset): Why it has its status (the gate's comparison, or a person's reason).
            status_by (None | str | Unset): Who gave it (`gate`, `token:{id} ({name})`, `anonymous`; `null` for
                sets approved when the gate was introduced) and when.
            status_at (None | str | Unset):
            camera_calibration_id (None | str | Unset): The calibration (`"{serial}/{version}"`) whose intrinsics were held
                fixed.
     """

    serial: str
    version: int
    created_at: str
    status: ReleaseStatus
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
    job_id: None | str | Unset = UNSET
    status_reason: None | str | Unset = UNSET
    status_by: None | str | Unset = UNSET
    status_at: None | str | Unset = UNSET
    camera_calibration_id: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        serial = self.serial

        version = self.version

        created_at = self.created_at

        status = self.status.value

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

        job_id: None | str | Unset
        if isinstance(self.job_id, Unset):
            job_id = UNSET
        else:
            job_id = self.job_id

        status_reason: None | str | Unset
        if isinstance(self.status_reason, Unset):
            status_reason = UNSET
        else:
            status_reason = self.status_reason

        status_by: None | str | Unset
        if isinstance(self.status_by, Unset):
            status_by = UNSET
        else:
            status_by = self.status_by

        status_at: None | str | Unset
        if isinstance(self.status_at, Unset):
            status_at = UNSET
        else:
            status_at = self.status_at

        camera_calibration_id: None | str | Unset
        if isinstance(self.camera_calibration_id, Unset):
            camera_calibration_id = UNSET
        else:
            camera_calibration_id = self.camera_calibration_id


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "serial": serial,
            "version": version,
            "created_at": created_at,
            "status": status,
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
        if job_id is not UNSET:
            field_dict["job_id"] = job_id
        if status_reason is not UNSET:
            field_dict["status_reason"] = status_reason
        if status_by is not UNSET:
            field_dict["status_by"] = status_by
        if status_at is not UNSET:
            field_dict["status_at"] = status_at
        if camera_calibration_id is not UNSET:
            field_dict["camera_calibration_id"] = camera_calibration_id

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        d = dict(src_dict)
        serial = d.pop("serial")

        version = d.pop("version")

        created_at = d.pop("created_at")

        status = ReleaseStatus(d.pop("status"))




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




        def _parse_job_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        job_id = _parse_job_id(d.pop("job_id", UNSET))


        def _parse_status_reason(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_reason = _parse_status_reason(d.pop("status_reason", UNSET))


        def _parse_status_by(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_by = _parse_status_by(d.pop("status_by", UNSET))


        def _parse_status_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_at = _parse_status_at(d.pop("status_at", UNSET))


        def _parse_camera_calibration_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        camera_calibration_id = _parse_camera_calibration_id(d.pop("camera_calibration_id", UNSET))


        hand_eye_set_out = cls(
            serial=serial,
            version=version,
            created_at=created_at,
            status=status,
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
            job_id=job_id,
            status_reason=status_reason,
            status_by=status_by,
            status_at=status_at,
            camera_calibration_id=camera_calibration_id,
        )


        hand_eye_set_out.additional_properties = d
        return hand_eye_set_out

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
