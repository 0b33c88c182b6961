from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.kept_term import KeptTerm
  from ..models.term_joint_range import TermJointRange
  from ..models.terms_covariance_doc import TermsCovarianceDoc





T = TypeVar("T", bound="TermsDoc")



@_attrs_define
class TermsDoc:
    """ A set's kept terms.

        Attributes:
            payload_kg (float): The session's payload at the tool (kg; 0 when none was given).
            tool_point_mm (list[float]): The tool point the tool and payload torques act at, flange frame (mm).
            terms (list[KeptTerm]):
            covariance (None | TermsCovarianceDoc | Unset):
            joint_ranges_deg (list[TermJointRange] | Unset): The span of each joint with a kept periodic term over the
                calibration poses: outside it the term extrapolates, and `forward`
                says so in the pose's `warnings` (calib's `term_range`). Absent in
                sets stored before it was kept.
     """

    payload_kg: float
    tool_point_mm: list[float]
    terms: list[KeptTerm]
    covariance: None | TermsCovarianceDoc | Unset = UNSET
    joint_ranges_deg: list[TermJointRange] | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.kept_term import KeptTerm # noqa: PLC0415
        from ..models.term_joint_range import TermJointRange # noqa: PLC0415
        from ..models.terms_covariance_doc import TermsCovarianceDoc # noqa: PLC0415
        payload_kg = self.payload_kg

        tool_point_mm = self.tool_point_mm



        terms = []
        for terms_item_data in self.terms:
            terms_item = terms_item_data.to_dict()
            terms.append(terms_item)



        covariance: dict[str, Any] | None | Unset
        if isinstance(self.covariance, Unset):
            covariance = UNSET
        elif isinstance(self.covariance, TermsCovarianceDoc):
            covariance = self.covariance.to_dict()
        else:
            covariance = self.covariance

        joint_ranges_deg: list[dict[str, Any]] | Unset = UNSET
        if not isinstance(self.joint_ranges_deg, Unset):
            joint_ranges_deg = []
            for joint_ranges_deg_item_data in self.joint_ranges_deg:
                joint_ranges_deg_item = joint_ranges_deg_item_data.to_dict()
                joint_ranges_deg.append(joint_ranges_deg_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "payload_kg": payload_kg,
            "tool_point_mm": tool_point_mm,
            "terms": terms,
        })
        if covariance is not UNSET:
            field_dict["covariance"] = covariance
        if joint_ranges_deg is not UNSET:
            field_dict["joint_ranges_deg"] = joint_ranges_deg

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.kept_term import KeptTerm # noqa: PLC0415
        from ..models.term_joint_range import TermJointRange # noqa: PLC0415
        from ..models.terms_covariance_doc import TermsCovarianceDoc # noqa: PLC0415
        d = dict(src_dict)
        payload_kg = d.pop("payload_kg")

        tool_point_mm = cast(list[float], d.pop("tool_point_mm"))


        terms = []
        _terms = d.pop("terms")
        for terms_item_data in (_terms):
            terms_item = KeptTerm.from_dict(terms_item_data)



            terms.append(terms_item)


        def _parse_covariance(data: object) -> None | TermsCovarianceDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                covariance_type_1 = TermsCovarianceDoc.from_dict(data)



                return covariance_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | TermsCovarianceDoc | Unset, data)

        covariance = _parse_covariance(d.pop("covariance", UNSET))


        _joint_ranges_deg = d.pop("joint_ranges_deg", UNSET)
        joint_ranges_deg: list[TermJointRange] | Unset = UNSET
        if _joint_ranges_deg is not UNSET:
            joint_ranges_deg = []
            for joint_ranges_deg_item_data in _joint_ranges_deg:
                joint_ranges_deg_item = TermJointRange.from_dict(joint_ranges_deg_item_data)



                joint_ranges_deg.append(joint_ranges_deg_item)


        terms_doc = cls(
            payload_kg=payload_kg,
            tool_point_mm=tool_point_mm,
            terms=terms,
            covariance=covariance,
            joint_ranges_deg=joint_ranges_deg,
        )


        terms_doc.additional_properties = d
        return terms_doc

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
