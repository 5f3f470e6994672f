pub mod scenes;
pub mod render;
