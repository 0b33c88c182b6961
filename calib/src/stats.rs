//! Accuracy statistics for reports (method.md §7).
