from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.configuration_elbow import ConfigurationElbow
from ..models.configuration_shoulder import ConfigurationShoulder
from ..models.configuration_wrist import ConfigurationWrist






T = TypeVar("T", bound="Configuration")



@_attrs_define
class Configuration:
    """ The arm configuration of a solution (spherical-wrist arms).

        Attributes:
            shoulder (ConfigurationShoulder): The wrist centre's side of joint 1, along the arm.
            elbow (ConfigurationElbow): The elbow above or below the shoulder–wrist line (in the arm's plane).
            wrist (ConfigurationWrist): The sign of joint 5 (with its offset).
     """

    shoulder: ConfigurationShoulder
    elbow: ConfigurationElbow
    wrist: ConfigurationWrist
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        shoulder = self.shoulder.value

        elbow = self.elbow.value

        wrist = self.wrist.value


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "shoulder": shoulder,
            "elbow": elbow,
            "wrist": wrist,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        shoulder = ConfigurationShoulder(d.pop("shoulder"))




        elbow = ConfigurationElbow(d.pop("elbow"))




        wrist = ConfigurationWrist(d.pop("wrist"))




        configuration = cls(
            shoulder=shoulder,
            elbow=elbow,
            wrist=wrist,
        )


        configuration.additional_properties = d
        return configuration

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
