//! Triangle rasterization (in progress).
