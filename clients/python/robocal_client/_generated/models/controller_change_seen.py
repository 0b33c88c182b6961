from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.controller_identity import ControllerIdentity





T = TypeVar("T", bound="ControllerChangeSeen")



@_attrs_define
class ControllerChangeSeen:
    """ The two controller identities behind a `controller_changed` verdict.

        Attributes:
            set_ (ControllerIdentity): Who the controller is. Every field is optional; an identity names at
                least one.
            session (ControllerIdentity): Who the controller is. Every field is optional; an identity names at
                least one.
     """

    set_: ControllerIdentity
    session: ControllerIdentity
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        set_ = self.set_.to_dict()

        session = self.session.to_dict()


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "set": set_,
            "session": session,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        d = dict(src_dict)
        set_ = ControllerIdentity.from_dict(d.pop("set"))




        session = ControllerIdentity.from_dict(d.pop("session"))




        controller_change_seen = cls(
            set_=set_,
            session=session,
        )


        controller_change_seen.additional_properties = d
        return controller_change_seen

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
