pub mod render;
pub mod scenes;
pub mod seeded;
