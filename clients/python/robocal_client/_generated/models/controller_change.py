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





T = TypeVar("T", bound="ControllerChange")



@_attrs_define
class ControllerChange:
    """ One change of a robot's controller identity (its history).

        Attributes:
            changed_at (str):
            from_ (ControllerIdentity | None | Unset):
            to (ControllerIdentity | None | Unset):
     """

    changed_at: str
    from_: ControllerIdentity | None | Unset = UNSET
    to: ControllerIdentity | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        changed_at = self.changed_at

        from_: dict[str, Any] | None | Unset
        if isinstance(self.from_, Unset):
            from_ = UNSET
        elif isinstance(self.from_, ControllerIdentity):
            from_ = self.from_.to_dict()
        else:
            from_ = self.from_

        to: dict[str, Any] | None | Unset
        if isinstance(self.to, Unset):
            to = UNSET
        elif isinstance(self.to, ControllerIdentity):
            to = self.to.to_dict()
        else:
            to = self.to


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "changed_at": changed_at,
        })
        if from_ is not UNSET:
            field_dict["from"] = from_
        if to is not UNSET:
            field_dict["to"] = to

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        d = dict(src_dict)
        changed_at = d.pop("changed_at")

        def _parse_from_(data: object) -> ControllerIdentity | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                from_type_1 = ControllerIdentity.from_dict(data)



                return from_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ControllerIdentity | None | Unset, data)

        from_ = _parse_from_(d.pop("from", UNSET))


        def _parse_to(data: object) -> ControllerIdentity | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                to_type_1 = ControllerIdentity.from_dict(data)



                return to_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ControllerIdentity | None | Unset, data)

        to = _parse_to(d.pop("to", UNSET))


        controller_change = cls(
            changed_at=changed_at,
            from_=from_,
            to=to,
        )


        controller_change.additional_properties = d
        return controller_change

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
