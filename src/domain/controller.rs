//! The controller a robot runs on (issue 34): vendor, serial, software and
//! the controller's own kinematics hash. A session records the identity it
//! was measured on, a parameter set inherits it, and the calls that apply
//! a set to a robot (`compensate`, `filter`, `export`, the re-check) refuse
//! with 409 when the caller expects another controller: a set made for one
//! controller applied to another is a silent error of millimetres.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::{Checker, FieldError};

/// Longest value of any identity field.
pub const MAX_CONTROLLER_FIELD_CHARS: usize = 200;

/// Who the controller is. Every field is optional; an identity names at
/// least one.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ControllerIdentity {
    /// The controller's maker (`Universal Robots`, `KUKA`, `ABB`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(max_length = 200)]
    pub vendor: Option<String>,
    /// The controller's (not the arm's) serial number.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(max_length = 200)]
    pub serial: Option<String>,
    /// Its software (firmware, PolyScope, KSS, RobotWare) version.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(max_length = 200)]
    pub software: Option<String>,
    /// The kinematics hash the controller reports (a UR arm's `calib_…`),
    /// which changes when the arm is re-mastered or its calibration reloaded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(max_length = 200)]
    pub kinematics_hash: Option<String>,
}

impl ControllerIdentity {
    /// The fields in contract order, with their names.
    fn fields(&self) -> [(&'static str, Option<&str>); 4] {
        [
            ("vendor", self.vendor.as_deref()),
            ("serial", self.serial.as_deref()),
            ("software", self.software.as_deref()),
            ("kinematics_hash", self.kinematics_hash.as_deref()),
        ]
    }

    /// Checks the identity sent under `field` (422 naming the field).
    pub fn check(&self, field: &str, c: &mut Checker) {
        let given = self.fields().into_iter().filter(|(_, v)| v.is_some());
        let mut any = false;
        for (name, value) in given {
            any = true;
            let value = value.unwrap_or_default();
            if value.trim().is_empty() || value.chars().count() > MAX_CONTROLLER_FIELD_CHARS {
                c.fail(
                    format!("{field}.{name}"),
                    format!(
                        "must be 1 to {MAX_CONTROLLER_FIELD_CHARS} characters, not only spaces"
                    ),
                );
            }
        }
        if !any {
            c.fail(
                field,
                "name at least one of vendor, serial, software, kinematics_hash",
            );
        }
    }

    /// Whether `recorded` is the controller this identity expects: every
    /// field this one names is equal in `recorded` (a field it leaves out
    /// is not compared).
    pub fn matches(&self, recorded: Option<&ControllerIdentity>) -> bool {
        let recorded = recorded.cloned().unwrap_or_default();
        let theirs = recorded.fields();
        let mine = self.fields();
        (0..mine.len()).all(|i| mine[i].1.is_none() || mine[i].1 == theirs[i].1)
    }

    /// One line for the header comment of an export and the fleet page:
    /// `vendor KUKA, serial 123, software KSS 8.6, kinematics_hash …`.
    pub fn describe(&self) -> String {
        let parts: Vec<String> = self
            .fields()
            .iter()
            .filter_map(|(name, v)| v.map(|v| format!("{name} {v}")))
            .collect();
        parts.join(", ")
    }
}

/// One change of a robot's controller identity (its history).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, ToSchema)]
pub struct ControllerChange {
    /// The identity before (`null`: none recorded).
    pub from: Option<ControllerIdentity>,
    /// The identity after (`null`: removed).
    pub to: Option<ControllerIdentity>,
    pub changed_at: String,
}

/// A call that expected one controller on a set (or robot) recorded on
/// another: the 409's `controller` member.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, ToSchema)]
pub struct ControllerMismatch {
    /// What the request expected (`expect_controller`, `controller_serial`).
    pub expected: ControllerIdentity,
    /// What the set (or, for a re-check, the robot) records; `null` when
    /// nothing was recorded.
    pub recorded: Option<ControllerIdentity>,
}

impl ControllerMismatch {
    /// The refusal in words, both identities named.
    pub fn message(&self, what: &str) -> String {
        let recorded = self
            .recorded
            .as_ref()
            .map(|r| r.describe())
            .unwrap_or_else(|| "no controller recorded".into());
        format!(
            "{what} was made on controller [{recorded}], the request expects controller [{}]",
            self.expected.describe()
        )
    }
}

/// `Err` when `expected` is given and `recorded` is not that controller.
pub fn check_expected(
    expected: Option<&ControllerIdentity>,
    recorded: Option<&ControllerIdentity>,
) -> Result<(), Box<ControllerMismatch>> {
    match expected {
        Some(e) if !e.matches(recorded) => Err(Box::new(ControllerMismatch {
            expected: e.clone(),
            recorded: recorded.cloned(),
        })),
        _ => Ok(()),
    }
}

/// What a caller expects: a whole identity (`expect_controller`) or only
/// the serial (`?controller_serial=`).
pub fn expectation(
    body: Option<&ControllerIdentity>,
    controller_serial: Option<&str>,
) -> Result<Option<ControllerIdentity>, Vec<FieldError>> {
    let mut c = Checker::default();
    if let Some(b) = body {
        b.check("expect_controller", &mut c);
    }
    if let Some(s) = controller_serial {
        if s.trim().is_empty() || s.chars().count() > MAX_CONTROLLER_FIELD_CHARS {
            c.fail(
                "controller_serial",
                format!("must be 1 to {MAX_CONTROLLER_FIELD_CHARS} characters"),
            );
        }
    }
    c.finish()?;
    Ok(match (body, controller_serial) {
        (Some(b), Some(s)) => Some(ControllerIdentity {
            serial: Some(s.to_string()),
            ..b.clone()
        }),
        (Some(b), None) => Some(b.clone()),
        (None, Some(s)) => Some(ControllerIdentity {
            serial: Some(s.to_string()),
            ..ControllerIdentity::default()
        }),
        (None, None) => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn id(serial: &str, hash: Option<&str>) -> ControllerIdentity {
        ControllerIdentity {
            vendor: Some("Universal Robots".into()),
            serial: Some(serial.into()),
            software: None,
            kinematics_hash: hash.map(str::to_string),
        }
    }

    #[test]
    fn an_expectation_compares_only_the_fields_it_names() {
        let recorded = id("2019301234", Some("calib_1"));
        let by_serial = expectation(None, Some("2019301234")).unwrap().unwrap();
        assert!(by_serial.matches(Some(&recorded)));
        assert!(!by_serial.matches(Some(&id("2019309999", Some("calib_1")))));
        assert!(!by_serial.matches(None));
        let remastered = id("2019301234", Some("calib_2"));
        assert!(!recorded.matches(Some(&remastered)));
        assert!(recorded.matches(Some(&recorded)));
    }

    #[test]
    fn an_empty_identity_or_field_is_refused_by_name() {
        let errors = expectation(Some(&ControllerIdentity::default()), None).unwrap_err();
        assert_eq!(errors[0].field, "expect_controller");
        let blank = ControllerIdentity {
            serial: Some(" ".into()),
            ..Default::default()
        };
        let errors = expectation(Some(&blank), None).unwrap_err();
        assert_eq!(errors[0].field, "expect_controller.serial");
    }
}
