from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.controller_identity import ControllerIdentity





T = TypeVar("T", bound="CheckBody")



@_attrs_define
class CheckBody:
    """ A re-check's options: only the controller the caller expects.

        Attributes:
            expect_controller (ControllerIdentity | None | Unset):
     """

    expect_controller: ControllerIdentity | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        expect_controller: dict[str, Any] | None | Unset
        if isinstance(self.expect_controller, Unset):
            expect_controller = UNSET
        elif isinstance(self.expect_controller, ControllerIdentity):
            expect_controller = self.expect_controller.to_dict()
        else:
            expect_controller = self.expect_controller


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if expect_controller is not UNSET:
            field_dict["expect_controller"] = expect_controller

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.controller_identity import ControllerIdentity # noqa: PLC0415
        d = dict(src_dict)
        def _parse_expect_controller(data: object) -> ControllerIdentity | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                expect_controller_type_1 = ControllerIdentity.from_dict(data)



                return expect_controller_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ControllerIdentity | None | Unset, data)

        expect_controller = _parse_expect_controller(d.pop("expect_controller", UNSET))


        check_body = cls(
            expect_controller=expect_controller,
        )

        return check_body

