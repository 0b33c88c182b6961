""" Contains all the data models used in inputs/outputs """

from .accuracy_summary import AccuracySummary
from .axis_stats_report import AxisStatsReport
from .board_scale_report import BoardScaleReport
from .box_doc import BoxDoc
from .calibration_options import CalibrationOptions
from .calibration_result import CalibrationResult
from .calibration_scope import CalibrationScope
from .camera_doc import CameraDoc
from .camera_report import CameraReport
from .campaign_plan_body import CampaignPlanBody
from .campaign_plan_out import CampaignPlanOut
from .check_body import CheckBody
from .check_doc import CheckDoc
from .check_options import CheckOptions
from .check_result import CheckResult
from .check_suspect import CheckSuspect
from .check_verdict import CheckVerdict
from .compensate_line import CompensateLine
from .compensate_request import CompensateRequest
from .compensate_response import CompensateResponse
from .configuration import Configuration
from .configuration_elbow import ConfigurationElbow
from .configuration_shoulder import ConfigurationShoulder
from .configuration_wrist import ConfigurationWrist
from .controller_change import ControllerChange
from .controller_change_seen import ControllerChangeSeen
from .controller_identity import ControllerIdentity
from .controller_mismatch import ControllerMismatch
from .convention import Convention
from .covariance_doc import CovarianceDoc
from .dataset_out import DatasetOut
from .decision import Decision
from .decision_body import DecisionBody
from .delivery_counts import DeliveryCounts
from .detection_failure import DetectionFailure
from .detection_report import DetectionReport
from .error_stats import ErrorStats
from .existing_predicted_doc import ExistingPredictedDoc
from .field_error import FieldError
from .filter_count_doc import FilterCountDoc
from .filter_line import FilterLine
from .filter_request import FilterRequest
from .filter_response import FilterResponse
from .flange_pose_doc import FlangePoseDoc
from .forward_pose import ForwardPose
from .forward_request import ForwardRequest
from .forward_response import ForwardResponse
from .frame_pose import FramePose
from .frame_report import FrameReport
from .gate_report import GateReport
from .hand_eye_report import HandEyeReport
from .hand_eye_set import HandEyeSet
from .hand_eye_set_kind import HandEyeSetKind
from .hand_eye_set_out import HandEyeSetOut
from .health import Health
from .history import History
from .history_check import HistoryCheck
from .history_version import HistoryVersion
from .holdout import Holdout
from .identifiability_report import IdentifiabilityReport
from .image_meta import ImageMeta
from .image_point_doc import ImagePointDoc
from .instrument import Instrument
from .intrinsics import Intrinsics
from .intrinsics_std import IntrinsicsStd
from .job_accepted import JobAccepted
from .job_event_frame import JobEventFrame
from .job_kind import JobKind
from .job_list import JobList
from .job_out import JobOut
from .job_state import JobState
from .job_summary import JobSummary
from .joint_doc import JointDoc
from .joint_type import JointType
from .keep_out_doc import KeepOutDoc
from .kept_term import KeptTerm
from .kept_term_term import KeptTermTerm
from .kinematic_set import KinematicSet
from .kinematic_set_kind import KinematicSetKind
from .kinematic_set_out import KinematicSetOut
from .kinematics_doc import KinematicsDoc
from .local_model import LocalModel
from .map_point import MapPoint
from .measurement import Measurement
from .measurement_accuracy_report import MeasurementAccuracyReport
from .model_selection_report import ModelSelectionReport
from .parameter_change import ParameterChange
from .parameter_report import ParameterReport
from .parameter_set_identity import ParameterSetIdentity
from .parameter_set_list import ParameterSetList
from .plan_purpose_doc import PlanPurposeDoc
from .planned_pose_doc import PlannedPoseDoc
from .pose_detection_out import PoseDetectionOut
from .pose_doc import PoseDoc
from .pose_image_point import PoseImagePoint
from .pose_image_upload import PoseImageUpload
from .pose_json_body import PoseJsonBody
from .pose_list import PoseList
from .pose_out import PoseOut
from .pose_report import PoseReport
from .pose_set import PoseSet
from .predicted_doc import PredictedDoc
from .predicted_doc_parameter_std_devs import PredictedDocParameterStdDevs
from .predicted_std import PredictedStd
from .preset import Preset
from .prior_doc import PriorDoc
from .problem import Problem
from .readiness import Readiness
from .region_report import RegionReport
from .release_status import ReleaseStatus
from .release_view import ReleaseView
from .report import Report
from .report_link import ReportLink
from .report_link_body import ReportLinkBody
from .residual_sample import ResidualSample
from .robot_body import RobotBody
from .robot_list import RobotList
from .robot_out import RobotOut
from .rung_report import RungReport
from .sequence_accuracy_report import SequenceAccuracyReport
from .session_board import SessionBoard
from .session_body import SessionBody
from .session_list import SessionList
from .session_out import SessionOut
from .session_spec_out import SessionSpecOut
from .solver_start import SolverStart
from .stage_camera_set import StageCameraSet
from .stage_camera_set_kind import StageCameraSetKind
from .stage_camera_set_out import StageCameraSetOut
from .stage_sequence import StageSequence
from .target_doc import TargetDoc
from .target_error import TargetError
from .target_kind import TargetKind
from .term_joint_range import TermJointRange
from .term_line import TermLine
from .terms_covariance_doc import TermsCovarianceDoc
from .terms_doc import TermsDoc
from .terms_report import TermsReport
from .token_body import TokenBody
from .token_created import TokenCreated
from .token_list import TokenList
from .token_out import TokenOut
from .travel_error_report import TravelErrorReport
from .uncertainty_cell import UncertaintyCell
from .uncertainty_map_report import UncertaintyMapReport
from .uncertainty_map_request import UncertaintyMapRequest
from .uncertainty_map_response import UncertaintyMapResponse
from .validation_named import ValidationNamed
from .view_report import ViewReport
from .webhook_body import WebhookBody
from .webhook_created import WebhookCreated
from .webhook_list import WebhookList
from .webhook_out import WebhookOut

