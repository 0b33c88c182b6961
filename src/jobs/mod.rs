//! The durable job queue (`queue`) and the bounded worker pool (`pool`).

pub mod load;
pub mod pool;
pub mod queue;
