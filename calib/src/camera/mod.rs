//! Camera models and calibration (method.md §2–4).
