//! BRDF models (work in progress).
