pub mod render;
pub mod scenes;
pub mod seeded;
pub mod worst_case;
