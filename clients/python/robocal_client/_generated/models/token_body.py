from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="TokenBody")



@_attrs_define
class TokenBody:
    """ 
        Attributes:
            name (str): 1 to 100 characters: who or what uses the token.
            scope (str):  Example: read.
            expires_in_secs (int | None | Unset): Seconds until the token is refused (absent: never expires). Example:
                2592000.
     """

    name: str
    scope: str
    expires_in_secs: int | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        scope = self.scope

        expires_in_secs: int | None | Unset
        if isinstance(self.expires_in_secs, Unset):
            expires_in_secs = UNSET
        else:
            expires_in_secs = self.expires_in_secs


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "name": name,
            "scope": scope,
        })
        if expires_in_secs is not UNSET:
            field_dict["expires_in_secs"] = expires_in_secs

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        scope = d.pop("scope")

        def _parse_expires_in_secs(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        expires_in_secs = _parse_expires_in_secs(d.pop("expires_in_secs", UNSET))


        token_body = cls(
            name=name,
            scope=scope,
            expires_in_secs=expires_in_secs,
        )

        return token_body

