from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.hand_eye_set_out import HandEyeSetOut
  from ..models.kinematic_set_out import KinematicSetOut
  from ..models.stage_camera_set_out import StageCameraSetOut





T = TypeVar("T", bound="ParameterSetList")



@_attrs_define
class ParameterSetList:
    """ 
        Attributes:
            items (list[HandEyeSetOut | KinematicSetOut | StageCameraSetOut]):
            next_cursor (None | str | Unset):
     """

    items: list[HandEyeSetOut | KinematicSetOut | StageCameraSetOut]
    next_cursor: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.hand_eye_set_out import HandEyeSetOut # noqa: PLC0415
        from ..models.kinematic_set_out import KinematicSetOut # noqa: PLC0415
        from ..models.stage_camera_set_out import StageCameraSetOut # noqa: PLC0415
        items = []
        for items_item_data in self.items:
            items_item: dict[str, Any]
            if isinstance(items_item_data, KinematicSetOut):
                items_item = items_item_data.to_dict()
            elif isinstance(items_item_data, HandEyeSetOut):
                items_item = items_item_data.to_dict()
            else:
                items_item = items_item_data.to_dict()

            items.append(items_item)



        next_cursor: None | str | Unset
        if isinstance(self.next_cursor, Unset):
            next_cursor = UNSET
        else:
            next_cursor = self.next_cursor


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "items": items,
        })
        if next_cursor is not UNSET:
            field_dict["next_cursor"] = next_cursor

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.hand_eye_set_out import HandEyeSetOut # noqa: PLC0415
        from ..models.kinematic_set_out import KinematicSetOut # noqa: PLC0415
        from ..models.stage_camera_set_out import StageCameraSetOut # noqa: PLC0415
        d = dict(src_dict)
        items = []
        _items = d.pop("items")
        for items_item_data in (_items):
            def _parse_items_item(data: object) -> HandEyeSetOut | KinematicSetOut | StageCameraSetOut:
                try:
                    if not isinstance(data, dict):
                        raise TypeError()
                    componentsschemas_parameter_set_out_type_0 = KinematicSetOut.from_dict(data)



                    return componentsschemas_parameter_set_out_type_0
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                try:
                    if not isinstance(data, dict):
                        raise TypeError()
                    componentsschemas_parameter_set_out_type_1 = HandEyeSetOut.from_dict(data)



                    return componentsschemas_parameter_set_out_type_1
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                if not isinstance(data, dict):
                    raise TypeError()
                componentsschemas_parameter_set_out_type_2 = StageCameraSetOut.from_dict(data)



                return componentsschemas_parameter_set_out_type_2

            items_item = _parse_items_item(items_item_data)

            items.append(items_item)


        def _parse_next_cursor(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        next_cursor = _parse_next_cursor(d.pop("next_cursor", UNSET))


        parameter_set_list = cls(
            items=items,
            next_cursor=next_cursor,
        )


        parameter_set_list.additional_properties = d
        return parameter_set_list

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
