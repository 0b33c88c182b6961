from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.board_scale_report import BoardScaleReport
  from ..models.frame_report import FrameReport





T = TypeVar("T", bound="HandEyeReport")



@_attrs_define
class HandEyeReport:
    """ 
        Attributes:
            flange_to_camera (FrameReport): A fitted rigid transform: translation (mm), fixed-axis X-Y-Z angles
                (deg, `R = Rz Ry Rx`), the 4x4 row-major matrix, and its standard
                deviations (mm; small-angle rotation in deg about the outer frame's
                axes).
            target_to_base (FrameReport): A fitted rigid transform: translation (mm), fixed-axis X-Y-Z angles
                (deg, `R = Rz Ry Rx`), the 4x4 row-major matrix, and its standard
                deviations (mm; small-angle rotation in deg about the outer frame's
                axes).
            base_to_target (FrameReport): A fitted rigid transform: translation (mm), fixed-axis X-Y-Z angles
                (deg, `R = Rz Ry Rx`), the 4x4 row-major matrix, and its standard
                deviations (mm; small-angle rotation in deg about the outer frame's
                axes).
            board_scale (BoardScaleReport): What the data say of the board's size: the fitted scale on the
                configured one, and the feature spacing it implies.
            std_source (str): `"jackknife"` or `"formal"`: which standard deviations `std_*` are.
            reprojection_rms_px (float): RMS reprojection over the poses in the fit (px, per point).
            sigma_px (float): Residual standard deviation per image axis (px).
            poses_used (int): Calibration poses in the fit, and image points they hold.
            points (int):
     """

    flange_to_camera: FrameReport
    target_to_base: FrameReport
    base_to_target: FrameReport
    board_scale: BoardScaleReport
    std_source: str
    reprojection_rms_px: float
    sigma_px: float
    poses_used: int
    points: int
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.board_scale_report import BoardScaleReport # noqa: PLC0415
        from ..models.frame_report import FrameReport # noqa: PLC0415
        flange_to_camera = self.flange_to_camera.to_dict()

        target_to_base = self.target_to_base.to_dict()

        base_to_target = self.base_to_target.to_dict()

        board_scale = self.board_scale.to_dict()

        std_source = self.std_source

        reprojection_rms_px = self.reprojection_rms_px

        sigma_px = self.sigma_px

        poses_used = self.poses_used

        points = self.points


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "flange_to_camera": flange_to_camera,
            "target_to_base": target_to_base,
            "base_to_target": base_to_target,
            "board_scale": board_scale,
            "std_source": std_source,
            "reprojection_rms_px": reprojection_rms_px,
            "sigma_px": sigma_px,
            "poses_used": poses_used,
            "points": points,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.board_scale_report import BoardScaleReport # noqa: PLC0415
        from ..models.frame_report import FrameReport # noqa: PLC0415
        d = dict(src_dict)
        flange_to_camera = FrameReport.from_dict(d.pop("flange_to_camera"))




        target_to_base = FrameReport.from_dict(d.pop("target_to_base"))




        base_to_target = FrameReport.from_dict(d.pop("base_to_target"))




        board_scale = BoardScaleReport.from_dict(d.pop("board_scale"))




        std_source = d.pop("std_source")

        reprojection_rms_px = d.pop("reprojection_rms_px")

        sigma_px = d.pop("sigma_px")

        poses_used = d.pop("poses_used")

        points = d.pop("points")

        hand_eye_report = cls(
            flange_to_camera=flange_to_camera,
            target_to_base=target_to_base,
            base_to_target=base_to_target,
            board_scale=board_scale,
            std_source=std_source,
            reprojection_rms_px=reprojection_rms_px,
            sigma_px=sigma_px,
            poses_used=poses_used,
            points=points,
        )


        hand_eye_report.additional_properties = d
        return hand_eye_report

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