__all__ = (
    "AccuracySummary",
    "AxisStatsReport",
    "BoardScaleReport",
    "BoxDoc",
    "CalibrationOptions",
    "CalibrationResult",
    "CalibrationScope",
    "CameraDoc",
    "CameraReport",
    "CampaignPlanBody",
    "CampaignPlanOut",
    "CheckBody",
    "CheckDoc",
    "CheckOptions",
    "CheckResult",
    "CheckSuspect",
    "CheckVerdict",
    "CompensateLine",
    "CompensateRequest",
    "CompensateResponse",
    "Configuration",
    "ConfigurationElbow",
    "ConfigurationShoulder",
    "ConfigurationWrist",
    "ControllerChange",
    "ControllerChangeSeen",
    "ControllerIdentity",
    "ControllerMismatch",
    "Convention",
    "CovarianceDoc",
    "DatasetOut",
    "Decision",
    "DecisionBody",
    "DeliveryCounts",
    "DetectionFailure",
    "DetectionReport",
    "ErrorStats",
    "ExistingPredictedDoc",
    "FieldError",
    "FilterCountDoc",
    "FilterLine",
    "FilterRequest",
    "FilterResponse",
    "FlangePoseDoc",
    "ForwardPose",
    "ForwardRequest",
    "ForwardResponse",
    "FramePose",
    "FrameReport",
    "GateReport",
    "HandEyeReport",
    "HandEyeSet",
    "HandEyeSetKind",
    "HandEyeSetOut",
    "Health",
    "History",
    "HistoryCheck",
    "HistoryVersion",
    "Holdout",
    "IdentifiabilityReport",
    "ImageMeta",
    "ImagePointDoc",
    "Instrument",
    "Intrinsics",
    "IntrinsicsStd",
    "JobAccepted",
    "JobEventFrame",
    "JobKind",
    "JobList",
    "JobOut",
    "JobState",
    "JobSummary",
    "JointDoc",
    "JointType",
    "KeepOutDoc",
    "KeptTerm",
    "KeptTermTerm",
    "KinematicsDoc",
    "KinematicSet",
    "KinematicSetKind",
    "KinematicSetOut",
    "LocalModel",
    "MapPoint",
    "Measurement",
    "MeasurementAccuracyReport",
    "ModelSelectionReport",
    "ParameterChange",
    "ParameterReport",
    "ParameterSetIdentity",
    "ParameterSetList",
    "PlannedPoseDoc",
    "PlanPurposeDoc",
    "PoseDetectionOut",
    "PoseDoc",
    "PoseImagePoint",
    "PoseImageUpload",
    "PoseJsonBody",
    "PoseList",
    "PoseOut",
    "PoseReport",
    "PoseSet",
    "PredictedDoc",
    "PredictedDocParameterStdDevs",
    "PredictedStd",
    "Preset",
    "PriorDoc",
    "Problem",
    "Readiness",
    "RegionReport",
    "ReleaseStatus",
    "ReleaseView",
    "Report",
    "ReportLink",
    "ReportLinkBody",
    "ResidualSample",
    "RobotBody",
    "RobotList",
    "RobotOut",
    "RungReport",
    "SequenceAccuracyReport",
    "SessionBoard",
    "SessionBody",
    "SessionList",
    "SessionOut",
    "SessionSpecOut",
    "SolverStart",
    "StageCameraSet",
    "StageCameraSetKind",
    "StageCameraSetOut",
    "StageSequence",
    "TargetDoc",
    "TargetError",
    "TargetKind",
    "TermJointRange",
    "TermLine",
    "TermsCovarianceDoc",
    "TermsDoc",
    "TermsReport",
    "TokenBody",
    "TokenCreated",
    "TokenList",
    "TokenOut",
    "TravelErrorReport",
    "UncertaintyCell",
    "UncertaintyMapReport",
    "UncertaintyMapRequest",
    "UncertaintyMapResponse",
    "ValidationNamed",
    "ViewReport",
    "WebhookBody",
    "WebhookCreated",
    "WebhookList",
    "WebhookOut",
)
