from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.intrinsics_std import IntrinsicsStd
  from ..models.view_report import ViewReport





T = TypeVar("T", bound="CameraReport")



@_attrs_define
class CameraReport:
    """ 
        Attributes:
            fx (float):
            fy (float):
            cx (float):
            cy (float):
            k1 (float):
            k2 (float):
            p1 (float):
            p2 (float):
            k3 (float):
            mode (str): "refined" (default), "paper" (`refine_intrinsics: false`) or
                "fixed" (reused from `camera_calibration_id`).
            image_width (int):
            image_height (int):
            reprojection_rms_px (float):
            outliers_dropped (int):
            views (list[ViewReport]):
            camera_calibration_id (None | str | Unset): The earlier calibration (`"{serial}/{version}"`) whose intrinsics
                were held fixed.
            std (IntrinsicsStd | None | Unset):
     """

    fx: float
    fy: float
    cx: float
    cy: float
    k1: float
    k2: float
    p1: float
    p2: float
    k3: float
    mode: str
    image_width: int
    image_height: int
    reprojection_rms_px: float
    outliers_dropped: int
    views: list[ViewReport]
    camera_calibration_id: None | str | Unset = UNSET
    std: IntrinsicsStd | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.intrinsics_std import IntrinsicsStd # noqa: PLC0415
        from ..models.view_report import ViewReport # noqa: PLC0415
        fx = self.fx

        fy = self.fy

        cx = self.cx

        cy = self.cy

        k1 = self.k1

        k2 = self.k2

        p1 = self.p1

        p2 = self.p2

        k3 = self.k3

        mode = self.mode

        image_width = self.image_width

        image_height = self.image_height

        reprojection_rms_px = self.reprojection_rms_px

        outliers_dropped = self.outliers_dropped

        views = []
        for views_item_data in self.views:
            views_item = views_item_data.to_dict()
            views.append(views_item)



        camera_calibration_id: None | str | Unset
        if isinstance(self.camera_calibration_id, Unset):
            camera_calibration_id = UNSET
        else:
            camera_calibration_id = self.camera_calibration_id

        std: dict[str, Any] | None | Unset
        if isinstance(self.std, Unset):
            std = UNSET
        elif isinstance(self.std, IntrinsicsStd):
            std = self.std.to_dict()
        else:
            std = self.std


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "fx": fx,
            "fy": fy,
            "cx": cx,
            "cy": cy,
            "k1": k1,
            "k2": k2,
            "p1": p1,
            "p2": p2,
            "k3": k3,
            "mode": mode,
            "image_width": image_width,
            "image_height": image_height,
            "reprojection_rms_px": reprojection_rms_px,
            "outliers_dropped": outliers_dropped,
            "views": views,
        })
        if camera_calibration_id is not UNSET:
            field_dict["camera_calibration_id"] = camera_calibration_id
        if std is not UNSET:
            field_dict["std"] = std

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.intrinsics_std import IntrinsicsStd # noqa: PLC0415
        from ..models.view_report import ViewReport # noqa: PLC0415
        d = dict(src_dict)
        fx = d.pop("fx")

        fy = d.pop("fy")

        cx = d.pop("cx")

        cy = d.pop("cy")

        k1 = d.pop("k1")

        k2 = d.pop("k2")

        p1 = d.pop("p1")

        p2 = d.pop("p2")

        k3 = d.pop("k3")

        mode = d.pop("mode")

        image_width = d.pop("image_width")

        image_height = d.pop("image_height")

        reprojection_rms_px = d.pop("reprojection_rms_px")

        outliers_dropped = d.pop("outliers_dropped")

        views = []
        _views = d.pop("views")
        for views_item_data in (_views):
            views_item = ViewReport.from_dict(views_item_data)



            views.append(views_item)


        def _parse_camera_calibration_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        camera_calibration_id = _parse_camera_calibration_id(d.pop("camera_calibration_id", UNSET))


        def _parse_std(data: object) -> IntrinsicsStd | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                std_type_1 = IntrinsicsStd.from_dict(data)



                return std_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(IntrinsicsStd | None | Unset, data)

        std = _parse_std(d.pop("std", UNSET))


        camera_report = cls(
            fx=fx,
            fy=fy,
            cx=cx,
            cy=cy,
            k1=k1,
            k2=k2,
            p1=p1,
            p2=p2,
            k3=k3,
            mode=mode,
            image_width=image_width,
            image_height=image_height,
            reprojection_rms_px=reprojection_rms_px,
            outliers_dropped=outliers_dropped,
            views=views,
            camera_calibration_id=camera_calibration_id,
            std=std,
        )


        camera_report.additional_properties = d
        return camera_report

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
