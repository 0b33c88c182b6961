from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.pose_set import PoseSet
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.flange_pose_doc import FlangePoseDoc
  from ..models.image_point_doc import ImagePointDoc
  from ..models.pose_doc import PoseDoc





T = TypeVar("T", bound="PoseJsonBody")



@_attrs_define
class PoseJsonBody:
    """ `POST /v1/sessions/{id}/poses` JSON body.

        Attributes:
            joints_deg (list[float] | None | Unset): The robot's joint angles, degrees (one per joint). A camera pose may
                carry `flange_pose` instead; a session takes one kind only.
            flange_pose (FlangePoseDoc | None | Unset):
            set_ (PoseSet | Unset):
            image_points (list[ImagePointDoc] | None | Unset):
            measured_position_mm (list[float] | None | Unset):
            measured_pose (None | PoseDoc | Unset):
            label (None | str | Unset): What the pose is called in reports (e.g. the photo's file name); 1
                to 200 characters. Absent: the pose is numbered (`#12`).
            group (None | str | Unset): The arm configuration the pose was taken in, e.g. `"shoulder_a"`:
                poses of one group are held out together when the job judges which
                model predicts configurations it was not fitted to. 1 to 32 of
                `A-Z a-z 0-9 _ -`. Absent: grouped by joints 1–3 (within 3°).
     """

    joints_deg: list[float] | None | Unset = UNSET
    flange_pose: FlangePoseDoc | None | Unset = UNSET
    set_: PoseSet | Unset = UNSET
    image_points: list[ImagePointDoc] | None | Unset = UNSET
    measured_position_mm: list[float] | None | Unset = UNSET
    measured_pose: None | PoseDoc | Unset = UNSET
    label: None | str | Unset = UNSET
    group: None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.flange_pose_doc import FlangePoseDoc # noqa: PLC0415
        from ..models.image_point_doc import ImagePointDoc # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        joints_deg: list[float] | None | Unset
        if isinstance(self.joints_deg, Unset):
            joints_deg = UNSET
        elif isinstance(self.joints_deg, list):
            joints_deg = self.joints_deg


        else:
            joints_deg = self.joints_deg

        flange_pose: dict[str, Any] | None | Unset
        if isinstance(self.flange_pose, Unset):
            flange_pose = UNSET
        elif isinstance(self.flange_pose, FlangePoseDoc):
            flange_pose = self.flange_pose.to_dict()
        else:
            flange_pose = self.flange_pose

        set_: str | Unset = UNSET
        if not isinstance(self.set_, Unset):
            set_ = self.set_.value


        image_points: list[dict[str, Any]] | None | Unset
        if isinstance(self.image_points, Unset):
            image_points = UNSET
        elif isinstance(self.image_points, list):
            image_points = []
            for image_points_type_0_item_data in self.image_points:
                image_points_type_0_item = image_points_type_0_item_data.to_dict()
                image_points.append(image_points_type_0_item)


        else:
            image_points = self.image_points

        measured_position_mm: list[float] | None | Unset
        if isinstance(self.measured_position_mm, Unset):
            measured_position_mm = UNSET
        elif isinstance(self.measured_position_mm, list):
            measured_position_mm = self.measured_position_mm


        else:
            measured_position_mm = self.measured_position_mm

        measured_pose: dict[str, Any] | None | Unset
        if isinstance(self.measured_pose, Unset):
            measured_pose = UNSET
        elif isinstance(self.measured_pose, PoseDoc):
            measured_pose = self.measured_pose.to_dict()
        else:
            measured_pose = self.measured_pose

        label: None | str | Unset
        if isinstance(self.label, Unset):
            label = UNSET
        else:
            label = self.label

        group: None | str | Unset
        if isinstance(self.group, Unset):
            group = UNSET
        else:
            group = self.group


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if joints_deg is not UNSET:
            field_dict["joints_deg"] = joints_deg
        if flange_pose is not UNSET:
            field_dict["flange_pose"] = flange_pose
        if set_ is not UNSET:
            field_dict["set"] = set_
        if image_points is not UNSET:
            field_dict["image_points"] = image_points
        if measured_position_mm is not UNSET:
            field_dict["measured_position_mm"] = measured_position_mm
        if measured_pose is not UNSET:
            field_dict["measured_pose"] = measured_pose
        if label is not UNSET:
            field_dict["label"] = label
        if group is not UNSET:
            field_dict["group"] = group

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.flange_pose_doc import FlangePoseDoc # noqa: PLC0415
        from ..models.image_point_doc import ImagePointDoc # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        d = dict(src_dict)
        def _parse_joints_deg(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                joints_deg_type_0 = cast(list[float], data)

                return joints_deg_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        joints_deg = _parse_joints_deg(d.pop("joints_deg", UNSET))


        def _parse_flange_pose(data: object) -> FlangePoseDoc | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                flange_pose_type_1 = FlangePoseDoc.from_dict(data)



                return flange_pose_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FlangePoseDoc | None | Unset, data)

        flange_pose = _parse_flange_pose(d.pop("flange_pose", UNSET))


        _set_ = d.pop("set", UNSET)
        set_: PoseSet | Unset
        if isinstance(_set_,  Unset):
            set_ = UNSET
        else:
            set_ = PoseSet(_set_)




        def _parse_image_points(data: object) -> list[ImagePointDoc] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                image_points_type_0 = []
                _image_points_type_0 = data
                for image_points_type_0_item_data in (_image_points_type_0):
                    image_points_type_0_item = ImagePointDoc.from_dict(image_points_type_0_item_data)



                    image_points_type_0.append(image_points_type_0_item)

                return image_points_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[ImagePointDoc] | None | Unset, data)

        image_points = _parse_image_points(d.pop("image_points", UNSET))


        def _parse_measured_position_mm(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                measured_position_mm_type_0 = cast(list[float], data)

                return measured_position_mm_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        measured_position_mm = _parse_measured_position_mm(d.pop("measured_position_mm", UNSET))


        def _parse_measured_pose(data: object) -> None | PoseDoc | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                measured_pose_type_1 = PoseDoc.from_dict(data)



                return measured_pose_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PoseDoc | Unset, data)

        measured_pose = _parse_measured_pose(d.pop("measured_pose", UNSET))


        def _parse_label(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        label = _parse_label(d.pop("label", UNSET))


        def _parse_group(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        group = _parse_group(d.pop("group", UNSET))


        pose_json_body = cls(
            joints_deg=joints_deg,
            flange_pose=flange_pose,
            set_=set_,
            image_points=image_points,
            measured_position_mm=measured_position_mm,
            measured_pose=measured_pose,
            label=label,
            group=group,
        )

        return pose_json_body

