//! (temporary stub until the catalogue documentation lands)
pub fn commands_markdown() -> String {
    String::new()
}
