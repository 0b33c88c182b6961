from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="ReportLinkBody")



@_attrs_define
class ReportLinkBody:
    """ 
        Attributes:
            expires_in_minutes (int): Minutes the link works, 1 to 10080 (a week). Example: 60.
     """

    expires_in_minutes: int





    def to_dict(self) -> dict[str, Any]:
        expires_in_minutes = self.expires_in_minutes


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "expires_in_minutes": expires_in_minutes,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        expires_in_minutes = d.pop("expires_in_minutes")

        report_link_body = cls(
            expires_in_minutes=expires_in_minutes,
        )

        return report_link_body

