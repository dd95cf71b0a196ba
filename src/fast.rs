//! Fast approximations (work in progress).
