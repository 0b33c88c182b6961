from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.frame_pose import FramePose





T = TypeVar("T", bound="StageSequence")



@_attrs_define
class StageSequence:
    """ One fitted sequence of a stage camera set.

        Attributes:
            sequence (int):
            target_to_camera (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
            target_to_stage (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
     """

    sequence: int
    target_to_camera: FramePose
    target_to_stage: FramePose
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        sequence = self.sequence

        target_to_camera = self.target_to_camera.to_dict()

        target_to_stage = self.target_to_stage.to_dict()


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "sequence": sequence,
            "target_to_camera": target_to_camera,
            "target_to_stage": target_to_stage,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        d = dict(src_dict)
        sequence = d.pop("sequence")

        target_to_camera = FramePose.from_dict(d.pop("target_to_camera"))




        target_to_stage = FramePose.from_dict(d.pop("target_to_stage"))




        stage_sequence = cls(
            sequence=sequence,
            target_to_camera=target_to_camera,
            target_to_stage=target_to_stage,
        )


        stage_sequence.additional_properties = d
        return stage_sequence

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
