from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ViewReport")



@_attrs_define
class ViewReport:
    """ One camera view's fit.

        Attributes:
            pose_id (str):
            rms_px (float):
            board_angle_deg (float):
            label (str | Unset): The pose's label (see [`PoseReport::label`]).
            warning (None | str | Unset): E.g. "board-to-image angle under 20 degrees: focal length poorly conditioned".
     """

    pose_id: str
    rms_px: float
    board_angle_deg: float
    label: str | Unset = UNSET
    warning: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        pose_id = self.pose_id

        rms_px = self.rms_px

        board_angle_deg = self.board_angle_deg

        label = self.label

        warning: None | str | Unset
        if isinstance(self.warning, Unset):
            warning = UNSET
        else:
            warning = self.warning


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "pose_id": pose_id,
            "rms_px": rms_px,
            "board_angle_deg": board_angle_deg,
        })
        if label is not UNSET:
            field_dict["label"] = label
        if warning is not UNSET:
            field_dict["warning"] = warning

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        pose_id = d.pop("pose_id")

        rms_px = d.pop("rms_px")

        board_angle_deg = d.pop("board_angle_deg")

        label = d.pop("label", UNSET)

        def _parse_warning(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        warning = _parse_warning(d.pop("warning", UNSET))


        view_report = cls(
            pose_id=pose_id,
            rms_px=rms_px,
            board_angle_deg=board_angle_deg,
            label=label,
            warning=warning,
        )


        view_report.additional_properties = d
        return view_report

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
