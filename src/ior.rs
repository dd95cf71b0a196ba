//! ior (work in progress).
