from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="ImageMeta")



@_attrs_define
class ImageMeta:
    """ Metadata of a stored image; the bytes live in the content-addressed blob store.

        Attributes:
            sha256 (str):
            size_bytes (int):
            content_type (str):
            width (int):
            height (int):
     """

    sha256: str
    size_bytes: int
    content_type: str
    width: int
    height: int
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        sha256 = self.sha256

        size_bytes = self.size_bytes

        content_type = self.content_type

        width = self.width

        height = self.height


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "sha256": sha256,
            "size_bytes": size_bytes,
            "content_type": content_type,
            "width": width,
            "height": height,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        sha256 = d.pop("sha256")

        size_bytes = d.pop("size_bytes")

        content_type = d.pop("content_type")

        width = d.pop("width")

        height = d.pop("height")

        image_meta = cls(
            sha256=sha256,
            size_bytes=size_bytes,
            content_type=content_type,
            width=width,
            height=height,
        )


        image_meta.additional_properties = d
        return image_meta

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
