from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ParameterChange")



@_attrs_define
class ParameterChange:
    """ One parameter's change between two sets.

        Attributes:
            name (str):
            unit (str):
            from_ (float):
            to (float):
            change (float): `to - from`.
            sigmas (float | None | Unset): The change over the combined standard deviation of both sets,
                `sqrt(σ_from² + σ_to²)`; `null` when neither states one.
     """

    name: str
    unit: str
    from_: float
    to: float
    change: float
    sigmas: float | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        unit = self.unit

        from_ = self.from_

        to = self.to

        change = self.change

        sigmas: float | None | Unset
        if isinstance(self.sigmas, Unset):
            sigmas = UNSET
        else:
            sigmas = self.sigmas


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "name": name,
            "unit": unit,
            "from": from_,
            "to": to,
            "change": change,
        })
        if sigmas is not UNSET:
            field_dict["sigmas"] = sigmas

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        unit = d.pop("unit")

        from_ = d.pop("from")

        to = d.pop("to")

        change = d.pop("change")

        def _parse_sigmas(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        sigmas = _parse_sigmas(d.pop("sigmas", UNSET))


        parameter_change = cls(
            name=name,
            unit=unit,
            from_=from_,
            to=to,
            change=change,
            sigmas=sigmas,
        )


        parameter_change.additional_properties = d
        return parameter_change

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
