from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.plan_purpose_doc import PlanPurposeDoc
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.filter_count_doc import FilterCountDoc
  from ..models.planned_pose_doc import PlannedPoseDoc
  from ..models.predicted_doc import PredictedDoc





T = TypeVar("T", bound="CampaignPlanOut")



@_attrs_define
class CampaignPlanOut:
    """ A stored campaign plan.

        Attributes:
            id (str):
            serial (str):
            poses (list[PlannedPoseDoc]): In path order.
            predicted (PredictedDoc): What the plan predicts for the campaign.
            purpose (PlanPurposeDoc): What the plan is for; by default a plan of 5 to 10 poses is a quick check.
            start_joints_deg (list[float]): Where the path starts.
            path_length_deg (float): Sum over the moves of the largest joint change (deg).
            candidates (list[FilterCountDoc]): Survivors of every candidate filter, in order.
            model (str): `"nominal"` or the parameter set `"{serial}/{version}"` whose
                kinematics the plan used.
            created_at (str):
            extend_session (None | str | Unset): The session the plan extends (the request's `extend_session`): the
                poses are the ones to add to it.
     """

    id: str
    serial: str
    poses: list[PlannedPoseDoc]
    predicted: PredictedDoc
    purpose: PlanPurposeDoc
    start_joints_deg: list[float]
    path_length_deg: float
    candidates: list[FilterCountDoc]
    model: str
    created_at: str
    extend_session: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.filter_count_doc import FilterCountDoc # noqa: PLC0415
        from ..models.planned_pose_doc import PlannedPoseDoc # noqa: PLC0415
        from ..models.predicted_doc import PredictedDoc # noqa: PLC0415
        id = self.id

        serial = self.serial

        poses = []
        for poses_item_data in self.poses:
            poses_item = poses_item_data.to_dict()
            poses.append(poses_item)



        predicted = self.predicted.to_dict()

        purpose = self.purpose.value

        start_joints_deg = self.start_joints_deg



        path_length_deg = self.path_length_deg

        candidates = []
        for candidates_item_data in self.candidates:
            candidates_item = candidates_item_data.to_dict()
            candidates.append(candidates_item)



        model = self.model

        created_at = self.created_at

        extend_session: None | str | Unset
        if isinstance(self.extend_session, Unset):
            extend_session = UNSET
        else:
            extend_session = self.extend_session


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "id": id,
            "serial": serial,
            "poses": poses,
            "predicted": predicted,
            "purpose": purpose,
            "start_joints_deg": start_joints_deg,
            "path_length_deg": path_length_deg,
            "candidates": candidates,
            "model": model,
            "created_at": created_at,
        })
        if extend_session is not UNSET:
            field_dict["extend_session"] = extend_session

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.filter_count_doc import FilterCountDoc # noqa: PLC0415
        from ..models.planned_pose_doc import PlannedPoseDoc # noqa: PLC0415
        from ..models.predicted_doc import PredictedDoc # noqa: PLC0415
        d = dict(src_dict)
        id = d.pop("id")

        serial = d.pop("serial")

        poses = []
        _poses = d.pop("poses")
        for poses_item_data in (_poses):
            poses_item = PlannedPoseDoc.from_dict(poses_item_data)



            poses.append(poses_item)


        predicted = PredictedDoc.from_dict(d.pop("predicted"))




        purpose = PlanPurposeDoc(d.pop("purpose"))




        start_joints_deg = cast(list[float], d.pop("start_joints_deg"))


        path_length_deg = d.pop("path_length_deg")

        candidates = []
        _candidates = d.pop("candidates")
        for candidates_item_data in (_candidates):
            candidates_item = FilterCountDoc.from_dict(candidates_item_data)



            candidates.append(candidates_item)


        model = d.pop("model")

        created_at = d.pop("created_at")

        def _parse_extend_session(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        extend_session = _parse_extend_session(d.pop("extend_session", UNSET))


        campaign_plan_out = cls(
            id=id,
            serial=serial,
            poses=poses,
            predicted=predicted,
            purpose=purpose,
            start_joints_deg=start_joints_deg,
            path_length_deg=path_length_deg,
            candidates=candidates,
            model=model,
            created_at=created_at,
            extend_session=extend_session,
        )


        campaign_plan_out.additional_properties = d
        return campaign_plan_out

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
