from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="RungReport")



@_attrs_define
class RungReport:
    """ One rung of the ladder.

        Attributes:
            rung (str): `hand_eye`, `joint_offsets`, `joint_offsets_prior`, `full`,
                `full_prior` or `full_terms` (full geometry with the non-geometric
                terms the selection keeps).
            description (str):
            parameters (int): Free parameters (kinematics, board and hand–eye).
            heldout_rms_px (float | None | Unset): RMS reprojection error of the held-out configurations' image points
                (px; camera jobs).
            heldout_rms_mm (float | None | Unset): RMS length of the held-out configurations' tool position errors
                (mm; tracker jobs, where the rungs are judged on it).
            heldout_mean_mm (float | None | Unset): Mean 3-D camera position error at the held-out poses (mm).
            failed (None | str | Unset): Why the rung could not be scored, if it could not.
     """

    rung: str
    description: str
    parameters: int
    heldout_rms_px: float | None | Unset = UNSET
    heldout_rms_mm: float | None | Unset = UNSET
    heldout_mean_mm: float | None | Unset = UNSET
    failed: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        rung = self.rung

        description = self.description

        parameters = self.parameters

        heldout_rms_px: float | None | Unset
        if isinstance(self.heldout_rms_px, Unset):
            heldout_rms_px = UNSET
        else:
            heldout_rms_px = self.heldout_rms_px

        heldout_rms_mm: float | None | Unset
        if isinstance(self.heldout_rms_mm, Unset):
            heldout_rms_mm = UNSET
        else:
            heldout_rms_mm = self.heldout_rms_mm

        heldout_mean_mm: float | None | Unset
        if isinstance(self.heldout_mean_mm, Unset):
            heldout_mean_mm = UNSET
        else:
            heldout_mean_mm = self.heldout_mean_mm

        failed: None | str | Unset
        if isinstance(self.failed, Unset):
            failed = UNSET
        else:
            failed = self.failed


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "rung": rung,
            "description": description,
            "parameters": parameters,
        })
        if heldout_rms_px is not UNSET:
            field_dict["heldout_rms_px"] = heldout_rms_px
        if heldout_rms_mm is not UNSET:
            field_dict["heldout_rms_mm"] = heldout_rms_mm
        if heldout_mean_mm is not UNSET:
            field_dict["heldout_mean_mm"] = heldout_mean_mm
        if failed is not UNSET:
            field_dict["failed"] = failed

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        rung = d.pop("rung")

        description = d.pop("description")

        parameters = d.pop("parameters")

        def _parse_heldout_rms_px(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        heldout_rms_px = _parse_heldout_rms_px(d.pop("heldout_rms_px", UNSET))


        def _parse_heldout_rms_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        heldout_rms_mm = _parse_heldout_rms_mm(d.pop("heldout_rms_mm", UNSET))


        def _parse_heldout_mean_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        heldout_mean_mm = _parse_heldout_mean_mm(d.pop("heldout_mean_mm", UNSET))


        def _parse_failed(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        failed = _parse_failed(d.pop("failed", UNSET))


        rung_report = cls(
            rung=rung,
            description=description,
            parameters=parameters,
            heldout_rms_px=heldout_rms_px,
            heldout_rms_mm=heldout_rms_mm,
            heldout_mean_mm=heldout_mean_mm,
            failed=failed,
        )


        rung_report.additional_properties = d
        return rung_report

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
