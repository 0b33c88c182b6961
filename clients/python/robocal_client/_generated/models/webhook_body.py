from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="WebhookBody")



@_attrs_define
class WebhookBody:
    """ `POST /v1/webhooks`.

        Attributes:
            url (str): Where events are POSTed: an `http` or `https` URL of another
                service (not this one), without user name or password. Example: https://hooks.example.com/robocal.
            events (list[str]): The events to send: `job.finished`, `check.finished`, `set.approved`. Example:
                ['job.finished'].
     """

    url: str
    events: list[str]





    def to_dict(self) -> dict[str, Any]:
        url = self.url

        events = self.events




        field_dict: dict[str, Any] = {}

        field_dict.update({
            "url": url,
            "events": events,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        url = d.pop("url")

        events = cast(list[str], d.pop("events"))


        webhook_body = cls(
            url=url,
            events=events,
        )

        return webhook_body

