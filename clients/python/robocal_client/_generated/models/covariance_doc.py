from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="CovarianceDoc")



@_attrs_define
class CovarianceDoc:
    """ Covariance of the identified parameters (held ones have none and are
    left out).

        Attributes:
            names (list[str]): Parameter names (as in `parameters[].name`), the matrix's order.
            units (list[str]): Per name, `mm` or `deg`: entry `[i][j]` is in `units[i]·units[j]`.
            matrix (list[list[float]]): Symmetric, row-major, `names.len()` square.
     """

    names: list[str]
    units: list[str]
    matrix: list[list[float]]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        names = self.names



        units = self.units



        matrix = []
        for matrix_item_data in self.matrix:
            matrix_item = matrix_item_data


            matrix.append(matrix_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "names": names,
            "units": units,
            "matrix": matrix,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        names = cast(list[str], d.pop("names"))


        units = cast(list[str], d.pop("units"))


        matrix = []
        _matrix = d.pop("matrix")
        for matrix_item_data in (_matrix):
            matrix_item = cast(list[float], matrix_item_data)

            matrix.append(matrix_item)


        covariance_doc = cls(
            names=names,
            units=units,
            matrix=matrix,
        )


        covariance_doc.additional_properties = d
        return covariance_doc

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
