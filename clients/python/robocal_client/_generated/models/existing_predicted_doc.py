from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ExistingPredictedDoc")



@_attrs_define
class ExistingPredictedDoc:
    """ What the session a plan extends is predicted to achieve alone; the
    plan's `validation_error_mean_mm` is the campaign with the planned
    poses added.

        Attributes:
            poses (int): The session's `cal` poses with joints that seeded the plan.
            validation_error_mean_mm (float | None | Unset): Mean 3-D camera position error (mm) at the same validation
                poses;
                absent when the session's poses do not determine every parameter.
            gain_mm (float | None | Unset): The predicted gain of shooting the planned poses: this error minus
                the extended campaign's (mm); absent with the error.
            undetermined (list[str] | Unset): The least determined parameters when the session's poses leave
                some undetermined (the planned poses are chosen to determine them).
     """

    poses: int
    validation_error_mean_mm: float | None | Unset = UNSET
    gain_mm: float | None | Unset = UNSET
    undetermined: list[str] | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        poses = self.poses

        validation_error_mean_mm: float | None | Unset
        if isinstance(self.validation_error_mean_mm, Unset):
            validation_error_mean_mm = UNSET
        else:
            validation_error_mean_mm = self.validation_error_mean_mm

        gain_mm: float | None | Unset
        if isinstance(self.gain_mm, Unset):
            gain_mm = UNSET
        else:
            gain_mm = self.gain_mm

        undetermined: list[str] | Unset = UNSET
        if not isinstance(self.undetermined, Unset):
            undetermined = self.undetermined




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "poses": poses,
        })
        if validation_error_mean_mm is not UNSET:
            field_dict["validation_error_mean_mm"] = validation_error_mean_mm
        if gain_mm is not UNSET:
            field_dict["gain_mm"] = gain_mm
        if undetermined is not UNSET:
            field_dict["undetermined"] = undetermined

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        poses = d.pop("poses")

        def _parse_validation_error_mean_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        validation_error_mean_mm = _parse_validation_error_mean_mm(d.pop("validation_error_mean_mm", UNSET))


        def _parse_gain_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        gain_mm = _parse_gain_mm(d.pop("gain_mm", UNSET))


        undetermined = cast(list[str], d.pop("undetermined", UNSET))


        existing_predicted_doc = cls(
            poses=poses,
            validation_error_mean_mm=validation_error_mean_mm,
            gain_mm=gain_mm,
            undetermined=undetermined,
        )


        existing_predicted_doc.additional_properties = d
        return existing_predicted_doc

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
