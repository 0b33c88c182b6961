from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.box_doc import BoxDoc
  from ..models.pose_doc import PoseDoc





T = TypeVar("T", bound="UncertaintyMapRequest")



@_attrs_define
class UncertaintyMapRequest:
    """ Where to predict: either `joints_deg` (rows of joints) or `box` (flange
    positions in the base frame at one flange orientation, each solved by
    the calibrated model's inverse kinematics from the seed).

        Attributes:
            joints_deg (list[list[float]] | None | Unset):
            box (BoxDoc | None | Unset):
            rotation_deg (list[float] | None | Unset): The flange's fixed-axis X-Y-Z orientation in the base frame over
                the box (deg); `[0, 180, 0]` (flange pointing down) when absent.
            seed_joints_deg (list[float] | None | Unset): Joints (deg) whose branch the box's solutions keep; mid-range when
                absent.
            tool (None | PoseDoc | Unset):
            session_id (None | str | Unset): A multi-session set's session: the σ of the tool in that
                session's board frame, with that board's own covariance (as
                `forward`'s `session_id`).
     """

    joints_deg: list[list[float]] | None | Unset = UNSET
    box: BoxDoc | None | Unset = UNSET
    rotation_deg: list[float] | None | Unset = UNSET
    seed_joints_deg: list[float] | None | Unset = UNSET
    tool: None | PoseDoc | Unset = UNSET
    session_id: None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.box_doc import BoxDoc # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        joints_deg: list[list[float]] | None | Unset
        if isinstance(self.joints_deg, Unset):
            joints_deg = UNSET
        elif isinstance(self.joints_deg, list):
            joints_deg = []
            for joints_deg_type_0_item_data in self.joints_deg:
                joints_deg_type_0_item = joints_deg_type_0_item_data


                joints_deg.append(joints_deg_type_0_item)


        else:
            joints_deg = self.joints_deg

        box: dict[str, Any] | None | Unset
        if isinstance(self.box, Unset):
            box = UNSET
        elif isinstance(self.box, BoxDoc):
            box = self.box.to_dict()
        else:
            box = self.box

        rotation_deg: list[float] | None | Unset
        if isinstance(self.rotation_deg, Unset):
            rotation_deg = UNSET
        elif isinstance(self.rotation_deg, list):
            rotation_deg = self.rotation_deg


        else:
            rotation_deg = self.rotation_deg

        seed_joints_deg: list[float] | None | Unset
        if isinstance(self.seed_joints_deg, Unset):
            seed_joints_deg = UNSET
        elif isinstance(self.seed_joints_deg, list):
            seed_joints_deg = self.seed_joints_deg


        else:
            seed_joints_deg = self.seed_joints_deg

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
        })
        if joints_deg is not UNSET:
            field_dict["joints_deg"] = joints_deg
        if box is not UNSET:
            field_dict["box"] = box
        if rotation_deg is not UNSET:
            field_dict["rotation_deg"] = rotation_deg
        if seed_joints_deg is not UNSET:
            field_dict["seed_joints_deg"] = seed_joints_deg
        if tool is not UNSET:
            field_dict["tool"] = tool
        if session_id is not UNSET:
            field_dict["session_id"] = session_id

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.box_doc import BoxDoc # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        d = dict(src_dict)
        def _parse_joints_deg(data: object) -> list[list[float]] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                joints_deg_type_0 = []
                _joints_deg_type_0 = data
                for joints_deg_type_0_item_data in (_joints_deg_type_0):
                    joints_deg_type_0_item = cast(list[float], joints_deg_type_0_item_data)

                    joints_deg_type_0.append(joints_deg_type_0_item)

                return joints_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[list[float]] | None | Unset, data)

        joints_deg = _parse_joints_deg(d.pop("joints_deg", UNSET))


        def _parse_box(data: object) -> BoxDoc | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                box_type_1 = BoxDoc.from_dict(data)



                return box_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(BoxDoc | None | Unset, data)

        box = _parse_box(d.pop("box", UNSET))


        def _parse_rotation_deg(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                rotation_deg_type_0 = cast(list[float], data)

                return rotation_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        rotation_deg = _parse_rotation_deg(d.pop("rotation_deg", UNSET))


        def _parse_seed_joints_deg(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                seed_joints_deg_type_0 = cast(list[float], data)

                return seed_joints_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        seed_joints_deg = _parse_seed_joints_deg(d.pop("seed_joints_deg", UNSET))


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


        uncertainty_map_request = cls(
            joints_deg=joints_deg,
            box=box,
            rotation_deg=rotation_deg,
            seed_joints_deg=seed_joints_deg,
            tool=tool,
            session_id=session_id,
        )

        return uncertainty_map_request

