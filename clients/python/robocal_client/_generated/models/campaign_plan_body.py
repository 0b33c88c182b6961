from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.plan_purpose_doc import PlanPurposeDoc
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.camera_doc import CameraDoc
  from ..models.keep_out_doc import KeepOutDoc
  from ..models.pose_doc import PoseDoc
  from ..models.target_doc import TargetDoc





T = TypeVar("T", bound="CampaignPlanBody")



@_attrs_define
class CampaignPlanBody:
    """ `POST /v1/robots/{serial}/campaign-plans` body.

        Attributes:
            poses (int): Calibration poses to plan (5 to 10: a quick check by default).
            target (None | TargetDoc | Unset):
            camera (CameraDoc | None | Unset):
            camera_calibration_id (None | str | Unset): A parameter set `"{serial}/{version}"` (or `"/latest"`) whose camera
                intrinsics the campaign's job will reuse and hold.
            flange_to_camera_guess (None | PoseDoc | Unset):
            target_to_base_guess (None | PoseDoc | Unset):
            validation_poses (int | Unset):
            distance_mm (list[float] | Unset): Camera-to-board-centre distance range.
            view_angle_deg (list[float] | Unset): Range of the angle between the line of sight and the board normal.
            joint_limits_deg (list[list[float]] | None | Unset): Per joint `[min, max]`, tighter than the robot's.
            keep_out (list[KeepOutDoc] | None | Unset):
            start_joints_deg (list[float] | None | Unset): Where the robot stands before the campaign; the path starts here.
            sigma_px (float | None | Unset): Dot noise for the prediction (px per image axis); default: what the
                robot's newest camera job measured on images of this size, else 0.1 px.
            purpose (None | PlanPurposeDoc | Unset):
            extend_session (None | str | Unset): A camera session of this robot whose campaign the plan extends:
                its `cal` poses' joints seed the selection, only the poses to add
                are returned (`poses` of them), and `predicted` says what the
                session's campaign achieves alone and with them. The purpose is then
                a calibration unless stated.
     """

    poses: int
    target: None | TargetDoc | Unset = UNSET
    camera: CameraDoc | None | Unset = UNSET
    camera_calibration_id: None | str | Unset = UNSET
    flange_to_camera_guess: None | PoseDoc | Unset = UNSET
    target_to_base_guess: None | PoseDoc | Unset = UNSET
    validation_poses: int | Unset = UNSET
    distance_mm: list[float] | Unset = UNSET
    view_angle_deg: list[float] | Unset = UNSET
    joint_limits_deg: list[list[float]] | None | Unset = UNSET
    keep_out: list[KeepOutDoc] | None | Unset = UNSET
    start_joints_deg: list[float] | None | Unset = UNSET
    sigma_px: float | None | Unset = UNSET
    purpose: None | PlanPurposeDoc | Unset = UNSET
    extend_session: None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.camera_doc import CameraDoc # noqa: PLC0415
        from ..models.keep_out_doc import KeepOutDoc # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        from ..models.target_doc import TargetDoc # noqa: PLC0415
        poses = self.poses

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

        camera_calibration_id: None | str | Unset
        if isinstance(self.camera_calibration_id, Unset):
            camera_calibration_id = UNSET
        else:
            camera_calibration_id = self.camera_calibration_id

        flange_to_camera_guess: dict[str, Any] | None | Unset
        if isinstance(self.flange_to_camera_guess, Unset):
            flange_to_camera_guess = UNSET
        elif isinstance(self.flange_to_camera_guess, PoseDoc):
            flange_to_camera_guess = self.flange_to_camera_guess.to_dict()
        else:
            flange_to_camera_guess = self.flange_to_camera_guess

        target_to_base_guess: dict[str, Any] | None | Unset
        if isinstance(self.target_to_base_guess, Unset):
            target_to_base_guess = UNSET
        elif isinstance(self.target_to_base_guess, PoseDoc):
            target_to_base_guess = self.target_to_base_guess.to_dict()
        else:
            target_to_base_guess = self.target_to_base_guess

        validation_poses = self.validation_poses

        distance_mm: list[float] | Unset = UNSET
        if not isinstance(self.distance_mm, Unset):
            distance_mm = self.distance_mm



        view_angle_deg: list[float] | Unset = UNSET
        if not isinstance(self.view_angle_deg, Unset):
            view_angle_deg = self.view_angle_deg



        joint_limits_deg: list[list[float]] | None | Unset
        if isinstance(self.joint_limits_deg, Unset):
            joint_limits_deg = UNSET
        elif isinstance(self.joint_limits_deg, list):
            joint_limits_deg = []
            for joint_limits_deg_type_0_item_data in self.joint_limits_deg:
                joint_limits_deg_type_0_item = joint_limits_deg_type_0_item_data


                joint_limits_deg.append(joint_limits_deg_type_0_item)


        else:
            joint_limits_deg = self.joint_limits_deg

        keep_out: list[dict[str, Any]] | None | Unset
        if isinstance(self.keep_out, Unset):
            keep_out = UNSET
        elif isinstance(self.keep_out, list):
            keep_out = []
            for keep_out_type_0_item_data in self.keep_out:
                keep_out_type_0_item = keep_out_type_0_item_data.to_dict()
                keep_out.append(keep_out_type_0_item)


        else:
            keep_out = self.keep_out

        start_joints_deg: list[float] | None | Unset
        if isinstance(self.start_joints_deg, Unset):
            start_joints_deg = UNSET
        elif isinstance(self.start_joints_deg, list):
            start_joints_deg = self.start_joints_deg


        else:
            start_joints_deg = self.start_joints_deg

        sigma_px: float | None | Unset
        if isinstance(self.sigma_px, Unset):
            sigma_px = UNSET
        else:
            sigma_px = self.sigma_px

        purpose: None | str | Unset
        if isinstance(self.purpose, Unset):
            purpose = UNSET
        elif isinstance(self.purpose, PlanPurposeDoc):
            purpose = self.purpose.value
        else:
            purpose = self.purpose

        extend_session: None | str | Unset
        if isinstance(self.extend_session, Unset):
            extend_session = UNSET
        else:
            extend_session = self.extend_session


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "poses": poses,
        })
        if target is not UNSET:
            field_dict["target"] = target
        if camera is not UNSET:
            field_dict["camera"] = camera
        if camera_calibration_id is not UNSET:
            field_dict["camera_calibration_id"] = camera_calibration_id
        if flange_to_camera_guess is not UNSET:
            field_dict["flange_to_camera_guess"] = flange_to_camera_guess
        if target_to_base_guess is not UNSET:
            field_dict["target_to_base_guess"] = target_to_base_guess
        if validation_poses is not UNSET:
            field_dict["validation_poses"] = validation_poses
        if distance_mm is not UNSET:
            field_dict["distance_mm"] = distance_mm
        if view_angle_deg is not UNSET:
            field_dict["view_angle_deg"] = view_angle_deg
        if joint_limits_deg is not UNSET:
            field_dict["joint_limits_deg"] = joint_limits_deg
        if keep_out is not UNSET:
            field_dict["keep_out"] = keep_out
        if start_joints_deg is not UNSET:
            field_dict["start_joints_deg"] = start_joints_deg
        if sigma_px is not UNSET:
            field_dict["sigma_px"] = sigma_px
        if purpose is not UNSET:
            field_dict["purpose"] = purpose
        if extend_session is not UNSET:
            field_dict["extend_session"] = extend_session

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.camera_doc import CameraDoc # noqa: PLC0415
        from ..models.keep_out_doc import KeepOutDoc # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        from ..models.target_doc import TargetDoc # noqa: PLC0415
        d = dict(src_dict)
        poses = d.pop("poses")

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


        def _parse_camera_calibration_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        camera_calibration_id = _parse_camera_calibration_id(d.pop("camera_calibration_id", UNSET))


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


        def _parse_target_to_base_guess(data: object) -> None | PoseDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                target_to_base_guess_type_1 = PoseDoc.from_dict(data)



                return target_to_base_guess_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PoseDoc | Unset, data)

        target_to_base_guess = _parse_target_to_base_guess(d.pop("target_to_base_guess", UNSET))


        validation_poses = d.pop("validation_poses", UNSET)

        distance_mm = cast(list[float], d.pop("distance_mm", UNSET))


        view_angle_deg = cast(list[float], d.pop("view_angle_deg", UNSET))


        def _parse_joint_limits_deg(data: object) -> list[list[float]] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                joint_limits_deg_type_0 = []
                _joint_limits_deg_type_0 = data
                for joint_limits_deg_type_0_item_data in (_joint_limits_deg_type_0):
                    joint_limits_deg_type_0_item = cast(list[float], joint_limits_deg_type_0_item_data)

                    joint_limits_deg_type_0.append(joint_limits_deg_type_0_item)

                return joint_limits_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[list[float]] | None | Unset, data)

        joint_limits_deg = _parse_joint_limits_deg(d.pop("joint_limits_deg", UNSET))


        def _parse_keep_out(data: object) -> list[KeepOutDoc] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                keep_out_type_0 = []
                _keep_out_type_0 = data
                for keep_out_type_0_item_data in (_keep_out_type_0):
                    keep_out_type_0_item = KeepOutDoc.from_dict(keep_out_type_0_item_data)



                    keep_out_type_0.append(keep_out_type_0_item)

                return keep_out_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[KeepOutDoc] | None | Unset, data)

        keep_out = _parse_keep_out(d.pop("keep_out", UNSET))


        def _parse_start_joints_deg(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                start_joints_deg_type_0 = cast(list[float], data)

                return start_joints_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        start_joints_deg = _parse_start_joints_deg(d.pop("start_joints_deg", UNSET))


        def _parse_sigma_px(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        sigma_px = _parse_sigma_px(d.pop("sigma_px", UNSET))


        def _parse_purpose(data: object) -> None | PlanPurposeDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                purpose_type_1 = PlanPurposeDoc(data)



                return purpose_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PlanPurposeDoc | Unset, data)

        purpose = _parse_purpose(d.pop("purpose", UNSET))


        def _parse_extend_session(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        extend_session = _parse_extend_session(d.pop("extend_session", UNSET))


        campaign_plan_body = cls(
            poses=poses,
            target=target,
            camera=camera,
            camera_calibration_id=camera_calibration_id,
            flange_to_camera_guess=flange_to_camera_guess,
            target_to_base_guess=target_to_base_guess,
            validation_poses=validation_poses,
            distance_mm=distance_mm,
            view_angle_deg=view_angle_deg,
            joint_limits_deg=joint_limits_deg,
            keep_out=keep_out,
            start_joints_deg=start_joints_deg,
            sigma_px=sigma_px,
            purpose=purpose,
            extend_session=extend_session,
        )

        return campaign_plan_body

