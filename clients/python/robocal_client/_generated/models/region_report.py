from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.accuracy_summary import AccuracySummary
  from ..models.local_model import LocalModel





T = TypeVar("T", bound="RegionReport")



@_attrs_define
class RegionReport:
    """ One session's (region's) accuracy on its own validation poses.

        Attributes:
            session_id (str):
            before (AccuracySummary): 3-D position-error statistics (the `ErrorStats` fields of the error
                norm) plus the same per axis (`|e_x|`, `|e_y|`, `|e_z|`), world frame.
            after (AccuracySummary): 3-D position-error statistics (the `ErrorStats` fields of the error
                norm) plus the same per axis (`|e_x|`, `|e_y|`, `|e_z|`), world frame.
            region (None | str | Unset): The session's `region` (free text), when it named one.
            volume (None | str | Unset): The session's `volume` (free text), when it named one.
            local (LocalModel | None | Unset):
     """

    session_id: str
    before: AccuracySummary
    after: AccuracySummary
    region: None | str | Unset = UNSET
    volume: None | str | Unset = UNSET
    local: LocalModel | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.accuracy_summary import AccuracySummary # noqa: PLC0415
        from ..models.local_model import LocalModel # noqa: PLC0415
        session_id = self.session_id

        before = self.before.to_dict()

        after = self.after.to_dict()

        region: None | str | Unset
        if isinstance(self.region, Unset):
            region = UNSET
        else:
            region = self.region

        volume: None | str | Unset
        if isinstance(self.volume, Unset):
            volume = UNSET
        else:
            volume = self.volume

        local: dict[str, Any] | None | Unset
        if isinstance(self.local, Unset):
            local = UNSET
        elif isinstance(self.local, LocalModel):
            local = self.local.to_dict()
        else:
            local = self.local


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "session_id": session_id,
            "before": before,
            "after": after,
        })
        if region is not UNSET:
            field_dict["region"] = region
        if volume is not UNSET:
            field_dict["volume"] = volume
        if local is not UNSET:
            field_dict["local"] = local

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.accuracy_summary import AccuracySummary # noqa: PLC0415
        from ..models.local_model import LocalModel # noqa: PLC0415
        d = dict(src_dict)
        session_id = d.pop("session_id")

        before = AccuracySummary.from_dict(d.pop("before"))




        after = AccuracySummary.from_dict(d.pop("after"))




        def _parse_region(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        region = _parse_region(d.pop("region", UNSET))


        def _parse_volume(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        volume = _parse_volume(d.pop("volume", UNSET))


        def _parse_local(data: object) -> LocalModel | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                local_type_1 = LocalModel.from_dict(data)



                return local_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(LocalModel | None | Unset, data)

        local = _parse_local(d.pop("local", UNSET))


        region_report = cls(
            session_id=session_id,
            before=before,
            after=after,
            region=region,
            volume=volume,
            local=local,
        )


        region_report.additional_properties = d
        return region_report

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
