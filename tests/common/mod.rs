pub mod render;
pub mod scenes;
