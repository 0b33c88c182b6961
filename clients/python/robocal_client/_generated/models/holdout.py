from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="Holdout")



@_attrs_define
class Holdout:
    """ 
        Attributes:
            holdout_fraction (float): The share of poses held out for validation, strictly between 0 and 1.
     """

    holdout_fraction: float





    def to_dict(self) -> dict[str, Any]:
        holdout_fraction = self.holdout_fraction


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "holdout_fraction": holdout_fraction,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        holdout_fraction = d.pop("holdout_fraction")

        holdout = cls(
            holdout_fraction=holdout_fraction,
        )

        return holdout

