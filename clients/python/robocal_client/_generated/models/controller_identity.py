from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ControllerIdentity")



@_attrs_define
class ControllerIdentity:
    """ Who the controller is. Every field is optional; an identity names at
    least one.

        Attributes:
            vendor (None | str | Unset): The controller's maker (`Universal Robots`, `KUKA`, `ABB`).
            serial (None | str | Unset): The controller's (not the arm's) serial number.
            software (None | str | Unset): Its software (firmware, PolyScope, KSS, RobotWare) version.
            kinematics_hash (None | str | Unset): The kinematics hash the controller reports (a UR arm's `calib_…`),
                which changes when the arm is re-mastered or its calibration reloaded.
     """

    vendor: None | str | Unset = UNSET
    serial: None | str | Unset = UNSET
    software: None | str | Unset = UNSET
    kinematics_hash: None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        vendor: None | str | Unset
        if isinstance(self.vendor, Unset):
            vendor = UNSET
        else:
            vendor = self.vendor

        serial: None | str | Unset
        if isinstance(self.serial, Unset):
            serial = UNSET
        else:
            serial = self.serial

        software: None | str | Unset
        if isinstance(self.software, Unset):
            software = UNSET
        else:
            software = self.software

        kinematics_hash: None | str | Unset
        if isinstance(self.kinematics_hash, Unset):
            kinematics_hash = UNSET
        else:
            kinematics_hash = self.kinematics_hash


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if vendor is not UNSET:
            field_dict["vendor"] = vendor
        if serial is not UNSET:
            field_dict["serial"] = serial
        if software is not UNSET:
            field_dict["software"] = software
        if kinematics_hash is not UNSET:
            field_dict["kinematics_hash"] = kinematics_hash

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        def _parse_vendor(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        vendor = _parse_vendor(d.pop("vendor", UNSET))


        def _parse_serial(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        serial = _parse_serial(d.pop("serial", UNSET))


        def _parse_software(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        software = _parse_software(d.pop("software", UNSET))


        def _parse_kinematics_hash(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        kinematics_hash = _parse_kinematics_hash(d.pop("kinematics_hash", UNSET))


        controller_identity = cls(
            vendor=vendor,
            serial=serial,
            software=software,
            kinematics_hash=kinematics_hash,
        )

        return controller_identity

