from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="JobSummary")



@_attrs_define
class JobSummary:
    """ The job's `result.summary`: the poses it used and, after a calibration,
    the mean validation error before and after.

        Attributes:
            stage (None | str | Unset): The stage a validation-only run stopped after (`validate`).
            calibration_poses (int | Unset):  Default: 0.
            validation_poses (int | Unset):  Default: 0.
            joints (int | None | Unset): The robot's joint count (validation-only runs).
            before_mean_mm (float | None | Unset): Mean validation error of the nominal model (mm).
            after_mean_mm (float | None | Unset): Mean validation error of the identified model (mm).
            outliers (int | None | Unset): Poses left out as contradicting their image (hand–eye jobs).
            reprojection_rms_px (float | None | Unset): Reprojection RMS of the hand–eye bundle (hand–eye jobs).
            board_scale (float | None | Unset): The board's fitted scale against its configured spacing (hand–eye
                jobs that fit it).
     """

    stage: None | str | Unset = UNSET
    calibration_poses: int | Unset = 0
    validation_poses: int | Unset = 0
    joints: int | None | Unset = UNSET
    before_mean_mm: float | None | Unset = UNSET
    after_mean_mm: float | None | Unset = UNSET
    outliers: int | None | Unset = UNSET
    reprojection_rms_px: float | None | Unset = UNSET
    board_scale: float | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        stage: None | str | Unset
        if isinstance(self.stage, Unset):
            stage = UNSET
        else:
            stage = self.stage

        calibration_poses = self.calibration_poses

        validation_poses = self.validation_poses

        joints: int | None | Unset
        if isinstance(self.joints, Unset):
            joints = UNSET
        else:
            joints = self.joints

        before_mean_mm: float | None | Unset
        if isinstance(self.before_mean_mm, Unset):
            before_mean_mm = UNSET
        else:
            before_mean_mm = self.before_mean_mm

        after_mean_mm: float | None | Unset
        if isinstance(self.after_mean_mm, Unset):
            after_mean_mm = UNSET
        else:
            after_mean_mm = self.after_mean_mm

        outliers: int | None | Unset
        if isinstance(self.outliers, Unset):
            outliers = UNSET
        else:
            outliers = self.outliers

        reprojection_rms_px: float | None | Unset
        if isinstance(self.reprojection_rms_px, Unset):
            reprojection_rms_px = UNSET
        else:
            reprojection_rms_px = self.reprojection_rms_px

        board_scale: float | None | Unset
        if isinstance(self.board_scale, Unset):
            board_scale = UNSET
        else:
            board_scale = self.board_scale


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
        })
        if stage is not UNSET:
            field_dict["stage"] = stage
        if calibration_poses is not UNSET:
            field_dict["calibration_poses"] = calibration_poses
        if validation_poses is not UNSET:
            field_dict["validation_poses"] = validation_poses
        if joints is not UNSET:
            field_dict["joints"] = joints
        if before_mean_mm is not UNSET:
            field_dict["before_mean_mm"] = before_mean_mm
        if after_mean_mm is not UNSET:
            field_dict["after_mean_mm"] = after_mean_mm
        if outliers is not UNSET:
            field_dict["outliers"] = outliers
        if reprojection_rms_px is not UNSET:
            field_dict["reprojection_rms_px"] = reprojection_rms_px
        if board_scale is not UNSET:
            field_dict["board_scale"] = board_scale

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        def _parse_stage(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        stage = _parse_stage(d.pop("stage", UNSET))


        calibration_poses = d.pop("calibration_poses", UNSET)

        validation_poses = d.pop("validation_poses", UNSET)

        def _parse_joints(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        joints = _parse_joints(d.pop("joints", UNSET))


        def _parse_before_mean_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        before_mean_mm = _parse_before_mean_mm(d.pop("before_mean_mm", UNSET))


        def _parse_after_mean_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        after_mean_mm = _parse_after_mean_mm(d.pop("after_mean_mm", UNSET))


        def _parse_outliers(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        outliers = _parse_outliers(d.pop("outliers", UNSET))


        def _parse_reprojection_rms_px(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        reprojection_rms_px = _parse_reprojection_rms_px(d.pop("reprojection_rms_px", UNSET))


        def _parse_board_scale(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        board_scale = _parse_board_scale(d.pop("board_scale", UNSET))


        job_summary = cls(
            stage=stage,
            calibration_poses=calibration_poses,
            validation_poses=validation_poses,
            joints=joints,
            before_mean_mm=before_mean_mm,
            after_mean_mm=after_mean_mm,
            outliers=outliers,
            reprojection_rms_px=reprojection_rms_px,
            board_scale=board_scale,
        )


        job_summary.additional_properties = d
        return job_summary

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
