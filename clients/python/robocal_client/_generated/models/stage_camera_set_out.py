from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.release_status import ReleaseStatus
from ..models.stage_camera_set_kind import StageCameraSetKind
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.intrinsics import Intrinsics
  from ..models.intrinsics_std import IntrinsicsStd
  from ..models.stage_sequence import StageSequence





T = TypeVar("T", bound="StageCameraSetOut")



@_attrs_define
class StageCameraSetOut:
    """ 
        Attributes:
            serial (str):
            version (int):
            created_at (str):
            status (ReleaseStatus):
            instrument (str): Always `stage`.
            session_id (str): The session the set was calibrated from.
            camera (Intrinsics): Pinhole intrinsics (px) and Brown–Conrady distortion.
            camera_mode (str): Always `stage`: fitted with the stage's translations as constraints.
            sequences (list[StageSequence]): Each fitted sequence (board placement).
            kind (StageCameraSetKind): What the set identified (the variant's tag).
            job_id (None | str | Unset):
            status_reason (None | str | Unset): Why it has its status (the gate's comparison, or a person's reason).
            status_by (None | str | Unset): Who gave it (`gate`, `token:{id} ({name})`, `anonymous`; `null` for
                sets approved when the gate was introduced) and when.
            status_at (None | str | Unset):
            camera_std (IntrinsicsStd | None | Unset):
     """

    serial: str
    version: int
    created_at: str
    status: ReleaseStatus
    instrument: str
    session_id: str
    camera: Intrinsics
    camera_mode: str
    sequences: list[StageSequence]
    kind: StageCameraSetKind
    job_id: None | str | Unset = UNSET
    status_reason: None | str | Unset = UNSET
    status_by: None | str | Unset = UNSET
    status_at: None | str | Unset = UNSET
    camera_std: IntrinsicsStd | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.intrinsics_std import IntrinsicsStd # noqa: PLC0415
        from ..models.stage_sequence import StageSequence # noqa: PLC0415
        serial = self.serial

        version = self.version

        created_at = self.created_at

        status = self.status.value

        instrument = self.instrument

        session_id = self.session_id

        camera = self.camera.to_dict()

        camera_mode = self.camera_mode

        sequences = []
        for sequences_item_data in self.sequences:
            sequences_item = sequences_item_data.to_dict()
            sequences.append(sequences_item)



        kind = self.kind.value

        job_id: None | str | Unset
        if isinstance(self.job_id, Unset):
            job_id = UNSET
        else:
            job_id = self.job_id

        status_reason: None | str | Unset
        if isinstance(self.status_reason, Unset):
            status_reason = UNSET
        else:
            status_reason = self.status_reason

        status_by: None | str | Unset
        if isinstance(self.status_by, Unset):
            status_by = UNSET
        else:
            status_by = self.status_by

        status_at: None | str | Unset
        if isinstance(self.status_at, Unset):
            status_at = UNSET
        else:
            status_at = self.status_at

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
            "serial": serial,
            "version": version,
            "created_at": created_at,
            "status": status,
            "instrument": instrument,
            "session_id": session_id,
            "camera": camera,
            "camera_mode": camera_mode,
            "sequences": sequences,
            "kind": kind,
        })
        if job_id is not UNSET:
            field_dict["job_id"] = job_id
        if status_reason is not UNSET:
            field_dict["status_reason"] = status_reason
        if status_by is not UNSET:
            field_dict["status_by"] = status_by
        if status_at is not UNSET:
            field_dict["status_at"] = status_at
        if camera_std is not UNSET:
            field_dict["camera_std"] = camera_std

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.intrinsics import Intrinsics # noqa: PLC0415
        from ..models.intrinsics_std import IntrinsicsStd # noqa: PLC0415
        from ..models.stage_sequence import StageSequence # noqa: PLC0415
        d = dict(src_dict)
        serial = d.pop("serial")

        version = d.pop("version")

        created_at = d.pop("created_at")

        status = ReleaseStatus(d.pop("status"))




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




        def _parse_job_id(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        job_id = _parse_job_id(d.pop("job_id", UNSET))


        def _parse_status_reason(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_reason = _parse_status_reason(d.pop("status_reason", UNSET))


        def _parse_status_by(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_by = _parse_status_by(d.pop("status_by", UNSET))


        def _parse_status_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_at = _parse_status_at(d.pop("status_at", UNSET))


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


        stage_camera_set_out = cls(
            serial=serial,
            version=version,
            created_at=created_at,
            status=status,
            instrument=instrument,
            session_id=session_id,
            camera=camera,
            camera_mode=camera_mode,
            sequences=sequences,
            kind=kind,
            job_id=job_id,
            status_reason=status_reason,
            status_by=status_by,
            status_at=status_at,
            camera_std=camera_std,
        )


        stage_camera_set_out.additional_properties = d
        return stage_camera_set_out

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
