from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.pose_doc import PoseDoc





T = TypeVar("T", bound="ForwardRequest")



@_attrs_define
class ForwardRequest:
    """ 
        Attributes:
            joints_deg (list[list[float]]):
            tool (None | PoseDoc | Unset):
            session_id (None | str | Unset): A multi-session set: work in this session's board frame
                (its `target_to_base`); absent: the set's own `target_to_base`.
     """

    joints_deg: list[list[float]]
    tool: None | PoseDoc | Unset = UNSET
    session_id: None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        joints_deg = []
        for joints_deg_item_data in self.joints_deg:
            joints_deg_item = joints_deg_item_data


            joints_deg.append(joints_deg_item)



        tool: dict[str, Any] | None | Unset
        if isinstance(self.tool, Unset):
            tool = UNSET
        elif isinstance(self.tool, PoseDoc):
            tool = self.tool.to_dict()
        else:
            tool = self.tool

        session_id: None | str | Unset
        if isinstance(self.session_id, Unset):
            session_id = UNSET
        else:
            session_id = self.session_id


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "joints_deg": joints_deg,
        })
        if tool is not UNSET:
            field_dict["tool"] = tool
        if session_id is not UNSET:
            field_dict["session_id"] = session_id

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        d = dict(src_dict)
        joints_deg = []
        _joints_deg = d.pop("joints_deg")
        for joints_deg_item_data in (_joints_deg):
            joints_deg_item = cast(list[float], joints_deg_item_data)

            joints_deg.append(joints_deg_item)


        def _parse_tool(data: object) -> None | PoseDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                tool_type_1 = PoseDoc.from_dict(data)



                return tool_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PoseDoc | Unset, data)

        tool = _parse_tool(d.pop("tool", UNSET))


        def _parse_session_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        session_id = _parse_session_id(d.pop("session_id", UNSET))


        forward_request = cls(
            joints_deg=joints_deg,
            tool=tool,
            session_id=session_id,
        )

        return forward_request

