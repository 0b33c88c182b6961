//! Target-image renderer: a known camera and board pose to an 8-bit image plus truth.
