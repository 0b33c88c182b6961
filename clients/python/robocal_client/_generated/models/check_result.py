from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.check_verdict import CheckVerdict
from ..models.release_status import ReleaseStatus
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.check_suspect import CheckSuspect
  from ..models.controller_change_seen import ControllerChangeSeen
  from ..models.job_summary import JobSummary





T = TypeVar("T", bound="CheckResult")



@_attrs_define
class CheckResult:
    """ A succeeded re-check's `result`: the verdict's fields beside the
    summary.

        Attributes:
            summary (JobSummary): The job's `result.summary`: the poses it used and, after a calibration,
                the mean validation error before and after.
            verdict (CheckVerdict): `pass`, `drift`, `base_moved` or `controller_changed`.
            mean_mm (float): Mean length of the position residuals against the set (mm).
            expected_mean_mm (float): What the set predicts for it (mm): the mean over poses of the RMS
                length its covariance and the measurement noise give.
            p_value (float): Upper-tail probability of the chi-square statistic.
            base_p_value (float): The same after re-fitting the base transform alone.
            chi2 (float):
            dof (int):
            significance (float): The test's level: `pass` when `p_value` is at least this.
            test (str): The test, in a sentence.
            checked_against (str): The set judged: `"{serial}/{version}"`.
            poses (int): Poses measured.
            suspects (list[CheckSuspect]):
            serial (None | str | Unset): The robot whose set the job stored.
            version (int | None | Unset): The version the job stored.
            status (None | ReleaseStatus | Unset):
            status_reason (None | str | Unset): Why the gate decided so.
            checked_version (int | Unset): That set's version (the `check.finished` event's `version`), typed
                so nothing parses it back out of `checked_against`. Absent from
                checks stored before it was carried (read as 0).
            joint_noise_deg (float | Unset): The joint noise the test assumed (deg): the set's own estimate, or
                the service's fallback for a set that carries none. Absent from
                checks stored before it was recorded (read as 0).
            controller_change (ControllerChangeSeen | None | Unset):
     """

    summary: JobSummary
    verdict: CheckVerdict
    mean_mm: float
    expected_mean_mm: float
    p_value: float
    base_p_value: float
    chi2: float
    dof: int
    significance: float
    test: str
    checked_against: str
    poses: int
    suspects: list[CheckSuspect]
    serial: None | str | Unset = UNSET
    version: int | None | Unset = UNSET
    status: None | ReleaseStatus | Unset = UNSET
    status_reason: None | str | Unset = UNSET
    checked_version: int | Unset = UNSET
    joint_noise_deg: float | Unset = UNSET
    controller_change: ControllerChangeSeen | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.check_suspect import CheckSuspect # noqa: PLC0415
        from ..models.controller_change_seen import ControllerChangeSeen # noqa: PLC0415
        from ..models.job_summary import JobSummary # noqa: PLC0415
        summary = self.summary.to_dict()

        verdict = self.verdict.value

        mean_mm = self.mean_mm

        expected_mean_mm = self.expected_mean_mm

        p_value = self.p_value

        base_p_value = self.base_p_value

        chi2 = self.chi2

        dof = self.dof

        significance = self.significance

        test = self.test

        checked_against = self.checked_against

        poses = self.poses

        suspects = []
        for suspects_item_data in self.suspects:
            suspects_item = suspects_item_data.to_dict()
            suspects.append(suspects_item)



        serial: None | str | Unset
        if isinstance(self.serial, Unset):
            serial = UNSET
        else:
            serial = self.serial

        version: int | None | Unset
        if isinstance(self.version, Unset):
            version = UNSET
        else:
            version = self.version

        status: None | str | Unset
        if isinstance(self.status, Unset):
            status = UNSET
        elif isinstance(self.status, ReleaseStatus):
            status = self.status.value
        else:
            status = self.status

        status_reason: None | str | Unset
        if isinstance(self.status_reason, Unset):
            status_reason = UNSET
        else:
            status_reason = self.status_reason

        checked_version = self.checked_version

        joint_noise_deg = self.joint_noise_deg

        controller_change: dict[str, Any] | None | Unset
        if isinstance(self.controller_change, Unset):
            controller_change = UNSET
        elif isinstance(self.controller_change, ControllerChangeSeen):
            controller_change = self.controller_change.to_dict()
        else:
            controller_change = self.controller_change


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "summary": summary,
            "verdict": verdict,
            "mean_mm": mean_mm,
            "expected_mean_mm": expected_mean_mm,
            "p_value": p_value,
            "base_p_value": base_p_value,
            "chi2": chi2,
            "dof": dof,
            "significance": significance,
            "test": test,
            "checked_against": checked_against,
            "poses": poses,
            "suspects": suspects,
        })
        if serial is not UNSET:
            field_dict["serial"] = serial
        if version is not UNSET:
            field_dict["version"] = version
        if status is not UNSET:
            field_dict["status"] = status
        if status_reason is not UNSET:
            field_dict["status_reason"] = status_reason
        if checked_version is not UNSET:
            field_dict["checked_version"] = checked_version
        if joint_noise_deg is not UNSET:
            field_dict["joint_noise_deg"] = joint_noise_deg
        if controller_change is not UNSET:
            field_dict["controller_change"] = controller_change

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.check_suspect import CheckSuspect # noqa: PLC0415
        from ..models.controller_change_seen import ControllerChangeSeen # noqa: PLC0415
        from ..models.job_summary import JobSummary # noqa: PLC0415
        d = dict(src_dict)
        summary = JobSummary.from_dict(d.pop("summary"))




        verdict = CheckVerdict(d.pop("verdict"))




        mean_mm = d.pop("mean_mm")

        expected_mean_mm = d.pop("expected_mean_mm")

        p_value = d.pop("p_value")

        base_p_value = d.pop("base_p_value")

        chi2 = d.pop("chi2")

        dof = d.pop("dof")

        significance = d.pop("significance")

        test = d.pop("test")

        checked_against = d.pop("checked_against")

        poses = d.pop("poses")

        suspects = []
        _suspects = d.pop("suspects")
        for suspects_item_data in (_suspects):
            suspects_item = CheckSuspect.from_dict(suspects_item_data)



            suspects.append(suspects_item)


        def _parse_serial(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        serial = _parse_serial(d.pop("serial", UNSET))


        def _parse_version(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        version = _parse_version(d.pop("version", UNSET))


        def _parse_status(data: object) -> None | ReleaseStatus | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                status_type_1 = ReleaseStatus(data)



                return status_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | ReleaseStatus | Unset, data)

        status = _parse_status(d.pop("status", UNSET))


        def _parse_status_reason(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        status_reason = _parse_status_reason(d.pop("status_reason", UNSET))


        checked_version = d.pop("checked_version", UNSET)

        joint_noise_deg = d.pop("joint_noise_deg", UNSET)

        def _parse_controller_change(data: object) -> ControllerChangeSeen | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                controller_change_type_1 = ControllerChangeSeen.from_dict(data)



                return controller_change_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ControllerChangeSeen | None | Unset, data)

        controller_change = _parse_controller_change(d.pop("controller_change", UNSET))


        check_result = cls(
            summary=summary,
            verdict=verdict,
            mean_mm=mean_mm,
            expected_mean_mm=expected_mean_mm,
            p_value=p_value,
            base_p_value=base_p_value,
            chi2=chi2,
            dof=dof,
            significance=significance,
            test=test,
            checked_against=checked_against,
            poses=poses,
            suspects=suspects,
            serial=serial,
            version=version,
            status=status,
            status_reason=status_reason,
            checked_version=checked_version,
            joint_noise_deg=joint_noise_deg,
            controller_change=controller_change,
        )


        check_result.additional_properties = d
        return check_result

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
