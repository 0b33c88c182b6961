from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.convention import Convention
from ..models.joint_type import JointType
from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="JointDoc")



@_attrs_define
class JointDoc:
    """ One joint and the link after it.

        Attributes:
            a_mm (float):
            alpha_deg (float):
            type_ (JointType | Unset):
            convention (Convention | None | Unset):
            d_mm (float | Unset):
            theta_offset_deg (float | Unset):
            beta_deg (float | Unset):
            min_deg (float | Unset):
            max_deg (float | Unset):
     """

    a_mm: float
    alpha_deg: float
    type_: JointType | Unset = UNSET
    convention: Convention | None | Unset = UNSET
    d_mm: float | Unset = UNSET
    theta_offset_deg: float | Unset = UNSET
    beta_deg: float | Unset = UNSET
    min_deg: float | Unset = UNSET
    max_deg: float | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        a_mm = self.a_mm

        alpha_deg = self.alpha_deg

        type_: str | Unset = UNSET
        if not isinstance(self.type_, Unset):
            type_ = self.type_.value


        convention: None | str | Unset
        if isinstance(self.convention, Unset):
            convention = UNSET
        elif isinstance(self.convention, Convention):
            convention = self.convention.value
        else:
            convention = self.convention

        d_mm = self.d_mm

        theta_offset_deg = self.theta_offset_deg

        beta_deg = self.beta_deg

        min_deg = self.min_deg

        max_deg = self.max_deg


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "a_mm": a_mm,
            "alpha_deg": alpha_deg,
        })
        if type_ is not UNSET:
            field_dict["type"] = type_
        if convention is not UNSET:
            field_dict["convention"] = convention
        if d_mm is not UNSET:
            field_dict["d_mm"] = d_mm
        if theta_offset_deg is not UNSET:
            field_dict["theta_offset_deg"] = theta_offset_deg
        if beta_deg is not UNSET:
            field_dict["beta_deg"] = beta_deg
        if min_deg is not UNSET:
            field_dict["min_deg"] = min_deg
        if max_deg is not UNSET:
            field_dict["max_deg"] = max_deg

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        a_mm = d.pop("a_mm")

        alpha_deg = d.pop("alpha_deg")

        _type_ = d.pop("type", UNSET)
        type_: JointType | Unset
        if isinstance(_type_,  Unset):
            type_ = UNSET
        else:
            type_ = JointType(_type_)




        def _parse_convention(data: object) -> Convention | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                convention_type_1 = Convention(data)



                return convention_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(Convention | None | Unset, data)

        convention = _parse_convention(d.pop("convention", UNSET))


        d_mm = d.pop("d_mm", UNSET)

        theta_offset_deg = d.pop("theta_offset_deg", UNSET)

        beta_deg = d.pop("beta_deg", UNSET)

        min_deg = d.pop("min_deg", UNSET)

        max_deg = d.pop("max_deg", UNSET)

        joint_doc = cls(
            a_mm=a_mm,
            alpha_deg=alpha_deg,
            type_=type_,
            convention=convention,
            d_mm=d_mm,
            theta_offset_deg=theta_offset_deg,
            beta_deg=beta_deg,
            min_deg=min_deg,
            max_deg=max_deg,
        )

        return joint_doc

