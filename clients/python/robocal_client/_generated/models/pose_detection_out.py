from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="PoseDetectionOut")



@_attrs_define
class PoseDetectionOut:
    """ How a pose's points were measured by the last calibration job.

        Attributes:
            job_id (str):
            error (None | str | Unset): Why no dots were detected on this pose's image.
            residual_rms_px (float | None | Unset): RMS length of this pose's residuals (px), outliers excluded.
     """

    job_id: str
    error: None | str | Unset = UNSET
    residual_rms_px: float | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        job_id = self.job_id

        error: None | str | Unset
        if isinstance(self.error, Unset):
            error = UNSET
        else:
            error = self.error

        residual_rms_px: float | None | Unset
        if isinstance(self.residual_rms_px, Unset):
            residual_rms_px = UNSET
        else:
            residual_rms_px = self.residual_rms_px


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "job_id": job_id,
        })
        if error is not UNSET:
            field_dict["error"] = error
        if residual_rms_px is not UNSET:
            field_dict["residual_rms_px"] = residual_rms_px

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        job_id = d.pop("job_id")

        def _parse_error(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        error = _parse_error(d.pop("error", UNSET))


        def _parse_residual_rms_px(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        residual_rms_px = _parse_residual_rms_px(d.pop("residual_rms_px", UNSET))


        pose_detection_out = cls(
            job_id=job_id,
            error=error,
            residual_rms_px=residual_rms_px,
        )


        pose_detection_out.additional_properties = d
        return pose_detection_out

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
