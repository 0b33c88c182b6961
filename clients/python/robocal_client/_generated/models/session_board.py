from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.covariance_doc import CovarianceDoc
  from ..models.frame_pose import FramePose





T = TypeVar("T", bound="SessionBoard")



@_attrs_define
class SessionBoard:
    """ One session's board placement in a multi-session set.

        Attributes:
            session_id (str):
            target_to_base (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
            covariance (CovarianceDoc | None | Unset):
     """

    session_id: str
    target_to_base: FramePose
    covariance: CovarianceDoc | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.covariance_doc import CovarianceDoc # noqa: PLC0415
        from ..models.frame_pose import FramePose # noqa: PLC0415
        session_id = self.session_id

        target_to_base = self.target_to_base.to_dict()

        covariance: dict[str, Any] | None | Unset
        if isinstance(self.covariance, Unset):
            covariance = UNSET
        elif isinstance(self.covariance, CovarianceDoc):
            covariance = self.covariance.to_dict()
        else:
            covariance = self.covariance


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "session_id": session_id,
            "target_to_base": target_to_base,
        })
        if covariance is not UNSET:
            field_dict["covariance"] = covariance

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.covariance_doc import CovarianceDoc # noqa: PLC0415
        from ..models.frame_pose import FramePose # noqa: PLC0415
        d = dict(src_dict)
        session_id = d.pop("session_id")

        target_to_base = FramePose.from_dict(d.pop("target_to_base"))




        def _parse_covariance(data: object) -> CovarianceDoc | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                covariance_type_1 = CovarianceDoc.from_dict(data)



                return covariance_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(CovarianceDoc | None | Unset, data)

        covariance = _parse_covariance(d.pop("covariance", UNSET))


        session_board = cls(
            session_id=session_id,
            target_to_base=target_to_base,
            covariance=covariance,
        )


        session_board.additional_properties = d
        return session_board

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
