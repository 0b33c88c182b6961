from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="DatasetOut")



@_attrs_define
class DatasetOut:
    """ 
        Attributes:
            session_id (str):
            poses_created (int):
            pose_ids (list[str]):
            detected_points (list[int]): Dots the detector found on each image at upload, in `pose_ids` order
                (0 where the board was not found; the pose's `detection_error` says why).
            warnings (list[str]): What the upload warns of although it stored every pose, e.g. "0 of
                32 images show the session's target; 32 say: …" (the job would fail).
     """

    session_id: str
    poses_created: int
    pose_ids: list[str]
    detected_points: list[int]
    warnings: list[str]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        session_id = self.session_id

        poses_created = self.poses_created

        pose_ids = self.pose_ids



        detected_points = self.detected_points



        warnings = self.warnings




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "session_id": session_id,
            "poses_created": poses_created,
            "pose_ids": pose_ids,
            "detected_points": detected_points,
            "warnings": warnings,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        session_id = d.pop("session_id")

        poses_created = d.pop("poses_created")

        pose_ids = cast(list[str], d.pop("pose_ids"))


        detected_points = cast(list[int], d.pop("detected_points"))


        warnings = cast(list[str], d.pop("warnings"))


        dataset_out = cls(
            session_id=session_id,
            poses_created=poses_created,
            pose_ids=pose_ids,
            detected_points=detected_points,
            warnings=warnings,
        )


        dataset_out.additional_properties = d
        return dataset_out

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
