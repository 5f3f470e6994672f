//! Framebuffers (in progress).
