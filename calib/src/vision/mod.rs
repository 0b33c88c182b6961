//! Dot-grid target detection (method.md §1): threshold, blobs, ellipses, grid.
