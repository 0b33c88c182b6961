from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.frame_pose import FramePose





T = TypeVar("T", bound="PoseReport")



@_attrs_define
class PoseReport:
    """ Per pose: position error at that pose before (nominal kinematics, only
    base and hand–eye fitted) and after calibration, world frame, mm.

        Attributes:
            pose_id (str):
            set_ (str): "cal" or "val".
            joints_deg (list[float]):
            before_error_mm (list[float]):
            after_error_mm (list[float]):
            before_mm (float):
            after_mm (float):
            label (str | Unset): What the pose is called: the uploaded image's file name, a JSON
                pose's `label`, or its number in upload order (`#12`). Empty in
                reports stored before labels existed.
            reprojection_rms_px (float | None | Unset):
            outlier (bool | Unset): Left out of the fit: the pose's joints contradict its image (a wrong
                joint file, a pose recorded before the robot settled). Its errors
                say how far the two disagree; it counts in no statistic.
            reason (None | str | Unset): Why the pose was left out.
            camera_in_target (FramePose | None | Unset):
     """

    pose_id: str
    set_: str
    joints_deg: list[float]
    before_error_mm: list[float]
    after_error_mm: list[float]
    before_mm: float
    after_mm: float
    label: str | Unset = UNSET
    reprojection_rms_px: float | None | Unset = UNSET
    outlier: bool | Unset = UNSET
    reason: None | str | Unset = UNSET
    camera_in_target: FramePose | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        pose_id = self.pose_id

        set_ = self.set_

        joints_deg = self.joints_deg



        before_error_mm = self.before_error_mm



        after_error_mm = self.after_error_mm



        before_mm = self.before_mm

        after_mm = self.after_mm

        label = self.label

        reprojection_rms_px: float | None | Unset
        if isinstance(self.reprojection_rms_px, Unset):
            reprojection_rms_px = UNSET
        else:
            reprojection_rms_px = self.reprojection_rms_px

        outlier = self.outlier

        reason: None | str | Unset
        if isinstance(self.reason, Unset):
            reason = UNSET
        else:
            reason = self.reason

        camera_in_target: dict[str, Any] | None | Unset
        if isinstance(self.camera_in_target, Unset):
            camera_in_target = UNSET
        elif isinstance(self.camera_in_target, FramePose):
            camera_in_target = self.camera_in_target.to_dict()
        else:
            camera_in_target = self.camera_in_target


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "pose_id": pose_id,
            "set": set_,
            "joints_deg": joints_deg,
            "before_error_mm": before_error_mm,
            "after_error_mm": after_error_mm,
            "before_mm": before_mm,
            "after_mm": after_mm,
        })
        if label is not UNSET:
            field_dict["label"] = label
        if reprojection_rms_px is not UNSET:
            field_dict["reprojection_rms_px"] = reprojection_rms_px
        if outlier is not UNSET:
            field_dict["outlier"] = outlier
        if reason is not UNSET:
            field_dict["reason"] = reason
        if camera_in_target is not UNSET:
            field_dict["camera_in_target"] = camera_in_target

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        d = dict(src_dict)
        pose_id = d.pop("pose_id")

        set_ = d.pop("set")

        joints_deg = cast(list[float], d.pop("joints_deg"))


        before_error_mm = cast(list[float], d.pop("before_error_mm"))


        after_error_mm = cast(list[float], d.pop("after_error_mm"))


        before_mm = d.pop("before_mm")

        after_mm = d.pop("after_mm")

        label = d.pop("label", UNSET)

        def _parse_reprojection_rms_px(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        reprojection_rms_px = _parse_reprojection_rms_px(d.pop("reprojection_rms_px", UNSET))


        outlier = d.pop("outlier", UNSET)

        def _parse_reason(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        reason = _parse_reason(d.pop("reason", UNSET))


        def _parse_camera_in_target(data: object) -> FramePose | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                camera_in_target_type_1 = FramePose.from_dict(data)



                return camera_in_target_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FramePose | None | Unset, data)

        camera_in_target = _parse_camera_in_target(d.pop("camera_in_target", UNSET))


        pose_report = cls(
            pose_id=pose_id,
            set_=set_,
            joints_deg=joints_deg,
            before_error_mm=before_error_mm,
            after_error_mm=after_error_mm,
            before_mm=before_mm,
            after_mm=after_mm,
            label=label,
            reprojection_rms_px=reprojection_rms_px,
            outlier=outlier,
            reason=reason,
            camera_in_target=camera_in_target,
        )


        pose_report.additional_properties = d
        return pose_report

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
