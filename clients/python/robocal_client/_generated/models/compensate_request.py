from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.controller_identity import ControllerIdentity
  from ..models.pose_doc import PoseDoc





T = TypeVar("T", bound="CompensateRequest")



@_attrs_define
class CompensateRequest:
    """ 
        Attributes:
            targets (list[PoseDoc]):
            tool (None | PoseDoc | Unset):
            seed_joints_deg (list[float] | list[list[float]] | None | Unset):
            session_id (None | str | Unset): A multi-session set: work in this session's board frame
                (its `target_to_base`); absent: the set's own `target_to_base`.
            expect_controller (ControllerIdentity | None | Unset):
     """

    targets: list[PoseDoc]
    tool: None | PoseDoc | Unset = UNSET
    seed_joints_deg: list[float] | list[list[float]] | None | Unset = UNSET
    session_id: None | str | Unset = UNSET
    expect_controller: ControllerIdentity | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        targets = []
        for targets_item_data in self.targets:
            targets_item = targets_item_data.to_dict()
            targets.append(targets_item)



        tool: dict[str, Any] | None | Unset
        if isinstance(self.tool, Unset):
            tool = UNSET
        elif isinstance(self.tool, PoseDoc):
            tool = self.tool.to_dict()
        else:
            tool = self.tool

        seed_joints_deg: list[float] | list[list[float]] | None | Unset
        if isinstance(self.seed_joints_deg, Unset):
            seed_joints_deg = UNSET
        elif isinstance(self.seed_joints_deg, list):
            seed_joints_deg = self.seed_joints_deg


        elif isinstance(self.seed_joints_deg, list):
            seed_joints_deg = []
            for componentsschemas_seeds_type_1_item_data in self.seed_joints_deg:
                componentsschemas_seeds_type_1_item = componentsschemas_seeds_type_1_item_data


                seed_joints_deg.append(componentsschemas_seeds_type_1_item)


        else:
            seed_joints_deg = self.seed_joints_deg

        session_id: None | str | Unset
        if isinstance(self.session_id, Unset):
            session_id = UNSET
        else:
            session_id = self.session_id

        expect_controller: dict[str, Any] | None | Unset
        if isinstance(self.expect_controller, Unset):
            expect_controller = UNSET
        elif isinstance(self.expect_controller, ControllerIdentity):
            expect_controller = self.expect_controller.to_dict()
        else:
            expect_controller = self.expect_controller


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "targets": targets,
        })
        if tool is not UNSET:
            field_dict["tool"] = tool
        if seed_joints_deg is not UNSET:
            field_dict["seed_joints_deg"] = seed_joints_deg
        if session_id is not UNSET:
            field_dict["session_id"] = session_id
        if expect_controller is not UNSET:
            field_dict["expect_controller"] = expect_controller

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        d = dict(src_dict)
        targets = []
        _targets = d.pop("targets")
        for targets_item_data in (_targets):
            targets_item = PoseDoc.from_dict(targets_item_data)



            targets.append(targets_item)


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


        def _parse_seed_joints_deg(data: object) -> list[float] | list[list[float]] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                componentsschemas_seeds_type_0 = cast(list[float], data)

                return componentsschemas_seeds_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            try:
                if not isinstance(data, list):
                    raise TypeError()
                componentsschemas_seeds_type_1 = []
                _componentsschemas_seeds_type_1 = data
                for componentsschemas_seeds_type_1_item_data in (_componentsschemas_seeds_type_1):
                    componentsschemas_seeds_type_1_item = cast(list[float], componentsschemas_seeds_type_1_item_data)

                    componentsschemas_seeds_type_1.append(componentsschemas_seeds_type_1_item)

                return componentsschemas_seeds_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | list[list[float]] | None | Unset, data)

        seed_joints_deg = _parse_seed_joints_deg(d.pop("seed_joints_deg", UNSET))


        def _parse_session_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        session_id = _parse_session_id(d.pop("session_id", UNSET))


        def _parse_expect_controller(data: object) -> ControllerIdentity | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                expect_controller_type_1 = ControllerIdentity.from_dict(data)



                return expect_controller_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ControllerIdentity | None | Unset, data)

        expect_controller = _parse_expect_controller(d.pop("expect_controller", UNSET))


        compensate_request = cls(
            targets=targets,
            tool=tool,
            seed_joints_deg=seed_joints_deg,
            session_id=session_id,
            expect_controller=expect_controller,
        )

        return compensate_request

