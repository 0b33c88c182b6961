from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.term_line import TermLine





T = TypeVar("T", bound="TermsReport")



@_attrs_define
class TermsReport:
    """ The selection of non-geometric terms.

        Attributes:
            criterion (str): How the selection decides.
            payload_kg (float): The session's payload at the tool (kg).
            z_threshold (float): The Wald threshold `|value|/σ` a term had to pass.
            bic_geometric (float):
            bic_with_terms (float):
            kept (int):
            lines (list[TermLine]):
     """

    criterion: str
    payload_kg: float
    z_threshold: float
    bic_geometric: float
    bic_with_terms: float
    kept: int
    lines: list[TermLine]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.term_line import TermLine # noqa: PLC0415
        criterion = self.criterion

        payload_kg = self.payload_kg

        z_threshold = self.z_threshold

        bic_geometric = self.bic_geometric

        bic_with_terms = self.bic_with_terms

        kept = self.kept

        lines = []
        for lines_item_data in self.lines:
            lines_item = lines_item_data.to_dict()
            lines.append(lines_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "criterion": criterion,
            "payload_kg": payload_kg,
            "z_threshold": z_threshold,
            "bic_geometric": bic_geometric,
            "bic_with_terms": bic_with_terms,
            "kept": kept,
            "lines": lines,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.term_line import TermLine # noqa: PLC0415
        d = dict(src_dict)
        criterion = d.pop("criterion")

        payload_kg = d.pop("payload_kg")

        z_threshold = d.pop("z_threshold")

        bic_geometric = d.pop("bic_geometric")

        bic_with_terms = d.pop("bic_with_terms")

        kept = d.pop("kept")

        lines = []
        _lines = d.pop("lines")
        for lines_item_data in (_lines):
            lines_item = TermLine.from_dict(lines_item_data)



            lines.append(lines_item)


        terms_report = cls(
            criterion=criterion,
            payload_kg=payload_kg,
            z_threshold=z_threshold,
            bic_geometric=bic_geometric,
            bic_with_terms=bic_with_terms,
            kept=kept,
            lines=lines,
        )


        terms_report.additional_properties = d
        return terms_report

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
