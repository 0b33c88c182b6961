from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="CheckSuspect")



@_attrs_define
class CheckSuspect:
    """ A parameter that may have changed, most likely first.

        Attributes:
            name (str): Its name in the parameter set (`dtheta_2`, `a_3`, ...), or a kept
                non-geometric term's (`periodic_4.cos2`, ...).
            unit (str): `deg` or `mm`; a term's own unit (`rad`, `rad*kg/(N*m)`, ...).
            change (float): The change that best explains the residuals beyond the base.
            change_sigmas (float): `change` in units of the set's standard deviation of the parameter.
            chi2_drop (float): The part of the chi-square statistic it explains.
     """

    name: str
    unit: str
    change: float
    change_sigmas: float
    chi2_drop: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        unit = self.unit

        change = self.change

        change_sigmas = self.change_sigmas

        chi2_drop = self.chi2_drop


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "name": name,
            "unit": unit,
            "change": change,
            "change_sigmas": change_sigmas,
            "chi2_drop": chi2_drop,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        unit = d.pop("unit")

        change = d.pop("change")

        change_sigmas = d.pop("change_sigmas")

        chi2_drop = d.pop("chi2_drop")

        check_suspect = cls(
            name=name,
            unit=unit,
            change=change,
            change_sigmas=change_sigmas,
            chi2_drop=chi2_drop,
        )


        check_suspect.additional_properties = d
        return check_suspect

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
