from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="PredictedStd")



@_attrs_define
class PredictedStd:
    """ The predicted 1σ of one row (see [`PredictedStd`]'s fields).

        Attributes:
            position_std_mm (float): 1σ of the tool's (the request's tool, else the camera's) 3-D position
                error in the target frame, board transform included: the square root
                of the trace of its 3x3 covariance, i.e. the RMS length of the error
                vector (a per-axis σ is about this over √3). mm.
            rotation_std_deg (float): The same for its orientation: square root of the trace of the 3x3
                covariance of the small-angle rotation error. deg.
            flange_position_std_mm (float): 1σ of the flange's 3-D position in the robot base frame (link
                parameters only), as `position_std_mm`. mm.
            flange_rotation_std_deg (float): 1σ of the flange's orientation in the base frame. deg.
     """

    position_std_mm: float
    rotation_std_deg: float
    flange_position_std_mm: float
    flange_rotation_std_deg: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        position_std_mm = self.position_std_mm

        rotation_std_deg = self.rotation_std_deg

        flange_position_std_mm = self.flange_position_std_mm

        flange_rotation_std_deg = self.flange_rotation_std_deg


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "position_std_mm": position_std_mm,
            "rotation_std_deg": rotation_std_deg,
            "flange_position_std_mm": flange_position_std_mm,
            "flange_rotation_std_deg": flange_rotation_std_deg,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        position_std_mm = d.pop("position_std_mm")

        rotation_std_deg = d.pop("rotation_std_deg")

        flange_position_std_mm = d.pop("flange_position_std_mm")

        flange_rotation_std_deg = d.pop("flange_rotation_std_deg")

        predicted_std = cls(
            position_std_mm=position_std_mm,
            rotation_std_deg=rotation_std_deg,
            flange_position_std_mm=flange_position_std_mm,
            flange_rotation_std_deg=flange_rotation_std_deg,
        )


        predicted_std.additional_properties = d
        return predicted_std

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
