from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.release_status import ReleaseStatus
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.accuracy_summary import AccuracySummary
  from ..models.camera_report import CameraReport
  from ..models.detection_report import DetectionReport
  from ..models.gate_report import GateReport
  from ..models.hand_eye_report import HandEyeReport
  from ..models.identifiability_report import IdentifiabilityReport
  from ..models.measurement_accuracy_report import MeasurementAccuracyReport
  from ..models.model_selection_report import ModelSelectionReport
  from ..models.parameter_report import ParameterReport
  from ..models.pose_report import PoseReport
  from ..models.region_report import RegionReport
  from ..models.residual_sample import ResidualSample
  from ..models.terms_report import TermsReport
  from ..models.uncertainty_map_report import UncertaintyMapReport





T = TypeVar("T", bound="Report")



@_attrs_define
class Report:
    """ 
        Attributes:
            serial (str):
            version (int):
            job_id (str):
            session_id (str):
            created_at (str):
            instrument (str): "camera" or "tracker".
            measurement (str): "pose" or "position".
            before (AccuracySummary): 3-D position-error statistics (the `ErrorStats` fields of the error
                norm) plus the same per axis (`|e_x|`, `|e_y|`, `|e_z|`), world frame.
            after (AccuracySummary): 3-D position-error statistics (the `ErrorStats` fields of the error
                norm) plus the same per axis (`|e_x|`, `|e_y|`, `|e_z|`), world frame.
            per_pose (list[PoseReport]):
            parameters (list[ParameterReport]):
            identifiability (IdentifiabilityReport):
            residual_field (list[ResidualSample]):
            notes (list[str]): Plain-language remarks for the cell engineer (warnings, what was
                held fixed and why, what remains unmodelled).
            status (None | ReleaseStatus | Unset):
            status_reason (None | str | Unset): Why it has its status (the gate's comparison or a person's reason).
            status_by (None | str | Unset): Who gave it: `gate`, `token:{id} ({name})` or `anonymous`.
            status_at (None | str | Unset): When (RFC 3339 UTC).
            camera (CameraReport | None | Unset):
            detection (DetectionReport | None | Unset):
            hand_eye (HandEyeReport | None | Unset):
            uncertainty_map (None | UncertaintyMapReport | Unset):
            gate (GateReport | None | Unset):
            measurement_accuracy (MeasurementAccuracyReport | None | Unset):
            terms (None | TermsReport | Unset):
            model_selection (ModelSelectionReport | None | Unset):
            regions (list[RegionReport] | Unset): A multi-session set: each session's (region's)
                validation accuracy, before and after, on its own validation poses.
     """

    serial: str
    version: int
    job_id: str
    session_id: str
    created_at: str
    instrument: str
    measurement: str
    before: AccuracySummary
    after: AccuracySummary
    per_pose: list[PoseReport]
    parameters: list[ParameterReport]
    identifiability: IdentifiabilityReport
    residual_field: list[ResidualSample]
    notes: list[str]
    status: None | ReleaseStatus | Unset = UNSET
    status_reason: None | str | Unset = UNSET
    status_by: None | str | Unset = UNSET
    status_at: None | str | Unset = UNSET
    camera: CameraReport | None | Unset = UNSET
    detection: DetectionReport | None | Unset = UNSET
    hand_eye: HandEyeReport | None | Unset = UNSET
    uncertainty_map: None | UncertaintyMapReport | Unset = UNSET
    gate: GateReport | None | Unset = UNSET
    measurement_accuracy: MeasurementAccuracyReport | None | Unset = UNSET
    terms: None | TermsReport | Unset = UNSET
    model_selection: ModelSelectionReport | None | Unset = UNSET
    regions: list[RegionReport] | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.accuracy_summary import AccuracySummary # noqa: PLC0415
        from ..models.camera_report import CameraReport # noqa: PLC0415
        from ..models.detection_report import DetectionReport # noqa: PLC0415
        from ..models.gate_report import GateReport # noqa: PLC0415
        from ..models.hand_eye_report import HandEyeReport # noqa: PLC0415
        from ..models.identifiability_report import IdentifiabilityReport # noqa: PLC0415
        from ..models.measurement_accuracy_report import MeasurementAccuracyReport # noqa: PLC0415
        from ..models.model_selection_report import ModelSelectionReport # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        from ..models.pose_report import PoseReport # noqa: PLC0415
        from ..models.region_report import RegionReport # noqa: PLC0415
        from ..models.residual_sample import ResidualSample # noqa: PLC0415
        from ..models.terms_report import TermsReport # noqa: PLC0415
        from ..models.uncertainty_map_report import UncertaintyMapReport # noqa: PLC0415
        serial = self.serial

        version = self.version

        job_id = self.job_id

        session_id = self.session_id

        created_at = self.created_at

        instrument = self.instrument

        measurement = self.measurement

        before = self.before.to_dict()

        after = self.after.to_dict()

        per_pose = []
        for per_pose_item_data in self.per_pose:
            per_pose_item = per_pose_item_data.to_dict()
            per_pose.append(per_pose_item)



        parameters = []
        for parameters_item_data in self.parameters:
            parameters_item = parameters_item_data.to_dict()
            parameters.append(parameters_item)



        identifiability = self.identifiability.to_dict()

        residual_field = []
        for residual_field_item_data in self.residual_field:
            residual_field_item = residual_field_item_data.to_dict()
            residual_field.append(residual_field_item)



        notes = self.notes



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

        camera: dict[str, Any] | None | Unset
        if isinstance(self.camera, Unset):
            camera = UNSET
        elif isinstance(self.camera, CameraReport):
            camera = self.camera.to_dict()
        else:
            camera = self.camera

        detection: dict[str, Any] | None | Unset
        if isinstance(self.detection, Unset):
            detection = UNSET
        elif isinstance(self.detection, DetectionReport):
            detection = self.detection.to_dict()
        else:
            detection = self.detection

        hand_eye: dict[str, Any] | None | Unset
        if isinstance(self.hand_eye, Unset):
            hand_eye = UNSET
        elif isinstance(self.hand_eye, HandEyeReport):
            hand_eye = self.hand_eye.to_dict()
        else:
            hand_eye = self.hand_eye

        uncertainty_map: dict[str, Any] | None | Unset
        if isinstance(self.uncertainty_map, Unset):
            uncertainty_map = UNSET
        elif isinstance(self.uncertainty_map, UncertaintyMapReport):
            uncertainty_map = self.uncertainty_map.to_dict()
        else:
            uncertainty_map = self.uncertainty_map

        gate: dict[str, Any] | None | Unset
        if isinstance(self.gate, Unset):
            gate = UNSET
        elif isinstance(self.gate, GateReport):
            gate = self.gate.to_dict()
        else:
            gate = self.gate

        measurement_accuracy: dict[str, Any] | None | Unset
        if isinstance(self.measurement_accuracy, Unset):
            measurement_accuracy = UNSET
        elif isinstance(self.measurement_accuracy, MeasurementAccuracyReport):
            measurement_accuracy = self.measurement_accuracy.to_dict()
        else:
            measurement_accuracy = self.measurement_accuracy

        terms: dict[str, Any] | None | Unset
        if isinstance(self.terms, Unset):
            terms = UNSET
        elif isinstance(self.terms, TermsReport):
            terms = self.terms.to_dict()
        else:
            terms = self.terms

        model_selection: dict[str, Any] | None | Unset
        if isinstance(self.model_selection, Unset):
            model_selection = UNSET
        elif isinstance(self.model_selection, ModelSelectionReport):
            model_selection = self.model_selection.to_dict()
        else:
            model_selection = self.model_selection

        regions: list[dict[str, Any]] | Unset = UNSET
        if not isinstance(self.regions, Unset):
            regions = []
            for regions_item_data in self.regions:
                regions_item = regions_item_data.to_dict()
                regions.append(regions_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "serial": serial,
            "version": version,
            "job_id": job_id,
            "session_id": session_id,
            "created_at": created_at,
            "instrument": instrument,
            "measurement": measurement,
            "before": before,
            "after": after,
            "per_pose": per_pose,
            "parameters": parameters,
            "identifiability": identifiability,
            "residual_field": residual_field,
            "notes": notes,
        })
        if status is not UNSET:
            field_dict["status"] = status
        if status_reason is not UNSET:
            field_dict["status_reason"] = status_reason
        if status_by is not UNSET:
            field_dict["status_by"] = status_by
        if status_at is not UNSET:
            field_dict["status_at"] = status_at
        if camera is not UNSET:
            field_dict["camera"] = camera
        if detection is not UNSET:
            field_dict["detection"] = detection
        if hand_eye is not UNSET:
            field_dict["hand_eye"] = hand_eye
        if uncertainty_map is not UNSET:
            field_dict["uncertainty_map"] = uncertainty_map
        if gate is not UNSET:
            field_dict["gate"] = gate
        if measurement_accuracy is not UNSET:
            field_dict["measurement_accuracy"] = measurement_accuracy
        if terms is not UNSET:
            field_dict["terms"] = terms
        if model_selection is not UNSET:
            field_dict["model_selection"] = model_selection
        if regions is not UNSET:
            field_dict["regions"] = regions

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.accuracy_summary import AccuracySummary # noqa: PLC0415
        from ..models.camera_report import CameraReport # noqa: PLC0415
        from ..models.detection_report import DetectionReport # noqa: PLC0415
        from ..models.gate_report import GateReport # noqa: PLC0415
        from ..models.hand_eye_report import HandEyeReport # noqa: PLC0415
        from ..models.identifiability_report import IdentifiabilityReport # noqa: PLC0415
        from ..models.measurement_accuracy_report import MeasurementAccuracyReport # noqa: PLC0415
        from ..models.model_selection_report import ModelSelectionReport # noqa: PLC0415
        from ..models.parameter_report import ParameterReport # noqa: PLC0415
        from ..models.pose_report import PoseReport # noqa: PLC0415
        from ..models.region_report import RegionReport # noqa: PLC0415
        from ..models.residual_sample import ResidualSample # noqa: PLC0415
        from ..models.terms_report import TermsReport # noqa: PLC0415
        from ..models.uncertainty_map_report import UncertaintyMapReport # noqa: PLC0415
        d = dict(src_dict)
        serial = d.pop("serial")

        version = d.pop("version")

        job_id = d.pop("job_id")

        session_id = d.pop("session_id")

        created_at = d.pop("created_at")

        instrument = d.pop("instrument")

        measurement = d.pop("measurement")

        before = AccuracySummary.from_dict(d.pop("before"))




        after = AccuracySummary.from_dict(d.pop("after"))




        per_pose = []
        _per_pose = d.pop("per_pose")
        for per_pose_item_data in (_per_pose):
            per_pose_item = PoseReport.from_dict(per_pose_item_data)



            per_pose.append(per_pose_item)


        parameters = []
        _parameters = d.pop("parameters")
        for parameters_item_data in (_parameters):
            parameters_item = ParameterReport.from_dict(parameters_item_data)



            parameters.append(parameters_item)


        identifiability = IdentifiabilityReport.from_dict(d.pop("identifiability"))




        residual_field = []
        _residual_field = d.pop("residual_field")
        for residual_field_item_data in (_residual_field):
            residual_field_item = ResidualSample.from_dict(residual_field_item_data)



            residual_field.append(residual_field_item)


        notes = cast(list[str], d.pop("notes"))


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


        def _parse_camera(data: object) -> CameraReport | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                camera_type_1 = CameraReport.from_dict(data)



                return camera_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(CameraReport | None | Unset, data)

        camera = _parse_camera(d.pop("camera", UNSET))


        def _parse_detection(data: object) -> DetectionReport | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                detection_type_1 = DetectionReport.from_dict(data)



                return detection_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(DetectionReport | None | Unset, data)

        detection = _parse_detection(d.pop("detection", UNSET))


        def _parse_hand_eye(data: object) -> HandEyeReport | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                hand_eye_type_1 = HandEyeReport.from_dict(data)



                return hand_eye_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(HandEyeReport | None | Unset, data)

        hand_eye = _parse_hand_eye(d.pop("hand_eye", UNSET))


        def _parse_uncertainty_map(data: object) -> None | UncertaintyMapReport | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                uncertainty_map_type_1 = UncertaintyMapReport.from_dict(data)



                return uncertainty_map_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | UncertaintyMapReport | Unset, data)

        uncertainty_map = _parse_uncertainty_map(d.pop("uncertainty_map", UNSET))


        def _parse_gate(data: object) -> GateReport | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                gate_type_1 = GateReport.from_dict(data)



                return gate_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(GateReport | None | Unset, data)

        gate = _parse_gate(d.pop("gate", UNSET))


        def _parse_measurement_accuracy(data: object) -> MeasurementAccuracyReport | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                measurement_accuracy_type_1 = MeasurementAccuracyReport.from_dict(data)



                return measurement_accuracy_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(MeasurementAccuracyReport | None | Unset, data)

        measurement_accuracy = _parse_measurement_accuracy(d.pop("measurement_accuracy", UNSET))


        def _parse_terms(data: object) -> None | TermsReport | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                terms_type_1 = TermsReport.from_dict(data)



                return terms_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | TermsReport | Unset, data)

        terms = _parse_terms(d.pop("terms", UNSET))


        def _parse_model_selection(data: object) -> ModelSelectionReport | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                model_selection_type_1 = ModelSelectionReport.from_dict(data)



                return model_selection_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(ModelSelectionReport | None | Unset, data)

        model_selection = _parse_model_selection(d.pop("model_selection", UNSET))


        _regions = d.pop("regions", UNSET)
        regions: list[RegionReport] | Unset = UNSET
        if _regions is not UNSET:
            regions = []
            for regions_item_data in _regions:
                regions_item = RegionReport.from_dict(regions_item_data)



                regions.append(regions_item)


        report = cls(
            serial=serial,
            version=version,
            job_id=job_id,
            session_id=session_id,
            created_at=created_at,
            instrument=instrument,
            measurement=measurement,
            before=before,
            after=after,
            per_pose=per_pose,
            parameters=parameters,
            identifiability=identifiability,
            residual_field=residual_field,
            notes=notes,
            status=status,
            status_reason=status_reason,
            status_by=status_by,
            status_at=status_at,
            camera=camera,
            detection=detection,
            hand_eye=hand_eye,
            uncertainty_map=uncertainty_map,
            gate=gate,
            measurement_accuracy=measurement_accuracy,
            terms=terms,
            model_selection=model_selection,
            regions=regions,
        )


        report.additional_properties = d
        return report

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
