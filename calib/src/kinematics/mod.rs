//! Robot kinematic model, identification and compensation (method.md §5–8).
