from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="GateReport")



@_attrs_define
class GateReport:
    """ The release gate's comparison in a report: what the set was
    compared with on the same validation poses at the end of the job.

        Attributes:
            status (str): The status the gate gave: `approved` or `candidate`.
            reason (str): Why, in a sentence.
            compared_with (str): What it was compared with: `nominal`, or the approved set
                `"{serial}/{version}"` (its kinematics with the base and hand–eye
                frames re-fitted on this session's calibration poses, as the
                nominal "before" is).
            worse (bool): This set predicts the same validation poses worse than before.
            compared_mean_mm (float | None | Unset): Mean 3-D validation error of what it was compared with (mm); absent
                when there was nothing to compare with (a hand–eye calibration).
            mean_mm (float | None | Unset): Mean 3-D validation error of this set (mm); absent when not finite.
            basis (None | str | Unset): How `mean_mm` and `compared_mean_mm` were both figured, when an
                approved set was compared (one rule for the two sets).
            compared_own_mean_mm (float | None | Unset): The headline mean 3-D validation error the compared set's own
                report gives (mm), on its own session's poses and by its own
                headline rule: it differs from `compared_mean_mm` when the poses or
                the rule differ (`basis` says how the gate figured it).
            compared_own_session_id (None | str | Unset): The session the compared set's own report measured.
     """

    status: str
    reason: str
    compared_with: str
    worse: bool
    compared_mean_mm: float | None | Unset = UNSET
    mean_mm: float | None | Unset = UNSET
    basis: None | str | Unset = UNSET
    compared_own_mean_mm: float | None | Unset = UNSET
    compared_own_session_id: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        status = self.status

        reason = self.reason

        compared_with = self.compared_with

        worse = self.worse

        compared_mean_mm: float | None | Unset
        if isinstance(self.compared_mean_mm, Unset):
            compared_mean_mm = UNSET
        else:
            compared_mean_mm = self.compared_mean_mm

        mean_mm: float | None | Unset
        if isinstance(self.mean_mm, Unset):
            mean_mm = UNSET
        else:
            mean_mm = self.mean_mm

        basis: None | str | Unset
        if isinstance(self.basis, Unset):
            basis = UNSET
        else:
            basis = self.basis

        compared_own_mean_mm: float | None | Unset
        if isinstance(self.compared_own_mean_mm, Unset):
            compared_own_mean_mm = UNSET
        else:
            compared_own_mean_mm = self.compared_own_mean_mm

        compared_own_session_id: None | str | Unset
        if isinstance(self.compared_own_session_id, Unset):
            compared_own_session_id = UNSET
        else:
            compared_own_session_id = self.compared_own_session_id


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "status": status,
            "reason": reason,
            "compared_with": compared_with,
            "worse": worse,
        })
        if compared_mean_mm is not UNSET:
            field_dict["compared_mean_mm"] = compared_mean_mm
        if mean_mm is not UNSET:
            field_dict["mean_mm"] = mean_mm
        if basis is not UNSET:
            field_dict["basis"] = basis
        if compared_own_mean_mm is not UNSET:
            field_dict["compared_own_mean_mm"] = compared_own_mean_mm
        if compared_own_session_id is not UNSET:
            field_dict["compared_own_session_id"] = compared_own_session_id

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        status = d.pop("status")

        reason = d.pop("reason")

        compared_with = d.pop("compared_with")

        worse = d.pop("worse")

        def _parse_compared_mean_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        compared_mean_mm = _parse_compared_mean_mm(d.pop("compared_mean_mm", UNSET))


        def _parse_mean_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        mean_mm = _parse_mean_mm(d.pop("mean_mm", UNSET))


        def _parse_basis(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        basis = _parse_basis(d.pop("basis", UNSET))


        def _parse_compared_own_mean_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        compared_own_mean_mm = _parse_compared_own_mean_mm(d.pop("compared_own_mean_mm", UNSET))


        def _parse_compared_own_session_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        compared_own_session_id = _parse_compared_own_session_id(d.pop("compared_own_session_id", UNSET))


        gate_report = cls(
            status=status,
            reason=reason,
            compared_with=compared_with,
            worse=worse,
            compared_mean_mm=compared_mean_mm,
            mean_mm=mean_mm,
            basis=basis,
            compared_own_mean_mm=compared_own_mean_mm,
            compared_own_session_id=compared_own_session_id,
        )


        gate_report.additional_properties = d
        return gate_report

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
