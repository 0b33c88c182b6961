//! Why a plan cannot be made: the constraint that bound, with how many
//! candidates survived each filter, never a silently shorter plan.

/// Survivors after one filter of candidate generation, in filter order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FilterCount {
    /// The filter, as the request names the constraint.
    pub constraint: &'static str,
    pub survivors: usize,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    #[error("invalid request field {field}: {message}")]
    Invalid {
        field: &'static str,
        message: String,
    },
    #[error("only {feasible} feasible poses for {wanted} asked; \"{constraint}\" bound ({counts})", counts = format_counts(.filters))]
    Infeasible {
        /// The filter that removed the most candidates (or the last with
        /// no survivors).
        constraint: &'static str,
        feasible: usize,
        wanted: usize,
        filters: Vec<FilterCount>,
    },
    #[error("the feasible poses do not determine {parameters:?} (vary the ranges)")]
    Unidentifiable { parameters: Vec<String> },
    #[error("the robot model cannot be evaluated: {0}")]
    Model(String),
}

fn format_counts(filters: &[FilterCount]) -> String {
    filters
        .iter()
        .map(|f| format!("{}: {}", f.constraint, f.survivors))
        .collect::<Vec<_>>()
        .join(", ")
}
