from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.accuracy_summary import AccuracySummary





T = TypeVar("T", bound="LocalModel")



@_attrs_define
class LocalModel:
    """ A local (one-session) set's figures in its region.

        Attributes:
            version (int): The local set's version.
            after (AccuracySummary): 3-D position-error statistics (the `ErrorStats` fields of the error
                norm) plus the same per axis (`|e_x|`, `|e_y|`, `|e_z|`), world frame.
     """

    version: int
    after: AccuracySummary
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.accuracy_summary import AccuracySummary # noqa: PLC0415
        version = self.version

        after = self.after.to_dict()


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "version": version,
            "after": after,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.accuracy_summary import AccuracySummary # noqa: PLC0415
        d = dict(src_dict)
        version = d.pop("version")

        after = AccuracySummary.from_dict(d.pop("after"))




        local_model = cls(
            version=version,
            after=after,
        )


        local_model.additional_properties = d
        return local_model

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
