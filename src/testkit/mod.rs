//! Test tooling: what tests and examples use to judge the service against
//! the simulator's truth. Behind the `testkit` feature, so production code
//! cannot use it (the crate's own tests, examples and benches enable it
//! through the self dev-dependency in `Cargo.toml`).

pub mod accuracy;
