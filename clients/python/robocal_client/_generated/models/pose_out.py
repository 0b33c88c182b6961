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
  from ..models.image_meta import ImageMeta
  from ..models.pose_detection_out import PoseDetectionOut
  from ..models.pose_doc import PoseDoc
  from ..models.pose_image_point import PoseImagePoint





T = TypeVar("T", bound="PoseOut")



@_attrs_define
class PoseOut:
    """ 
        Attributes:
            id (str):
            session_id (str):
            joints_deg (list[float]): The joint angles (empty for a pose sent with `flange_pose`).
            set_ (PoseSet):
            source (str): `image`, `image_points` or `measured`.
            detected_points (int): Number of image points: uploaded, or found by the dot detector on
                the image (at upload, and again by the last calibration job). 0 for
                an image whose board was not found (`detection_error` says why).
            points (list[PoseImagePoint]): The image points: as uploaded, or as the detector found them at
                upload, or as the last calibration job measured them (then with the
                perspective-bias-corrected centres as `x`, `y`, the raw ones as
                `raw_x`, `raw_y`, and residuals once that job succeeded).
            created_at (str):
            flange_pose (FlangePoseDoc | None | Unset):
            stage_position_mm (list[float] | None | Unset): A stage session's image: the stage's reading (mm, stage axes).
            sequence (int | None | Unset): A stage session's image: its sequence (board placement).
            detection_error (None | str | Unset): Why the dot detector found no board on this pose's image (at upload,
                or in the last calibration job). The image is kept either way; a
                job leaves such poses out.
            detection (None | PoseDetectionOut | Unset):
            image (ImageMeta | None | Unset):
            measured_position_mm (list[float] | None | Unset):
            measured_pose (None | PoseDoc | Unset):
            label (None | str | Unset): What the pose is called: the uploaded image's file name (multipart
                filename, or its path in a dataset archive) or a JSON pose's
                `label`. Absent when none was given; reports then number the pose.
            group (None | str | Unset): The arm configuration the pose was taken in, as uploaded. Absent:
                a job groups the pose by its joints 1–3.
     """

    id: str
    session_id: str
    joints_deg: list[float]
    set_: PoseSet
    source: str
    detected_points: int
    points: list[PoseImagePoint]
    created_at: str
    flange_pose: FlangePoseDoc | None | Unset = UNSET
    stage_position_mm: list[float] | None | Unset = UNSET
    sequence: int | None | Unset = UNSET
    detection_error: None | str | Unset = UNSET
    detection: None | PoseDetectionOut | Unset = UNSET
    image: ImageMeta | None | Unset = UNSET
    measured_position_mm: list[float] | None | Unset = UNSET
    measured_pose: None | PoseDoc | Unset = UNSET
    label: None | str | Unset = UNSET
    group: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.flange_pose_doc import FlangePoseDoc # noqa: PLC0415
        from ..models.image_meta import ImageMeta # noqa: PLC0415
        from ..models.pose_detection_out import PoseDetectionOut # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        from ..models.pose_image_point import PoseImagePoint # noqa: PLC0415
        id = self.id

        session_id = self.session_id

        joints_deg = self.joints_deg



        set_ = self.set_.value

        source = self.source

        detected_points = self.detected_points

        points = []
        for points_item_data in self.points:
            points_item = points_item_data.to_dict()
            points.append(points_item)



        created_at = self.created_at

        flange_pose: dict[str, Any] | None | Unset
        if isinstance(self.flange_pose, Unset):
            flange_pose = UNSET
        elif isinstance(self.flange_pose, FlangePoseDoc):
            flange_pose = self.flange_pose.to_dict()
        else:
            flange_pose = self.flange_pose

        stage_position_mm: list[float] | None | Unset
        if isinstance(self.stage_position_mm, Unset):
            stage_position_mm = UNSET
        elif isinstance(self.stage_position_mm, list):
            stage_position_mm = self.stage_position_mm


        else:
            stage_position_mm = self.stage_position_mm

        sequence: int | None | Unset
        if isinstance(self.sequence, Unset):
            sequence = UNSET
        else:
            sequence = self.sequence

        detection_error: None | str | Unset
        if isinstance(self.detection_error, Unset):
            detection_error = UNSET
        else:
            detection_error = self.detection_error

        detection: dict[str, Any] | None | Unset
        if isinstance(self.detection, Unset):
            detection = UNSET
        elif isinstance(self.detection, PoseDetectionOut):
            detection = self.detection.to_dict()
        else:
            detection = self.detection

        image: dict[str, Any] | None | Unset
        if isinstance(self.image, Unset):
            image = UNSET
        elif isinstance(self.image, ImageMeta):
            image = self.image.to_dict()
        else:
            image = self.image

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
        field_dict.update(self.additional_properties)
        field_dict.update({
            "id": id,
            "session_id": session_id,
            "joints_deg": joints_deg,
            "set": set_,
            "source": source,
            "detected_points": detected_points,
            "points": points,
            "created_at": created_at,
        })
        if flange_pose is not UNSET:
            field_dict["flange_pose"] = flange_pose
        if stage_position_mm is not UNSET:
            field_dict["stage_position_mm"] = stage_position_mm
        if sequence is not UNSET:
            field_dict["sequence"] = sequence
        if detection_error is not UNSET:
            field_dict["detection_error"] = detection_error
        if detection is not UNSET:
            field_dict["detection"] = detection
        if image is not UNSET:
            field_dict["image"] = image
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
        from ..models.image_meta import ImageMeta # noqa: PLC0415
        from ..models.pose_detection_out import PoseDetectionOut # noqa: PLC0415
        from ..models.pose_doc import PoseDoc # noqa: PLC0415
        from ..models.pose_image_point import PoseImagePoint # noqa: PLC0415
        d = dict(src_dict)
        id = d.pop("id")

        session_id = d.pop("session_id")

        joints_deg = cast(list[float], d.pop("joints_deg"))


        set_ = PoseSet(d.pop("set"))




        source = d.pop("source")

        detected_points = d.pop("detected_points")

        points = []
        _points = d.pop("points")
        for points_item_data in (_points):
            points_item = PoseImagePoint.from_dict(points_item_data)



            points.append(points_item)


        created_at = d.pop("created_at")

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


        def _parse_stage_position_mm(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                stage_position_mm_type_0 = cast(list[float], data)

                return stage_position_mm_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        stage_position_mm = _parse_stage_position_mm(d.pop("stage_position_mm", UNSET))


        def _parse_sequence(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        sequence = _parse_sequence(d.pop("sequence", UNSET))


        def _parse_detection_error(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        detection_error = _parse_detection_error(d.pop("detection_error", UNSET))


        def _parse_detection(data: object) -> None | PoseDetectionOut | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                detection_type_1 = PoseDetectionOut.from_dict(data)



                return detection_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | PoseDetectionOut | Unset, data)

        detection = _parse_detection(d.pop("detection", UNSET))


        def _parse_image(data: object) -> ImageMeta | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                image_type_1 = ImageMeta.from_dict(data)



                return image_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ImageMeta | None | Unset, data)

        image = _parse_image(d.pop("image", UNSET))


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


        pose_out = cls(
            id=id,
            session_id=session_id,
            joints_deg=joints_deg,
            set_=set_,
            source=source,
            detected_points=detected_points,
            points=points,
            created_at=created_at,
            flange_pose=flange_pose,
            stage_position_mm=stage_position_mm,
            sequence=sequence,
            detection_error=detection_error,
            detection=detection,
            image=image,
            measured_position_mm=measured_position_mm,
            measured_pose=measured_pose,
            label=label,
            group=group,
        )


        pose_out.additional_properties = d
        return pose_out

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
