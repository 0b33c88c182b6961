//! The one Levenberg–Marquardt solver (method.md §6).
