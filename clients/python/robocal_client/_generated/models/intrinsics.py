from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="Intrinsics")



@_attrs_define
class Intrinsics:
    """ Pinhole intrinsics (px) and Brown–Conrady distortion.

        Attributes:
            fx (float):
            fy (float):
            cx (float):
            cy (float):
            k1 (float):
            k2 (float):
            p1 (float):
            p2 (float):
            k3 (float):
     """

    fx: float
    fy: float
    cx: float
    cy: float
    k1: float
    k2: float
    p1: float
    p2: float
    k3: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        fx = self.fx

        fy = self.fy

        cx = self.cx

        cy = self.cy

        k1 = self.k1

        k2 = self.k2

        p1 = self.p1

        p2 = self.p2

        k3 = self.k3


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "fx": fx,
            "fy": fy,
            "cx": cx,
            "cy": cy,
            "k1": k1,
            "k2": k2,
            "p1": p1,
            "p2": p2,
            "k3": k3,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        fx = d.pop("fx")

        fy = d.pop("fy")

        cx = d.pop("cx")

        cy = d.pop("cy")

        k1 = d.pop("k1")

        k2 = d.pop("k2")

        p1 = d.pop("p1")

        p2 = d.pop("p2")

        k3 = d.pop("k3")

        intrinsics = cls(
            fx=fx,
            fy=fy,
            cx=cx,
            cy=cy,
            k1=k1,
            k2=k2,
            p1=p1,
            p2=p2,
            k3=k3,
        )


        intrinsics.additional_properties = d
        return intrinsics

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
