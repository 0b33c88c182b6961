from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.map_point import MapPoint
  from ..models.target_error import TargetError





T = TypeVar("T", bound="UncertaintyMapResponse")



@_attrs_define
class UncertaintyMapResponse:
    """ Per point (grid order: x fastest, then y, then z; or the rows given),
    `null` where `errors` names the index.

        Attributes:
            points (list[MapPoint | None]):
            errors (list[TargetError]):
     """

    points: list[MapPoint | None]
    errors: list[TargetError]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.map_point import MapPoint # noqa: PLC0415
        from ..models.target_error import TargetError # noqa: PLC0415
        points = []
        for points_item_data in self.points:
            points_item: dict[str, Any] | None
            if isinstance(points_item_data, MapPoint):
                points_item = points_item_data.to_dict()
            else:
                points_item = points_item_data
            points.append(points_item)



        errors = []
        for errors_item_data in self.errors:
            errors_item = errors_item_data.to_dict()
            errors.append(errors_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "points": points,
            "errors": errors,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.map_point import MapPoint # noqa: PLC0415
        from ..models.target_error import TargetError # noqa: PLC0415
        d = dict(src_dict)
        points = []
        _points = d.pop("points")
        for points_item_data in (_points):
            def _parse_points_item(data: object) -> MapPoint | None:
                if data is None:
                    return data
                try:
                    if not isinstance(data, dict):
                        raise TypeError()
                    points_item_type_1 = MapPoint.from_dict(data)



                    return points_item_type_1
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                return cast(MapPoint | None, data)

            points_item = _parse_points_item(points_item_data)

            points.append(points_item)


        errors = []
        _errors = d.pop("errors")
        for errors_item_data in (_errors):
            errors_item = TargetError.from_dict(errors_item_data)



            errors.append(errors_item)


        uncertainty_map_response = cls(
            points=points,
            errors=errors,
        )


        uncertainty_map_response.additional_properties = d
        return uncertainty_map_response

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
