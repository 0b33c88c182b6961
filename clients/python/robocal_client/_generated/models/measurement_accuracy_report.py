from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.sequence_accuracy_report import SequenceAccuracyReport





T = TypeVar("T", bound="MeasurementAccuracyReport")



@_attrs_define
class MeasurementAccuracyReport:
    """ 
        Attributes:
            sequences (list[SequenceAccuracyReport]): One row per sequence, ascending.
     """

    sequences: list[SequenceAccuracyReport]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.sequence_accuracy_report import SequenceAccuracyReport # noqa: PLC0415
        sequences = []
        for sequences_item_data in self.sequences:
            sequences_item = sequences_item_data.to_dict()
            sequences.append(sequences_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "sequences": sequences,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.sequence_accuracy_report import SequenceAccuracyReport # noqa: PLC0415
        d = dict(src_dict)
        sequences = []
        _sequences = d.pop("sequences")
        for sequences_item_data in (_sequences):
            sequences_item = SequenceAccuracyReport.from_dict(sequences_item_data)



            sequences.append(sequences_item)


        measurement_accuracy_report = cls(
            sequences=sequences,
        )


        measurement_accuracy_report.additional_properties = d
        return measurement_accuracy_report

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
