from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field
import json
from .. import types

from ..types import UNSET, Unset

from ..models.pose_set import PoseSet
from ..types import File, FileTypes
from ..types import UNSET, Unset
from io import BytesIO
from typing import cast






T = TypeVar("T", bound="PoseImageUpload")



@_attrs_define
class PoseImageUpload:
    """ The `multipart/form-data` pose upload (its schema; the parts are read
    one by one in `add_pose`).

        Attributes:
            image (File): The photo of the board, PNG or JPEG.
            joints_deg (None | str | Unset): JSON array of the joint angles in degrees, e.g. `[0, -10, 20, 0, 30, 0]`.
                A camera pose may send `flange_pose` instead (not both).
            flange_pose (None | str | Unset): The controller's flange pose in the base frame, as JSON:
                `{"translation_mm": [x, y, z], "rotation_deg": [rx, ry, rz]}` (fixed
                X-Y-Z angles, `R = Rz Ry Rx`) or `{"translation_mm", "matrix": 3x3}`.
            stage_position_mm (None | str | Unset): Stage sessions (instead of joints): the stage's reading, JSON
                `[x, y, z]` in mm (the stage's axes).
            sequence (int | None | Unset): Stage sessions: the sequence (board placement) of the image, 1 to 1000.
            set_ (None | PoseSet | Unset):
            group (None | str | Unset): The arm configuration the photo was taken in, e.g. `shoulder_a`
                (1 to 32 of `A-Z a-z 0-9 _ -`): poses of one group are held out
                together when the job chooses its model. Absent: grouped by joints
                1–3.
     """

    image: File
    joints_deg: None | str | Unset = UNSET
    flange_pose: None | str | Unset = UNSET
    stage_position_mm: None | str | Unset = UNSET
    sequence: int | None | Unset = UNSET
    set_: None | PoseSet | Unset = UNSET
    group: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        image = self.image.to_tuple()


        joints_deg: None | str | Unset
        if isinstance(self.joints_deg, Unset):
            joints_deg = UNSET
        else:
            joints_deg = self.joints_deg

        flange_pose: None | str | Unset
        if isinstance(self.flange_pose, Unset):
            flange_pose = UNSET
        else:
            flange_pose = self.flange_pose

        stage_position_mm: None | str | Unset
        if isinstance(self.stage_position_mm, Unset):
            stage_position_mm = UNSET
        else:
            stage_position_mm = self.stage_position_mm

        sequence: int | None | Unset
        if isinstance(self.sequence, Unset):
            sequence = UNSET
        else:
            sequence = self.sequence

        set_: None | str | Unset
        if isinstance(self.set_, Unset):
            set_ = UNSET
        elif isinstance(self.set_, PoseSet):
            set_ = self.set_.value
        else:
            set_ = self.set_

        group: None | str | Unset
        if isinstance(self.group, Unset):
            group = UNSET
        else:
            group = self.group


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "image": image,
        })
        if joints_deg is not UNSET:
            field_dict["joints_deg"] = joints_deg
        if flange_pose is not UNSET:
            field_dict["flange_pose"] = flange_pose
        if stage_position_mm is not UNSET:
            field_dict["stage_position_mm"] = stage_position_mm
        if sequence is not UNSET:
            field_dict["sequence"] = sequence
        if set_ is not UNSET:
            field_dict["set"] = set_
        if group is not UNSET:
            field_dict["group"] = group

        return field_dict


    def to_multipart(self) -> types.RequestFiles:
        files: types.RequestFiles = []

        files.append(("image", self.image.to_tuple()))



        if not isinstance(self.joints_deg, Unset):
            if isinstance(self.joints_deg, str):

                files.append(("joints_deg", (None, str(self.joints_deg).encode(), "text/plain")))
            else:
                files.append(("joints_deg", (None, str(self.joints_deg).encode(), "text/plain")))


        if not isinstance(self.flange_pose, Unset):
            if isinstance(self.flange_pose, str):

                files.append(("flange_pose", (None, str(self.flange_pose).encode(), "text/plain")))
            else:
                files.append(("flange_pose", (None, str(self.flange_pose).encode(), "text/plain")))


        if not isinstance(self.stage_position_mm, Unset):
            if isinstance(self.stage_position_mm, str):

                files.append(("stage_position_mm", (None, str(self.stage_position_mm).encode(), "text/plain")))
            else:
                files.append(("stage_position_mm", (None, str(self.stage_position_mm).encode(), "text/plain")))


        if not isinstance(self.sequence, Unset):
            if isinstance(self.sequence, int):

                files.append(("sequence", (None, str(self.sequence).encode(), "text/plain")))
            else:
                files.append(("sequence", (None, str(self.sequence).encode(), "text/plain")))


        if not isinstance(self.set_, Unset):
            if self.set_ is None:

                files.append(("set", (None, str(self.set_).encode(), "text/plain")))
            else:
                files.append(("set",  (None, str(self.set_.value).encode(), "text/plain")))


        if not isinstance(self.group, Unset):
            if isinstance(self.group, str):

                files.append(("group", (None, str(self.group).encode(), "text/plain")))
            else:
                files.append(("group", (None, str(self.group).encode(), "text/plain")))



        for prop_name, prop in self.additional_properties.items():
            files.append((prop_name, (None, str(prop).encode(), "text/plain")))



        return files


    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        image = File(
             payload = BytesIO(d.pop("image"))
        )




        def _parse_joints_deg(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        joints_deg = _parse_joints_deg(d.pop("joints_deg", UNSET))


        def _parse_flange_pose(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        flange_pose = _parse_flange_pose(d.pop("flange_pose", UNSET))


        def _parse_stage_position_mm(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        stage_position_mm = _parse_stage_position_mm(d.pop("stage_position_mm", UNSET))


        def _parse_sequence(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        sequence = _parse_sequence(d.pop("sequence", UNSET))


        def _parse_set_(data: object) -> None | PoseSet | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                set_type_1 = PoseSet(data)



                return set_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PoseSet | Unset, data)

        set_ = _parse_set_(d.pop("set", UNSET))


        def _parse_group(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        group = _parse_group(d.pop("group", UNSET))


        pose_image_upload = cls(
            image=image,
            joints_deg=joints_deg,
            flange_pose=flange_pose,
            stage_position_mm=stage_position_mm,
            sequence=sequence,
            set_=set_,
            group=group,
        )


        pose_image_upload.additional_properties = d
        return pose_image_upload

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
