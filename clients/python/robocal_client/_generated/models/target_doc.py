from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.target_kind import TargetKind
from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="TargetDoc")



@_attrs_define
class TargetDoc:
    """ The board. Dots: `rows`, `cols`, `pitch_mm`, `dot_diameter_mm`,
    `origin_marker_diameter_mm` (omitted for a grid without the larger
    origin dot: its ordering is then known only up to the grid's symmetry).
    Asymmetric circles (OpenCV's `CALIB_CB_ASYMMETRIC_GRID`, found by
    `findCirclesGrid(image, (cols, rows))`): `rows`, `cols` (dots per row),
    `pitch_mm` (OpenCV's `squareSize`: dot `(i, j)` at
    `((2 j + i mod 2) pitch, i pitch)`, so dots in a row are `2 pitch`
    apart), `dot_diameter_mm`. ChArUco (OpenCV's `CharucoBoard`):
    `squares` `[cols, rows]`, `square_mm`, `marker_mm`, `dictionary` (an
    OpenCV predefined dictionary name, e.g. `DICT_5X5_100`) and
    `legacy_layout` (boards made by OpenCV < 4.6; default false).
    Chessboard (OpenCV's `findChessboardCorners`): `inner_corners`
    `[cols, rows]` and `square_mm`; corners in OpenCV's order. A field of
    another kind is refused.

        Attributes:
            kind (TargetKind | Unset): What board the camera sees: robocal's dot grid (`kind`
                `"dots"`, the default, may be omitted), a ChArUco board, a chessboard
                or OpenCV's asymmetric circle grid.
            rows (int | None | Unset):
            cols (int | None | Unset):
            pitch_mm (float | None | Unset):
            dot_diameter_mm (float | None | Unset):
            origin_marker_diameter_mm (float | None | Unset):
            squares (list[int] | None | Unset):
            square_mm (float | None | Unset):
            marker_mm (float | None | Unset):
            dictionary (None | str | Unset):
            legacy_layout (bool | None | Unset):
            inner_corners (list[int] | None | Unset): Chessboard: inner corners `[cols, rows]` (`cols` per row), as
                OpenCV's `patternSize`.
     """

    kind: TargetKind | Unset = UNSET
    rows: int | None | Unset = UNSET
    cols: int | None | Unset = UNSET
    pitch_mm: float | None | Unset = UNSET
    dot_diameter_mm: float | None | Unset = UNSET
    origin_marker_diameter_mm: float | None | Unset = UNSET
    squares: list[int] | None | Unset = UNSET
    square_mm: float | None | Unset = UNSET
    marker_mm: float | None | Unset = UNSET
    dictionary: None | str | Unset = UNSET
    legacy_layout: bool | None | Unset = UNSET
    inner_corners: list[int] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        kind: str | Unset = UNSET
        if not isinstance(self.kind, Unset):
            kind = self.kind.value


        rows: int | None | Unset
        if isinstance(self.rows, Unset):
            rows = UNSET
        else:
            rows = self.rows

        cols: int | None | Unset
        if isinstance(self.cols, Unset):
            cols = UNSET
        else:
            cols = self.cols

        pitch_mm: float | None | Unset
        if isinstance(self.pitch_mm, Unset):
            pitch_mm = UNSET
        else:
            pitch_mm = self.pitch_mm

        dot_diameter_mm: float | None | Unset
        if isinstance(self.dot_diameter_mm, Unset):
            dot_diameter_mm = UNSET
        else:
            dot_diameter_mm = self.dot_diameter_mm

        origin_marker_diameter_mm: float | None | Unset
        if isinstance(self.origin_marker_diameter_mm, Unset):
            origin_marker_diameter_mm = UNSET
        else:
            origin_marker_diameter_mm = self.origin_marker_diameter_mm

        squares: list[int] | None | Unset
        if isinstance(self.squares, Unset):
            squares = UNSET
        elif isinstance(self.squares, list):
            squares = self.squares


        else:
            squares = self.squares

        square_mm: float | None | Unset
        if isinstance(self.square_mm, Unset):
            square_mm = UNSET
        else:
            square_mm = self.square_mm

        marker_mm: float | None | Unset
        if isinstance(self.marker_mm, Unset):
            marker_mm = UNSET
        else:
            marker_mm = self.marker_mm

        dictionary: None | str | Unset
        if isinstance(self.dictionary, Unset):
            dictionary = UNSET
        else:
            dictionary = self.dictionary

        legacy_layout: bool | None | Unset
        if isinstance(self.legacy_layout, Unset):
            legacy_layout = UNSET
        else:
            legacy_layout = self.legacy_layout

        inner_corners: list[int] | None | Unset
        if isinstance(self.inner_corners, Unset):
            inner_corners = UNSET
        elif isinstance(self.inner_corners, list):
            inner_corners = self.inner_corners


        else:
            inner_corners = self.inner_corners


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if kind is not UNSET:
            field_dict["kind"] = kind
        if rows is not UNSET:
            field_dict["rows"] = rows
        if cols is not UNSET:
            field_dict["cols"] = cols
        if pitch_mm is not UNSET:
            field_dict["pitch_mm"] = pitch_mm
        if dot_diameter_mm is not UNSET:
            field_dict["dot_diameter_mm"] = dot_diameter_mm
        if origin_marker_diameter_mm is not UNSET:
            field_dict["origin_marker_diameter_mm"] = origin_marker_diameter_mm
        if squares is not UNSET:
            field_dict["squares"] = squares
        if square_mm is not UNSET:
            field_dict["square_mm"] = square_mm
        if marker_mm is not UNSET:
            field_dict["marker_mm"] = marker_mm
        if dictionary is not UNSET:
            field_dict["dictionary"] = dictionary
        if legacy_layout is not UNSET:
            field_dict["legacy_layout"] = legacy_layout
        if inner_corners is not UNSET:
            field_dict["inner_corners"] = inner_corners

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        _kind = d.pop("kind", UNSET)
        kind: TargetKind | Unset
        if isinstance(_kind,  Unset):
            kind = UNSET
        else:
            kind = TargetKind(_kind)




        def _parse_rows(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        rows = _parse_rows(d.pop("rows", UNSET))


        def _parse_cols(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        cols = _parse_cols(d.pop("cols", UNSET))


        def _parse_pitch_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        pitch_mm = _parse_pitch_mm(d.pop("pitch_mm", UNSET))


        def _parse_dot_diameter_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        dot_diameter_mm = _parse_dot_diameter_mm(d.pop("dot_diameter_mm", UNSET))


        def _parse_origin_marker_diameter_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        origin_marker_diameter_mm = _parse_origin_marker_diameter_mm(d.pop("origin_marker_diameter_mm", UNSET))


        def _parse_squares(data: object) -> list[int] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                squares_type_0 = cast(list[int], data)

                return squares_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[int] | None | Unset, data)

        squares = _parse_squares(d.pop("squares", UNSET))


        def _parse_square_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        square_mm = _parse_square_mm(d.pop("square_mm", UNSET))


        def _parse_marker_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        marker_mm = _parse_marker_mm(d.pop("marker_mm", UNSET))


        def _parse_dictionary(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        dictionary = _parse_dictionary(d.pop("dictionary", UNSET))


        def _parse_legacy_layout(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        legacy_layout = _parse_legacy_layout(d.pop("legacy_layout", UNSET))


        def _parse_inner_corners(data: object) -> list[int] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                inner_corners_type_0 = cast(list[int], data)

                return inner_corners_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[int] | None | Unset, data)

        inner_corners = _parse_inner_corners(d.pop("inner_corners", UNSET))


        target_doc = cls(
            kind=kind,
            rows=rows,
            cols=cols,
            pitch_mm=pitch_mm,
            dot_diameter_mm=dot_diameter_mm,
            origin_marker_diameter_mm=origin_marker_diameter_mm,
            squares=squares,
            square_mm=square_mm,
            marker_mm=marker_mm,
            dictionary=dictionary,
            legacy_layout=legacy_layout,
            inner_corners=inner_corners,
        )

        return target_doc

