from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.uncertainty_cell import UncertaintyCell





T = TypeVar("T", bound="UncertaintyMapReport")



@_attrs_define
class UncertaintyMapReport:
    """ Predicted 1σ of the tool (camera or tracker tool point) position over a
    horizontal slice of the workspace: flange positions on a grid in the
    robot base frame at the campaign's median height and one flange
    orientation, each solved by the calibrated inverse kinematics.

        Attributes:
            z_mm (float): Height of the slice: flange z in the base frame (mm).
            rotation_deg (list[float]): The flange's fixed-axis X-Y-Z orientation over the slice (deg).
            step_mm (float): Grid spacing (mm).
            cells (list[UncertaintyCell]): Reachable grid points with their predicted σ.
            poses_xy_mm (list[list[float]]): The calibration poses' flange positions (x, y mm, base frame).
     """

    z_mm: float
    rotation_deg: list[float]
    step_mm: float
    cells: list[UncertaintyCell]
    poses_xy_mm: list[list[float]]
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.uncertainty_cell import UncertaintyCell # noqa: PLC0415
        z_mm = self.z_mm

        rotation_deg = self.rotation_deg



        step_mm = self.step_mm

        cells = []
        for cells_item_data in self.cells:
            cells_item = cells_item_data.to_dict()
            cells.append(cells_item)



        poses_xy_mm = []
        for poses_xy_mm_item_data in self.poses_xy_mm:
            poses_xy_mm_item = poses_xy_mm_item_data


            poses_xy_mm.append(poses_xy_mm_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "z_mm": z_mm,
            "rotation_deg": rotation_deg,
            "step_mm": step_mm,
            "cells": cells,
            "poses_xy_mm": poses_xy_mm,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.uncertainty_cell import UncertaintyCell # noqa: PLC0415
        d = dict(src_dict)
        z_mm = d.pop("z_mm")

        rotation_deg = cast(list[float], d.pop("rotation_deg"))


        step_mm = d.pop("step_mm")

        cells = []
        _cells = d.pop("cells")
        for cells_item_data in (_cells):
            cells_item = UncertaintyCell.from_dict(cells_item_data)



            cells.append(cells_item)


        poses_xy_mm = []
        _poses_xy_mm = d.pop("poses_xy_mm")
        for poses_xy_mm_item_data in (_poses_xy_mm):
            poses_xy_mm_item = cast(list[float], poses_xy_mm_item_data)

            poses_xy_mm.append(poses_xy_mm_item)


        uncertainty_map_report = cls(
            z_mm=z_mm,
            rotation_deg=rotation_deg,
            step_mm=step_mm,
            cells=cells,
            poses_xy_mm=poses_xy_mm,
        )


        uncertainty_map_report.additional_properties = d
        return uncertainty_map_report

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
