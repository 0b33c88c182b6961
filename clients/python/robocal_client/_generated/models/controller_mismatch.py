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





T = TypeVar("T", bound="ControllerMismatch")



@_attrs_define
class ControllerMismatch:
    """ A call that expected one controller on a set (or robot) recorded on
    another: the 409's `controller` member.

        Attributes:
            expected (ControllerIdentity): Who the controller is. Every field is optional; an identity names at
                least one.
            recorded (ControllerIdentity | None | Unset):
     """

    expected: ControllerIdentity
    recorded: ControllerIdentity | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        expected = self.expected.to_dict()

        recorded: dict[str, Any] | None | Unset
        if isinstance(self.recorded, Unset):
            recorded = UNSET
        elif isinstance(self.recorded, ControllerIdentity):
            recorded = self.recorded.to_dict()
        else:
            recorded = self.recorded


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "expected": expected,
        })
        if recorded is not UNSET:
            field_dict["recorded"] = recorded

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        d = dict(src_dict)
        expected = ControllerIdentity.from_dict(d.pop("expected"))




        def _parse_recorded(data: object) -> ControllerIdentity | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                recorded_type_1 = ControllerIdentity.from_dict(data)



                return recorded_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ControllerIdentity | None | Unset, data)

        recorded = _parse_recorded(d.pop("recorded", UNSET))


        controller_mismatch = cls(
            expected=expected,
            recorded=recorded,
        )


        controller_mismatch.additional_properties = d
        return controller_mismatch

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
