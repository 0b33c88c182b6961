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





T = TypeVar("T", bound="FilterRequest")



@_attrs_define
class FilterRequest:
    """ 
        Attributes:
            targets (list[PoseDoc]): Desired poses of the tool in the target frame (camera sessions) or
                the tracker frame.
            tool (PoseDoc): A pose in the contract form: translation in mm, fixed-axis X-Y-Z angles in
                degrees (`R = Rz(rz) Ry(ry) Rx(rx)`), optionally a 4x4 row-major matrix.
            seed_joints_deg (list[float] | None | Unset): Joints (deg) whose branch every solution keeps: the robot's usual
                configuration in the program. Mid-range joints when absent.
            session_id (None | str | Unset): A multi-session set: work in this session's board frame
                (its `target_to_base`); absent: the set's own `target_to_base`.
            expect_controller (ControllerIdentity | None | Unset):
     """

    targets: list[PoseDoc]
    tool: PoseDoc
    seed_joints_deg: list[float] | None | Unset = UNSET
    session_id: None | str | Unset = UNSET
    expect_controller: ControllerIdentity | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        targets = []
        for targets_item_data in self.targets:
            targets_item = targets_item_data.to_dict()
            targets.append(targets_item)



        tool = self.tool.to_dict()

        seed_joints_deg: list[float] | None | Unset
        if isinstance(self.seed_joints_deg, Unset):
            seed_joints_deg = UNSET
        elif isinstance(self.seed_joints_deg, list):
            seed_joints_deg = self.seed_joints_deg


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
            "tool": tool,
        })
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


        tool = PoseDoc.from_dict(d.pop("tool"))




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


        filter_request = cls(
            targets=targets,
            tool=tool,
            seed_joints_deg=seed_joints_deg,
            session_id=session_id,
            expect_controller=expect_controller,
        )

        return filter_request

