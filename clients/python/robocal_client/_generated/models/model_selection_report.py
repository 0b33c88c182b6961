from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.rung_report import RungReport





T = TypeVar("T", bound="ModelSelectionReport")



@_attrs_define
class ModelSelectionReport:
    """ How the model was chosen and how it was validated.

        Attributes:
            configurations (int): Distinct arm configurations (joints 1–3 within a few degrees, or
                the poses' `group`) among the poses compared.
            val_shares_configurations (bool): Whether validation poses share configurations with calibration poses.
            validation (str): `leave_group_out` (the headline before/after are held-out
                configurations' predictions) or `validation_poses`.
            folds (int): Folds of the held-out comparison.
            rungs (list[RungReport]):
            chosen (str): The rung kept.
            reason (str):
            undetermined (list[str]): Parameters the campaign could not determine: held at nominal (or
                at their prior) whatever the data said.
     """

    configurations: int
    val_shares_configurations: bool
    validation: str
    folds: int
    rungs: list[RungReport]
    chosen: str
    reason: str
    undetermined: list[str]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.rung_report import RungReport # noqa: PLC0415
        configurations = self.configurations

        val_shares_configurations = self.val_shares_configurations

        validation = self.validation

        folds = self.folds

        rungs = []
        for rungs_item_data in self.rungs:
            rungs_item = rungs_item_data.to_dict()
            rungs.append(rungs_item)



        chosen = self.chosen

        reason = self.reason

        undetermined = self.undetermined




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "configurations": configurations,
            "val_shares_configurations": val_shares_configurations,
            "validation": validation,
            "folds": folds,
            "rungs": rungs,
            "chosen": chosen,
            "reason": reason,
            "undetermined": undetermined,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.rung_report import RungReport # noqa: PLC0415
        d = dict(src_dict)
        configurations = d.pop("configurations")

        val_shares_configurations = d.pop("val_shares_configurations")

        validation = d.pop("validation")

        folds = d.pop("folds")

        rungs = []
        _rungs = d.pop("rungs")
        for rungs_item_data in (_rungs):
            rungs_item = RungReport.from_dict(rungs_item_data)



            rungs.append(rungs_item)


        chosen = d.pop("chosen")

        reason = d.pop("reason")

        undetermined = cast(list[str], d.pop("undetermined"))


        model_selection_report = cls(
            configurations=configurations,
            val_shares_configurations=val_shares_configurations,
            validation=validation,
            folds=folds,
            rungs=rungs,
            chosen=chosen,
            reason=reason,
            undetermined=undetermined,
        )


        model_selection_report.additional_properties = d
        return model_selection_report

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
