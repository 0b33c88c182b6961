from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.frame_pose import FramePose





T = TypeVar("T", bound="ForwardPose")



@_attrs_define
class ForwardPose:
    """ 
        Attributes:
            flange_in_base (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
            camera_in_target (FramePose): A pose in the contract's form plus its exact matrix: translation in mm,
                fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
            warnings (list[str]): One message per joint outside its limits (the pose is still
                computed: the controller would refuse it), and per joint outside
                the range its kept non-geometric terms were identified on (the set's
                `terms.joint_ranges_deg`: they extrapolate there). Empty when all
                are within.
            tool_in_target (FramePose | None | Unset):
            position_std_mm (float | None | Unset): Predicted 1σ of `tool_in_target` (or `camera_in_target` without a
                tool) from the set's parameter covariance, board transform included:
                `sqrt(trace)` of the 3x3 position covariance, the RMS length of the
                3-D error (mm). Absent for sets stored without a covariance.
            rotation_std_deg (float | None | Unset): The same pose's orientation 1σ: `sqrt(trace)` of its 3x3 rotation
                covariance (deg).
            flange_position_std_mm (float | None | Unset): Predicted 1σ of `flange_in_base` (link parameters only), as
                `position_std_mm` (mm).
            flange_rotation_std_deg (float | None | Unset): Predicted orientation 1σ of `flange_in_base` (deg).
     """

    flange_in_base: FramePose
    camera_in_target: FramePose
    warnings: list[str]
    tool_in_target: FramePose | None | Unset = UNSET
    position_std_mm: float | None | Unset = UNSET
    rotation_std_deg: float | None | Unset = UNSET
    flange_position_std_mm: float | None | Unset = UNSET
    flange_rotation_std_deg: float | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        flange_in_base = self.flange_in_base.to_dict()

        camera_in_target = self.camera_in_target.to_dict()

        warnings = self.warnings



        tool_in_target: dict[str, Any] | None | Unset
        if isinstance(self.tool_in_target, Unset):
            tool_in_target = UNSET
        elif isinstance(self.tool_in_target, FramePose):
            tool_in_target = self.tool_in_target.to_dict()
        else:
            tool_in_target = self.tool_in_target

        position_std_mm: float | None | Unset
        if isinstance(self.position_std_mm, Unset):
            position_std_mm = UNSET
        else:
            position_std_mm = self.position_std_mm

        rotation_std_deg: float | None | Unset
        if isinstance(self.rotation_std_deg, Unset):
            rotation_std_deg = UNSET
        else:
            rotation_std_deg = self.rotation_std_deg

        flange_position_std_mm: float | None | Unset
        if isinstance(self.flange_position_std_mm, Unset):
            flange_position_std_mm = UNSET
        else:
            flange_position_std_mm = self.flange_position_std_mm

        flange_rotation_std_deg: float | None | Unset
        if isinstance(self.flange_rotation_std_deg, Unset):
            flange_rotation_std_deg = UNSET
        else:
            flange_rotation_std_deg = self.flange_rotation_std_deg


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "flange_in_base": flange_in_base,
            "camera_in_target": camera_in_target,
            "warnings": warnings,
        })
        if tool_in_target is not UNSET:
            field_dict["tool_in_target"] = tool_in_target
        if position_std_mm is not UNSET:
            field_dict["position_std_mm"] = position_std_mm
        if rotation_std_deg is not UNSET:
            field_dict["rotation_std_deg"] = rotation_std_deg
        if flange_position_std_mm is not UNSET:
            field_dict["flange_position_std_mm"] = flange_position_std_mm
        if flange_rotation_std_deg is not UNSET:
            field_dict["flange_rotation_std_deg"] = flange_rotation_std_deg

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.frame_pose import FramePose # noqa: PLC0415
        d = dict(src_dict)
        flange_in_base = FramePose.from_dict(d.pop("flange_in_base"))




        camera_in_target = FramePose.from_dict(d.pop("camera_in_target"))




        warnings = cast(list[str], d.pop("warnings"))


        def _parse_tool_in_target(data: object) -> FramePose | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                tool_in_target_type_1 = FramePose.from_dict(data)



                return tool_in_target_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(FramePose | None | Unset, data)

        tool_in_target = _parse_tool_in_target(d.pop("tool_in_target", UNSET))


        def _parse_position_std_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        position_std_mm = _parse_position_std_mm(d.pop("position_std_mm", UNSET))


        def _parse_rotation_std_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        rotation_std_deg = _parse_rotation_std_deg(d.pop("rotation_std_deg", UNSET))


        def _parse_flange_position_std_mm(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        flange_position_std_mm = _parse_flange_position_std_mm(d.pop("flange_position_std_mm", UNSET))


        def _parse_flange_rotation_std_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        flange_rotation_std_deg = _parse_flange_rotation_std_deg(d.pop("flange_rotation_std_deg", UNSET))


        forward_pose = cls(
            flange_in_base=flange_in_base,
            camera_in_target=camera_in_target,
            warnings=warnings,
            tool_in_target=tool_in_target,
            position_std_mm=position_std_mm,
            rotation_std_deg=rotation_std_deg,
            flange_position_std_mm=flange_position_std_mm,
            flange_rotation_std_deg=flange_rotation_std_deg,
        )


        forward_pose.additional_properties = d
        return forward_pose

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
