//! Map loading.
