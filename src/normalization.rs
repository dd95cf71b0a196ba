//! normalization (work in progress).
