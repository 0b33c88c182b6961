from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="TermsCovarianceDoc")



@_attrs_define
class TermsCovarianceDoc:
    """ Covariances of the kept terms (camera sets: the terms were refined on
    the image points), in the units of the set's `parameters` rows (mm or
    deg) and each term's `unit`.

        Attributes:
            names (list[str]): Parameter names, as the set's `covariance.names`.
            with_parameters (list[list[float]]): One row per name, one column per term (`terms` order).
            among_terms (list[list[float]]): Term by term.
     """

    names: list[str]
    with_parameters: list[list[float]]
    among_terms: list[list[float]]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        names = self.names



        with_parameters = []
        for with_parameters_item_data in self.with_parameters:
            with_parameters_item = with_parameters_item_data


            with_parameters.append(with_parameters_item)



        among_terms = []
        for among_terms_item_data in self.among_terms:
            among_terms_item = among_terms_item_data


            among_terms.append(among_terms_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "names": names,
            "with_parameters": with_parameters,
            "among_terms": among_terms,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        names = cast(list[str], d.pop("names"))


        with_parameters = []
        _with_parameters = d.pop("with_parameters")
        for with_parameters_item_data in (_with_parameters):
            with_parameters_item = cast(list[float], with_parameters_item_data)

            with_parameters.append(with_parameters_item)


        among_terms = []
        _among_terms = d.pop("among_terms")
        for among_terms_item_data in (_among_terms):
            among_terms_item = cast(list[float], among_terms_item_data)

            among_terms.append(among_terms_item)


        terms_covariance_doc = cls(
            names=names,
            with_parameters=with_parameters,
            among_terms=among_terms,
        )


        terms_covariance_doc.additional_properties = d
        return terms_covariance_doc

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
