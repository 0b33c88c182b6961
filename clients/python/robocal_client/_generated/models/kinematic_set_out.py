from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.instrument import Instrument
from ..models.kinematic_set_kind import KinematicSetKind
from ..models.measurement import Measurement
from ..models.release_status import ReleaseStatus
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.controller_identity import ControllerIdentity
  from ..models.covariance_doc import CovarianceDoc
  from ..models.frame_pose import FramePose
  from ..models.intrinsics import Intrinsics
  from ..models.kinematics_doc import KinematicsDoc
  from ..models.parameter_report import ParameterReport
  from ..models.session_board import SessionBoard
  from ..models.terms_doc import TermsDoc





T = TypeVar("T", bound="KinematicSetOut")



@_attrs_define
class KinematicSetOut:
    """ 
        Attributes:
            serial (str):
            version (int):
            created_at (str):
            status (ReleaseStatus):
            instrument (Instrument): The session's instrument.
            session_id (str): The session the parameters were identified from.
            kinematics (KinematicsDoc):
            fixed (list[str]): Parameters held fixed as unidentifiable.
            parameters (list[ParameterReport]): Every identified parameter against its nominal value.
            kind (KinematicSetKind): What the set identified (the variant's tag).
            job_id (None | str | Unset):
            status_reason (None | str | Unset): Why it has its status (the gate's comparison, or a person's reason).
            status_by (None | str | Unset): Who gave it (`gate`, `token:{id} ({name})`, `anonymous`; `null` for
                sets approved when the gate was introduced) and when.
            status_at (None | str | Unset):
            measurement (Measurement | None | Unset):
            target_to_base (FramePose | None | Unset):
            instrument_to_base (FramePose | None | Unset):
            flange_to_camera (FramePose | None | Unset):
            flange_to_tool (FramePose | None | Unset):
            camera (Intrinsics | None | Unset):
            camera_mode (None | str | Unset): How `camera` was obtained: `refined`, `paper` or `fixed`.
            camera_calibration_id (None | str | Unset): The calibration (`"{serial}/{version}"`) whose intrinsics were held
                fixed.
            covariance (CovarianceDoc | None | Unset):
            joint_noise_deg (float | None | Unset): Joint noise (deg, one standard deviation per joint) the joint
                refinement estimated from the images; absent when it did not run.
            terms (None | TermsDoc | Unset):
            session_target_to_base (list[SessionBoard] | Unset): A set calibrated over several sessions (board placements):
                each
                session's board in the base frame, the first equal to
                `target_to_base`. Absent for a one-session set.
            controller (ControllerIdentity | None | Unset):
     """

    serial: str
    version: int
    created_at: str
    status: ReleaseStatus
    instrument: Instrument
    session_id: str
    kinematics: KinematicsDoc
    fixed: list[str]
    parameters: list[ParameterReport]
    kind: KinematicSetKind
    job_id: None | str | Unset = UNSET
    status_reason: None | str | Unset = UNSET
    status_by: None | str | Unset = UNSET
    status_at: None | str | Unset = UNSET
    measurement: Measurement | None | Unset = UNSET
    target_to_base: FramePose | None | Unset = UNSET
    instrument_to_base: FramePose | None | Unset = UNSET
    flange_to_camera: FramePose | None | Unset = UNSET
    flange_to_tool: FramePose | None | Unset = UNSET
    camera: Intrinsics | None | Unset = UNSET
    camera_mode: None | str | Unset = UNSET
    camera_calibration_id: None | str | Unset = UNSET
    covariance: CovarianceDoc | None | Unset = UNSET
    joint_noise_deg: float | None | Unset = UNSET
    terms: None | TermsDoc | Unset = UNSET
    session_target_to_base: list[SessionBoard] | Unset = UNSET
    controller: ControllerIdentity | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.covariance_doc import CovarianceDoc # noqa: PLC0415
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.kinematics_doc import KinematicsDoc # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        from ..models.session_board import SessionBoard # noqa: PLC0415
        from ..models.terms_doc import TermsDoc # noqa: PLC0415
        serial = self.serial

        version = self.version

        created_at = self.created_at

        status = self.status.value

        instrument = self.instrument.value

        session_id = self.session_id

        kinematics = self.kinematics.to_dict()

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

        measurement: None | str | Unset
        if isinstance(self.measurement, Unset):
            measurement = UNSET
        elif isinstance(self.measurement, Measurement):
            measurement = self.measurement.value
        else:
            measurement = self.measurement

        target_to_base: dict[str, Any] | None | Unset
        if isinstance(self.target_to_base, Unset):
            target_to_base = UNSET
        elif isinstance(self.target_to_base, FramePose):
            target_to_base = self.target_to_base.to_dict()
        else:
            target_to_base = self.target_to_base

        instrument_to_base: dict[str, Any] | None | Unset
        if isinstance(self.instrument_to_base, Unset):
            instrument_to_base = UNSET
        elif isinstance(self.instrument_to_base, FramePose):
            instrument_to_base = self.instrument_to_base.to_dict()
        else:
            instrument_to_base = self.instrument_to_base

        flange_to_camera: dict[str, Any] | None | Unset
        if isinstance(self.flange_to_camera, Unset):
            flange_to_camera = UNSET
        elif isinstance(self.flange_to_camera, FramePose):
            flange_to_camera = self.flange_to_camera.to_dict()
        else:
            flange_to_camera = self.flange_to_camera

        flange_to_tool: dict[str, Any] | None | Unset
        if isinstance(self.flange_to_tool, Unset):
            flange_to_tool = UNSET
        elif isinstance(self.flange_to_tool, FramePose):
            flange_to_tool = self.flange_to_tool.to_dict()
        else:
            flange_to_tool = self.flange_to_tool

        camera: dict[str, Any] | None | Unset
        if isinstance(self.camera, Unset):
            camera = UNSET
        elif isinstance(self.camera, Intrinsics):
            camera = self.camera.to_dict()
        else:
            camera = self.camera

        camera_mode: None | str | Unset
        if isinstance(self.camera_mode, Unset):
            camera_mode = UNSET
        else:
            camera_mode = self.camera_mode

        camera_calibration_id: None | str | Unset
        if isinstance(self.camera_calibration_id, Unset):
            camera_calibration_id = UNSET
        else:
            camera_calibration_id = self.camera_calibration_id

        covariance: dict[str, Any] | None | Unset
        if isinstance(self.covariance, Unset):
            covariance = UNSET
        elif isinstance(self.covariance, CovarianceDoc):
            covariance = self.covariance.to_dict()
        else:
            covariance = self.covariance

        joint_noise_deg: float | None | Unset
        if isinstance(self.joint_noise_deg, Unset):
            joint_noise_deg = UNSET
        else:
            joint_noise_deg = self.joint_noise_deg

        terms: dict[str, Any] | None | Unset
        if isinstance(self.terms, Unset):
            terms = UNSET
        elif isinstance(self.terms, TermsDoc):
            terms = self.terms.to_dict()
        else:
            terms = self.terms

        session_target_to_base: list[dict[str, Any]] | Unset = UNSET
        if not isinstance(self.session_target_to_base, Unset):
            session_target_to_base = []
            for session_target_to_base_item_data in self.session_target_to_base:
                session_target_to_base_item = session_target_to_base_item_data.to_dict()
                session_target_to_base.append(session_target_to_base_item)



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
            "serial": serial,
            "version": version,
            "created_at": created_at,
            "status": status,
            "instrument": instrument,
            "session_id": session_id,
            "kinematics": kinematics,
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
        if measurement is not UNSET:
            field_dict["measurement"] = measurement
        if target_to_base is not UNSET:
            field_dict["target_to_base"] = target_to_base
        if instrument_to_base is not UNSET:
            field_dict["instrument_to_base"] = instrument_to_base
        if flange_to_camera is not UNSET:
            field_dict["flange_to_camera"] = flange_to_camera
        if flange_to_tool is not UNSET:
            field_dict["flange_to_tool"] = flange_to_tool
        if camera is not UNSET:
            field_dict["camera"] = camera
        if camera_mode is not UNSET:
            field_dict["camera_mode"] = camera_mode
        if camera_calibration_id is not UNSET:
            field_dict["camera_calibration_id"] = camera_calibration_id
        if covariance is not UNSET:
            field_dict["covariance"] = covariance
        if joint_noise_deg is not UNSET:
            field_dict["joint_noise_deg"] = joint_noise_deg
        if terms is not UNSET:
            field_dict["terms"] = terms
        if session_target_to_base is not UNSET:
            field_dict["session_target_to_base"] = session_target_to_base
        if controller is not UNSET:
            field_dict["controller"] = controller

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.covariance_doc import CovarianceDoc # noqa: PLC0415
        from ..models.frame_pose import FramePose # noqa: PLC0415
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.kinematics_doc import KinematicsDoc # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        from ..models.session_board import SessionBoard # noqa: PLC0415
        from ..models.terms_doc import TermsDoc # noqa: PLC0415
        d = dict(src_dict)
        serial = d.pop("serial")

        version = d.pop("version")

        created_at = d.pop("created_at")

        status = ReleaseStatus(d.pop("status"))




        instrument = Instrument(d.pop("instrument"))




        session_id = d.pop("session_id")

        kinematics = KinematicsDoc.from_dict(d.pop("kinematics"))




        fixed = cast(list[str], d.pop("fixed"))


        parameters = []
        _parameters = d.pop("parameters")
        for parameters_item_data in (_parameters):
            parameters_item = ParameterReport.from_dict(parameters_item_data)



            parameters.append(parameters_item)


        kind = KinematicSetKind(d.pop("kind"))




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


        def _parse_target_to_base(data: object) -> FramePose | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                target_to_base_type_1 = FramePose.from_dict(data)



                return target_to_base_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FramePose | None | Unset, data)

        target_to_base = _parse_target_to_base(d.pop("target_to_base", UNSET))


        def _parse_instrument_to_base(data: object) -> FramePose | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                instrument_to_base_type_1 = FramePose.from_dict(data)



                return instrument_to_base_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FramePose | None | Unset, data)

        instrument_to_base = _parse_instrument_to_base(d.pop("instrument_to_base", UNSET))


        def _parse_flange_to_camera(data: object) -> FramePose | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                flange_to_camera_type_1 = FramePose.from_dict(data)



                return flange_to_camera_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FramePose | None | Unset, data)

        flange_to_camera = _parse_flange_to_camera(d.pop("flange_to_camera", UNSET))


        def _parse_flange_to_tool(data: object) -> FramePose | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                flange_to_tool_type_1 = FramePose.from_dict(data)



                return flange_to_tool_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FramePose | None | Unset, data)

        flange_to_tool = _parse_flange_to_tool(d.pop("flange_to_tool", UNSET))


        def _parse_camera(data: object) -> Intrinsics | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                camera_type_1 = Intrinsics.from_dict(data)



                return camera_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(Intrinsics | None | Unset, data)

        camera = _parse_camera(d.pop("camera", UNSET))


        def _parse_camera_mode(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        camera_mode = _parse_camera_mode(d.pop("camera_mode", UNSET))


        def _parse_camera_calibration_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        camera_calibration_id = _parse_camera_calibration_id(d.pop("camera_calibration_id", UNSET))


        def _parse_covariance(data: object) -> CovarianceDoc | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                covariance_type_1 = CovarianceDoc.from_dict(data)



                return covariance_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(CovarianceDoc | None | Unset, data)

        covariance = _parse_covariance(d.pop("covariance", UNSET))


        def _parse_joint_noise_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        joint_noise_deg = _parse_joint_noise_deg(d.pop("joint_noise_deg", UNSET))


        def _parse_terms(data: object) -> None | TermsDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                terms_type_1 = TermsDoc.from_dict(data)



                return terms_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | TermsDoc | Unset, data)

        terms = _parse_terms(d.pop("terms", UNSET))


        _session_target_to_base = d.pop("session_target_to_base", UNSET)
        session_target_to_base: list[SessionBoard] | Unset = UNSET
        if _session_target_to_base is not UNSET:
            session_target_to_base = []
            for session_target_to_base_item_data in _session_target_to_base:
                session_target_to_base_item = SessionBoard.from_dict(session_target_to_base_item_data)



                session_target_to_base.append(session_target_to_base_item)


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


        kinematic_set_out = cls(
            serial=serial,
            version=version,
            created_at=created_at,
            status=status,
            instrument=instrument,
            session_id=session_id,
            kinematics=kinematics,
            fixed=fixed,
            parameters=parameters,
            kind=kind,
            job_id=job_id,
            status_reason=status_reason,
            status_by=status_by,
            status_at=status_at,
            measurement=measurement,
            target_to_base=target_to_base,
            instrument_to_base=instrument_to_base,
            flange_to_camera=flange_to_camera,
            flange_to_tool=flange_to_tool,
            camera=camera,
            camera_mode=camera_mode,
            camera_calibration_id=camera_calibration_id,
            covariance=covariance,
            joint_noise_deg=joint_noise_deg,
            terms=terms,
            session_target_to_base=session_target_to_base,
            controller=controller,
        )


        kinematic_set_out.additional_properties = d
        return kinematic_set_out

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
