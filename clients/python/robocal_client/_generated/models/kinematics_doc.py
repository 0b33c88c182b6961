from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.joint_doc import JointDoc





T = TypeVar("T", bound="KinematicsDoc")



@_attrs_define
class KinematicsDoc:
    """ 
        Attributes:
            joints (list[JointDoc]):
     """

    joints: list[JointDoc]





    def to_dict(self) -> dict[str, Any]:
        from ..models.joint_doc import JointDoc # noqa: PLC0415
        joints = []
        for joints_item_data in self.joints:
            joints_item = joints_item_data.to_dict()
            joints.append(joints_item)




        field_dict: dict[str, Any] = {}

        field_dict.update({
            "joints": joints,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.joint_doc import JointDoc # noqa: PLC0415
        d = dict(src_dict)
        joints = []
        _joints = d.pop("joints")
        for joints_item_data in (_joints):
            joints_item = JointDoc.from_dict(joints_item_data)



            joints.append(joints_item)


        kinematics_doc = cls(
            joints=joints,
        )

        return kinematics_doc

