from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="ReportLink")



@_attrs_define
class ReportLink:
    """ 
        Attributes:
            url (str): The printable HTML report; opens without a header until `expires_at`.
            svg_url (str): The same report as one SVG sheet.
            json_url (str): The same report as JSON.
            expires_at (str): RFC 3339 UTC; the link answers 401 after it.
     """

    url: str
    svg_url: str
    json_url: str
    expires_at: str
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        url = self.url

        svg_url = self.svg_url

        json_url = self.json_url

        expires_at = self.expires_at


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "url": url,
            "svg_url": svg_url,
            "json_url": json_url,
            "expires_at": expires_at,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        url = d.pop("url")

        svg_url = d.pop("svg_url")

        json_url = d.pop("json_url")

        expires_at = d.pop("expires_at")

        report_link = cls(
            url=url,
            svg_url=svg_url,
            json_url=json_url,
            expires_at=expires_at,
        )


        report_link.additional_properties = d
        return report_link

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
