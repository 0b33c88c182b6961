from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.controller_change import ControllerChange
  from ..models.decision import Decision
  from ..models.history_check import HistoryCheck
  from ..models.history_version import HistoryVersion





T = TypeVar("T", bound="History")



@_attrs_define
class History:
    """ `GET /v1/robots/{serial}/history`.

        Attributes:
            serial (str):
            approved (list[HistoryVersion]): Approved versions, oldest first.
            decisions (list[Decision]): Every status decision on the robot's sets, oldest first.
            checks (list[HistoryCheck]): Re-checks, newest first (at most 100).
            controller_changes (list[ControllerChange]): Every change of the robot's controller identity, oldest
                first: from, to, when.
     """

    serial: str
    approved: list[HistoryVersion]
    decisions: list[Decision]
    checks: list[HistoryCheck]
    controller_changes: list[ControllerChange]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_change import ControllerChange # noqa: PLC0415
        from ..models.decision import Decision # noqa: PLC0415
        from ..models.history_check import HistoryCheck # noqa: PLC0415
        from ..models.history_version import HistoryVersion # noqa: PLC0415
        serial = self.serial

        approved = []
        for approved_item_data in self.approved:
            approved_item = approved_item_data.to_dict()
            approved.append(approved_item)



        decisions = []
        for decisions_item_data in self.decisions:
            decisions_item = decisions_item_data.to_dict()
            decisions.append(decisions_item)



        checks = []
        for checks_item_data in self.checks:
            checks_item = checks_item_data.to_dict()
            checks.append(checks_item)



        controller_changes = []
        for controller_changes_item_data in self.controller_changes:
            controller_changes_item = controller_changes_item_data.to_dict()
            controller_changes.append(controller_changes_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "serial": serial,
            "approved": approved,
            "decisions": decisions,
            "checks": checks,
            "controller_changes": controller_changes,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_change import ControllerChange # noqa: PLC0415
        from ..models.decision import Decision # noqa: PLC0415
        from ..models.history_check import HistoryCheck # noqa: PLC0415
        from ..models.history_version import HistoryVersion # noqa: PLC0415
        d = dict(src_dict)
        serial = d.pop("serial")

        approved = []
        _approved = d.pop("approved")
        for approved_item_data in (_approved):
            approved_item = HistoryVersion.from_dict(approved_item_data)



            approved.append(approved_item)


        decisions = []
        _decisions = d.pop("decisions")
        for decisions_item_data in (_decisions):
            decisions_item = Decision.from_dict(decisions_item_data)



            decisions.append(decisions_item)


        checks = []
        _checks = d.pop("checks")
        for checks_item_data in (_checks):
            checks_item = HistoryCheck.from_dict(checks_item_data)



            checks.append(checks_item)


        controller_changes = []
        _controller_changes = d.pop("controller_changes")
        for controller_changes_item_data in (_controller_changes):
            controller_changes_item = ControllerChange.from_dict(controller_changes_item_data)



            controller_changes.append(controller_changes_item)


        history = cls(
            serial=serial,
            approved=approved,
            decisions=decisions,
            checks=checks,
            controller_changes=controller_changes,
        )


        history.additional_properties = d
        return history

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
