from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="BoardScaleReport")



@_attrs_define
class BoardScaleReport:
    """ What the data say of the board's size: the fitted scale on the
    configured one, and the feature spacing it implies.

        Attributes:
            scale (float): True board coordinates / configured ones.
            std (float):
            configured_pitch_mm (float): The spacing the session's target configures (dot pitch or square
                side), mm.
            pitch_mm (float): `scale * configured_pitch_mm`: the spacing as printed, mm.
            pitch_std_mm (float):
     """

    scale: float
    std: float
    configured_pitch_mm: float
    pitch_mm: float
    pitch_std_mm: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        scale = self.scale

        std = self.std

        configured_pitch_mm = self.configured_pitch_mm

        pitch_mm = self.pitch_mm

        pitch_std_mm = self.pitch_std_mm


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "scale": scale,
            "std": std,
            "configured_pitch_mm": configured_pitch_mm,
            "pitch_mm": pitch_mm,
            "pitch_std_mm": pitch_std_mm,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        scale = d.pop("scale")

        std = d.pop("std")

        configured_pitch_mm = d.pop("configured_pitch_mm")

        pitch_mm = d.pop("pitch_mm")

        pitch_std_mm = d.pop("pitch_std_mm")

        board_scale_report = cls(
            scale=scale,
            std=std,
            configured_pitch_mm=configured_pitch_mm,
            pitch_mm=pitch_mm,
            pitch_std_mm=pitch_std_mm,
        )


        board_scale_report.additional_properties = d
        return board_scale_report

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
