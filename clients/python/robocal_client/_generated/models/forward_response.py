from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.forward_pose import ForwardPose





T = TypeVar("T", bound="ForwardResponse")



@_attrs_define
class ForwardResponse:
    """ 
        Attributes:
            poses (list[ForwardPose]):
     """

    poses: list[ForwardPose]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.forward_pose import ForwardPose # noqa: PLC0415
        poses = []
        for poses_item_data in self.poses:
            poses_item = poses_item_data.to_dict()
            poses.append(poses_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "poses": poses,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.forward_pose import ForwardPose # noqa: PLC0415
        d = dict(src_dict)
        poses = []
        _poses = d.pop("poses")
        for poses_item_data in (_poses):
            poses_item = ForwardPose.from_dict(poses_item_data)



            poses.append(poses_item)


        forward_response = cls(
            poses=poses,
        )


        forward_response.additional_properties = d
        return forward_response

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
