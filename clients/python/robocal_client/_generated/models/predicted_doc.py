from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.existing_predicted_doc import ExistingPredictedDoc
  from ..models.predicted_doc_parameter_std_devs import PredictedDocParameterStdDevs





T = TypeVar("T", bound="PredictedDoc")



@_attrs_define
class PredictedDoc:
    """ What the plan predicts for the campaign.

        Attributes:
            validation_error_mean_mm (float): Mean 3-D camera position error (mm) the calibrated model will show
                at random validation poses in the same ranges.
            parameter_std_devs (PredictedDocParameterStdDevs): 1σ of every identified parameter: mm for lengths and
                translations,
                degrees for angles, pixels for `fx fy cx cy`, unitless for distortion.
            condition_number (float): `s_max / s_min` of the column-scaled image-level Jacobian.
            sigma_px (float): The dot noise the prediction assumed (px per image axis).
            sigma_px_source (None | str | Unset): Where `sigma_px` came from: `"request"` (the body's `sigma_px`), the
                parameter set `"{serial}/{version}"` whose job measured it (its
                report's reprojection RMS / sqrt 2, on images of the plan's size), or
                `"default"` (0.1 px). Absent only in plans stored before it existed.
            existing (ExistingPredictedDoc | None | Unset):
     """

    validation_error_mean_mm: float
    parameter_std_devs: PredictedDocParameterStdDevs
    condition_number: float
    sigma_px: float
    sigma_px_source: None | str | Unset = UNSET
    existing: ExistingPredictedDoc | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.existing_predicted_doc import ExistingPredictedDoc # noqa: PLC0415
        from ..models.predicted_doc_parameter_std_devs import PredictedDocParameterStdDevs # noqa: PLC0415
        validation_error_mean_mm = self.validation_error_mean_mm

        parameter_std_devs = self.parameter_std_devs.to_dict()

        condition_number = self.condition_number

        sigma_px = self.sigma_px

        sigma_px_source: None | str | Unset
        if isinstance(self.sigma_px_source, Unset):
            sigma_px_source = UNSET
        else:
            sigma_px_source = self.sigma_px_source

        existing: dict[str, Any] | None | Unset
        if isinstance(self.existing, Unset):
            existing = UNSET
        elif isinstance(self.existing, ExistingPredictedDoc):
            existing = self.existing.to_dict()
        else:
            existing = self.existing


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "validation_error_mean_mm": validation_error_mean_mm,
            "parameter_std_devs": parameter_std_devs,
            "condition_number": condition_number,
            "sigma_px": sigma_px,
        })
        if sigma_px_source is not UNSET:
            field_dict["sigma_px_source"] = sigma_px_source
        if existing is not UNSET:
            field_dict["existing"] = existing

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.existing_predicted_doc import ExistingPredictedDoc # noqa: PLC0415
        from ..models.predicted_doc_parameter_std_devs import PredictedDocParameterStdDevs # noqa: PLC0415
        d = dict(src_dict)
        validation_error_mean_mm = d.pop("validation_error_mean_mm")

        parameter_std_devs = PredictedDocParameterStdDevs.from_dict(d.pop("parameter_std_devs"))




        condition_number = d.pop("condition_number")

        sigma_px = d.pop("sigma_px")

        def _parse_sigma_px_source(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        sigma_px_source = _parse_sigma_px_source(d.pop("sigma_px_source", UNSET))


        def _parse_existing(data: object) -> ExistingPredictedDoc | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                existing_type_1 = ExistingPredictedDoc.from_dict(data)



                return existing_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ExistingPredictedDoc | None | Unset, data)

        existing = _parse_existing(d.pop("existing", UNSET))


        predicted_doc = cls(
            validation_error_mean_mm=validation_error_mean_mm,
            parameter_std_devs=parameter_std_devs,
            condition_number=condition_number,
            sigma_px=sigma_px,
            sigma_px_source=sigma_px_source,
            existing=existing,
        )


        predicted_doc.additional_properties = d
        return predicted_doc

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
