from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="PoseImagePoint")



@_attrs_define
class PoseImagePoint:
    """ One image point of a pose (schema of `points`).

        Attributes:
            row (int):
            col (int):
            x (float): Dot centre in the image (px): uploaded or as the detector found it
                (the raw ellipse centre); after a calibration job measured the pose,
                the centre corrected for perspective bias by the calibrated camera
                model (what the fits use), the raw one then in `raw_x`, `raw_y`.
            y (float):
            raw_x (float | None | Unset): The raw centre (px), as detected or uploaded, when `x`, `y` are
                the bias-corrected one (after a calibration job; absent for the
                origin marker, which the fits leave out).
            raw_y (float | None | Unset):
            residual_px (list[float] | None | Unset): `[dx, dy]` (px) after a successful calibration: the observed centre
                (corrected for perspective bias) minus the calibrated model's
                projection of the dot. Absent for points the fit leaves out (the
                origin marker).
            outlier (bool | None | Unset): Dropped by the camera calibration as an outlier.
     """

    row: int
    col: int
    x: float
    y: float
    raw_x: float | None | Unset = UNSET
    raw_y: float | None | Unset = UNSET
    residual_px: list[float] | None | Unset = UNSET
    outlier: bool | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        row = self.row

        col = self.col

        x = self.x

        y = self.y

        raw_x: float | None | Unset
        if isinstance(self.raw_x, Unset):
            raw_x = UNSET
        else:
            raw_x = self.raw_x

        raw_y: float | None | Unset
        if isinstance(self.raw_y, Unset):
            raw_y = UNSET
        else:
            raw_y = self.raw_y

        residual_px: list[float] | None | Unset
        if isinstance(self.residual_px, Unset):
            residual_px = UNSET
        elif isinstance(self.residual_px, list):
            residual_px = self.residual_px


        else:
            residual_px = self.residual_px

        outlier: bool | None | Unset
        if isinstance(self.outlier, Unset):
            outlier = UNSET
        else:
            outlier = self.outlier


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "row": row,
            "col": col,
            "x": x,
            "y": y,
        })
        if raw_x is not UNSET:
            field_dict["raw_x"] = raw_x
        if raw_y is not UNSET:
            field_dict["raw_y"] = raw_y
        if residual_px is not UNSET:
            field_dict["residual_px"] = residual_px
        if outlier is not UNSET:
            field_dict["outlier"] = outlier

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        row = d.pop("row")

        col = d.pop("col")

        x = d.pop("x")

        y = d.pop("y")

        def _parse_raw_x(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        raw_x = _parse_raw_x(d.pop("raw_x", UNSET))


        def _parse_raw_y(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        raw_y = _parse_raw_y(d.pop("raw_y", UNSET))


        def _parse_residual_px(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                residual_px_type_0 = cast(list[float], data)

                return residual_px_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        residual_px = _parse_residual_px(d.pop("residual_px", UNSET))


        def _parse_outlier(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        outlier = _parse_outlier(d.pop("outlier", UNSET))


        pose_image_point = cls(
            row=row,
            col=col,
            x=x,
            y=y,
            raw_x=raw_x,
            raw_y=raw_y,
            residual_px=residual_px,
            outlier=outlier,
        )


        pose_image_point.additional_properties = d
        return pose_image_point

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
