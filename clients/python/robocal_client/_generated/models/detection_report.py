from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.detection_failure import DetectionFailure





T = TypeVar("T", bound="DetectionReport")



@_attrs_define
class DetectionReport:
    """ 
        Attributes:
            images (int):
            images_detected (int):
            dots_per_image (int):
            failures (list[DetectionFailure]):
     """

    images: int
    images_detected: int
    dots_per_image: int
    failures: list[DetectionFailure]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.detection_failure import DetectionFailure # noqa: PLC0415
        images = self.images

        images_detected = self.images_detected

        dots_per_image = self.dots_per_image

        failures = []
        for failures_item_data in self.failures:
            failures_item = failures_item_data.to_dict()
            failures.append(failures_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "images": images,
            "images_detected": images_detected,
            "dots_per_image": dots_per_image,
            "failures": failures,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.detection_failure import DetectionFailure # noqa: PLC0415
        d = dict(src_dict)
        images = d.pop("images")

        images_detected = d.pop("images_detected")

        dots_per_image = d.pop("dots_per_image")

        failures = []
        _failures = d.pop("failures")
        for failures_item_data in (_failures):
            failures_item = DetectionFailure.from_dict(failures_item_data)



            failures.append(failures_item)


        detection_report = cls(
            images=images,
            images_detected=images_detected,
            dots_per_image=dots_per_image,
            failures=failures,
        )


        detection_report.additional_properties = d
        return detection_report

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
