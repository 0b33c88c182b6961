from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.stage_camera_set_kind import StageCameraSetKind
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.intrinsics import Intrinsics
  from ..models.intrinsics_std import IntrinsicsStd
  from ..models.stage_sequence import StageSequence





T = TypeVar("T", bound="StageCameraSet")



@_attrs_define
class StageCameraSet:
    """ A stage camera set (`kind` `stage_camera`).

        Attributes:
            instrument (str): Always `stage`.
            session_id (str): The session the set was calibrated from.
            camera (Intrinsics): Pinhole intrinsics (px) and Brown–Conrady distortion.
            camera_mode (str): Always `stage`: fitted with the stage's translations as constraints.
            sequences (list[StageSequence]): Each fitted sequence (board placement).
            kind (StageCameraSetKind): What the set identified (the variant's tag).
            camera_std (IntrinsicsStd | None | Unset):
     """

    instrument: str
    session_id: str
    camera: Intrinsics
    camera_mode: str
    sequences: list[StageSequence]
    kind: StageCameraSetKind
    camera_std: IntrinsicsStd | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.intrinsics_std import IntrinsicsStd # noqa: PLC0415
        from ..models.stage_sequence import StageSequence # noqa: PLC0415
        instrument = self.instrument

        session_id = self.session_id

        camera = self.camera.to_dict()

        camera_mode = self.camera_mode

        sequences = []
        for sequences_item_data in self.sequences:
            sequences_item = sequences_item_data.to_dict()
            sequences.append(sequences_item)



        kind = self.kind.value

        camera_std: dict[str, Any] | None | Unset
        if isinstance(self.camera_std, Unset):
            camera_std = UNSET
        elif isinstance(self.camera_std, IntrinsicsStd):
            camera_std = self.camera_std.to_dict()
        else:
            camera_std = self.camera_std


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "instrument": instrument,
            "session_id": session_id,
            "camera": camera,
            "camera_mode": camera_mode,
            "sequences": sequences,
            "kind": kind,
        })
        if camera_std is not UNSET:
            field_dict["camera_std"] = camera_std

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.intrinsics_std import IntrinsicsStd # noqa: PLC0415
        from ..models.stage_sequence import StageSequence # noqa: PLC0415
        d = dict(src_dict)
        instrument = d.pop("instrument")

        session_id = d.pop("session_id")

        camera = Intrinsics.from_dict(d.pop("camera"))




        camera_mode = d.pop("camera_mode")

        sequences = []
        _sequences = d.pop("sequences")
        for sequences_item_data in (_sequences):
            sequences_item = StageSequence.from_dict(sequences_item_data)



            sequences.append(sequences_item)


        kind = StageCameraSetKind(d.pop("kind"))




        def _parse_camera_std(data: object) -> IntrinsicsStd | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                camera_std_type_1 = IntrinsicsStd.from_dict(data)



                return camera_std_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(IntrinsicsStd | None | Unset, data)

        camera_std = _parse_camera_std(d.pop("camera_std", UNSET))


        stage_camera_set = cls(
            instrument=instrument,
            session_id=session_id,
            camera=camera,
            camera_mode=camera_mode,
            sequences=sequences,
            kind=kind,
            camera_std=camera_std,
        )


        stage_camera_set.additional_properties = d
        return stage_camera_set

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
