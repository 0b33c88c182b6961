from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="FlangePoseDoc")



@_attrs_define
class FlangePoseDoc:
    """ The flange in the robot base frame (`base_to_flange`): `translation_mm`
    and either `rotation_deg` (fixed-axis X-Y-Z angles in degrees,
    `R = Rz(rz) Ry(ry) Rx(rx)`, as every pose of the contract) or `matrix`
    (the 3x3 rotation, row-major, orthonormal with determinant +1), not both.

        Attributes:
            translation_mm (list[float]):
            rotation_deg (list[float] | None | Unset):
            matrix (list[list[float]] | None | Unset): 3x3 row-major rotation of the flange in the base frame (instead of
                rotation_deg)
     """

    translation_mm: list[float]
    rotation_deg: list[float] | None | Unset = UNSET
    matrix: list[list[float]] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        translation_mm = self.translation_mm



        rotation_deg: list[float] | None | Unset
        if isinstance(self.rotation_deg, Unset):
            rotation_deg = UNSET
        elif isinstance(self.rotation_deg, list):
            rotation_deg = self.rotation_deg


        else:
            rotation_deg = self.rotation_deg

        matrix: list[list[float]] | None | Unset
        if isinstance(self.matrix, Unset):
            matrix = UNSET
        elif isinstance(self.matrix, list):
            matrix = []
            for matrix_type_0_item_data in self.matrix:
                matrix_type_0_item = matrix_type_0_item_data


                matrix.append(matrix_type_0_item)


        else:
            matrix = self.matrix


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "translation_mm": translation_mm,
        })
        if rotation_deg is not UNSET:
            field_dict["rotation_deg"] = rotation_deg
        if matrix is not UNSET:
            field_dict["matrix"] = matrix

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        translation_mm = cast(list[float], d.pop("translation_mm"))


        def _parse_rotation_deg(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                rotation_deg_type_0 = cast(list[float], data)

                return rotation_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        rotation_deg = _parse_rotation_deg(d.pop("rotation_deg", UNSET))


        def _parse_matrix(data: object) -> list[list[float]] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                matrix_type_0 = []
                _matrix_type_0 = data
                for matrix_type_0_item_data in (_matrix_type_0):
                    matrix_type_0_item = cast(list[float], matrix_type_0_item_data)

                    matrix_type_0.append(matrix_type_0_item)

                return matrix_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[list[float]] | None | Unset, data)

        matrix = _parse_matrix(d.pop("matrix", UNSET))


        flange_pose_doc = cls(
            translation_mm=translation_mm,
            rotation_deg=rotation_deg,
            matrix=matrix,
        )

        return flange_pose_doc

