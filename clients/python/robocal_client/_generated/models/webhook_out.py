from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.delivery_counts import DeliveryCounts





T = TypeVar("T", bound="WebhookOut")



@_attrs_define
class WebhookOut:
    """ A webhook as listed (its secret is shown only when it is created).

        Attributes:
            id (str):
            url (str):
            events (list[str]):
            created_at (str):
            deliveries (DeliveryCounts): How many of a webhook's events are in each delivery state.
     """

    id: str
    url: str
    events: list[str]
    created_at: str
    deliveries: DeliveryCounts
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.delivery_counts import DeliveryCounts # noqa: PLC0415
        id = self.id

        url = self.url

        events = self.events



        created_at = self.created_at

        deliveries = self.deliveries.to_dict()


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "id": id,
            "url": url,
            "events": events,
            "created_at": created_at,
            "deliveries": deliveries,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.delivery_counts import DeliveryCounts # noqa: PLC0415
        d = dict(src_dict)
        id = d.pop("id")

        url = d.pop("url")

        events = cast(list[str], d.pop("events"))


        created_at = d.pop("created_at")

        deliveries = DeliveryCounts.from_dict(d.pop("deliveries"))




        webhook_out = cls(
            id=id,
            url=url,
            events=events,
            created_at=created_at,
            deliveries=deliveries,
        )


        webhook_out.additional_properties = d
        return webhook_out

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
