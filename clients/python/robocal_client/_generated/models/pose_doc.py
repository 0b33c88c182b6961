from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="PoseDoc")



@_attrs_define
class PoseDoc:
    """ A pose in the contract form: translation in mm, fixed-axis X-Y-Z angles in
    degrees (`R = Rz(rz) Ry(ry) Rx(rx)`), optionally a 4x4 row-major matrix.

        Attributes:
            translation_mm (list[float]):
            rotation_deg (list[float]):
            matrix (list[list[float]] | None | Unset): 4x4 row-major homogeneous matrix (optional)
     """

    translation_mm: list[float]
    rotation_deg: list[float]
    matrix: list[list[float]] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        translation_mm = self.translation_mm



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
            "rotation_deg": rotation_deg,
        })
        if matrix is not UNSET:
            field_dict["matrix"] = matrix

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        translation_mm = cast(list[float], d.pop("translation_mm"))


        rotation_deg = cast(list[float], d.pop("rotation_deg"))


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


        pose_doc = cls(
            translation_mm=translation_mm,
            rotation_deg=rotation_deg,
            matrix=matrix,
        )

        return pose_doc

