//! One section of an existing report rewritten alone, so a study can be regenerated without
//! the others (`tribosim bench speed|rough --markdown PATH`).

/// Rewrites only the section under `heading` of the report `text` (the rest is another
/// run's): replaced where it is, or put before the peers' section (or at the end) when it
/// is missing.
pub(super) fn splice(text: &str, heading: &str, section: &str) -> String {
    let (before, after) = match text.find(&format!("\n{heading}\n")) {
        Some(start) => {
            let body = start + 1 + heading.len();
            let end = text[body..]
                .find("\n## ")
                .map_or(text.len(), |e| body + e + 1);
            (&text[..start + 1], &text[end..])
        }
        None => match text.find("\n## Peers") {
            Some(start) => (&text[..start + 1], &text[start + 1..]),
            None => (text, ""),
        },
    };
    let before = before.trim_end();
    let separator = if before.is_empty() { "" } else { "\n\n" };
    format!("{before}{separator}{}\n\n{after}", section.trim_end())
        .trim_end()
        .to_owned()
        + "\n"
}
