//! The one rule for the text a user names and labels things with (a scene's name, a study's
//! name and its axes' strings, a surface's name, a job's sample, note and tags): a bound on
//! its length, and no character that hides or disguises what it shows.
//!
//! Such text is stored in every record that carries it and shown in lists, file names and
//! terminals, so two kinds of character are refused:
//!
//! - controls (C0 `U+0000`-`U+001F`, `U+007F` and C1 `U+0080`-`U+009F`): a NUL truncates the
//!   text in C tools, a carriage return or an escape sequence rewrites a terminal's line;
//!   a multi-line text (a note, a paragraph) may hold line feeds and tabs;
//! - bidirectional controls (`U+061C`, `U+200E`, `U+200F`, `U+202A`-`U+202E`,
//!   `U+2066`-`U+2069`), invisible characters (`U+200B`-`U+200D`, `U+2060`-`U+2064`,
//!   `U+FEFF`) and the line and paragraph separators (`U+2028`, `U+2029`): a tag
//!   `U+202E gpj.exe` displays as `exe.jpg`, and two names that differ only by a zero-width
//!   space look the same (the "Trojan Source" attacks, CVE-2021-42574).
//!
//! The bounds themselves are each field's; [`NAME_MAX_CHARS`] is the one names share.

use thiserror::Error;

/// The longest name, in characters, of a scene, a study or a surface: a title in a list,
/// not a text. 200 leaves a study member's name (its base's name and its values) room on
/// one line of a wide screen, and keeps a page of 1000 jobs' names under 1 MB.
pub const NAME_MAX_CHARS: usize = 200;

/// Whether a text may span lines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lines {
    /// One line: a name, a tag. No control character at all.
    One,
    /// A paragraph (a note): line feeds and tabs allowed, no other control.
    Many,
}

/// Why a text was refused; the caller names the field.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum TextError {
    /// Longer than its bound.
    #[error("{chars} characters; at most {max}")]
    TooLong {
        /// Its length, in characters (Unicode scalar values).
        chars: usize,
        /// The bound.
        max: usize,
    },
    /// It holds a character that hides or disguises text.
    #[error(
        "holds U+{:04X} ({what}) at character {position}; {}",
        u32::from(*character),
        allowed(*lines)
    )]
    Forbidden {
        /// The character.
        character: char,
        /// Its position, counted in characters from 1.
        position: usize,
        /// What kind of character it is.
        what: &'static str,
        /// Which rule refused it.
        lines: Lines,
    },
}

/// What a text of `lines` may not hold, in words.
fn allowed(lines: Lines) -> &'static str {
    match lines {
        Lines::One => "names and labels hold no control, bidirectional or invisible characters",
        Lines::Many => {
            "a paragraph holds no control (but line feed and tab), bidirectional or invisible \
             characters"
        }
    }
}

/// What the rule refuses `c` as, or `None` if it is allowed in a text of `lines`.
pub fn forbidden(c: char, lines: Lines) -> Option<&'static str> {
    match c {
        '\n' | '\t' if lines == Lines::Many => None,
        '\u{0}'..='\u{1F}' | '\u{7F}'..='\u{9F}' => Some("a control character"),
        '\u{61C}' | '\u{200E}' | '\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}' => {
            Some("a bidirectional control")
        }
        '\u{200B}'..='\u{200D}' | '\u{2060}'..='\u{2064}' | '\u{FEFF}' => {
            Some("an invisible character")
        }
        '\u{2028}' | '\u{2029}' => Some("a line or paragraph separator"),
        _ => None,
    }
}

/// Checks `text` against the rule: at most `max_chars` characters, then no character
/// [`forbidden`] in a text of `lines` (the first one named, with its position). Linear in
/// the text, and the length is checked first, from the byte count when that decides it.
pub fn check(text: &str, max_chars: usize, lines: Lines) -> Result<(), TextError> {
    // A character is at least one byte, so text of at most `max_chars` bytes fits.
    if text.len() > max_chars {
        let chars = text.chars().count();
        if chars > max_chars {
            return Err(TextError::TooLong {
                chars,
                max: max_chars,
            });
        }
    }
    match text
        .chars()
        .enumerate()
        .find_map(|(i, c)| forbidden(c, lines).map(|what| (i, c, what)))
    {
        Some((i, character, what)) => Err(TextError::Forbidden {
            character,
            position: i + 1,
            what,
            lines,
        }),
        None => Ok(()),
    }
}

/// `text` made to pass [`check`] for one line of at most `max_chars` characters: its
/// [`forbidden`] characters dropped, then cut to its first `max_chars`. For text accepted
/// before the rule bound it (a job's scene stored by an earlier version), which must still
/// run rather than fail on its name.
pub fn tidy(text: &str, max_chars: usize) -> String {
    text.chars()
        .filter(|&c| forbidden(c, Lines::One).is_none())
        .take(max_chars)
        .collect()
}

/// The first `max_chars` characters of `text`, with `...` after them if there were more: how
/// much of a refused text an error echoes, so that the refusal of a megabyte is not one.
pub fn cut(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        Some((end, _)) => format!("{}...", &text[..end]),
        None => text.to_owned(),
    }
}

/// What a text of `lines` under `max_chars` must be, in words that follow "must be", for
/// the references (`docs/scene.md`'s table).
pub fn describe(max_chars: usize, lines: Lines) -> String {
    let controls = match lines {
        Lines::One => "control",
        Lines::Many => "control (but line feed and tab)",
    };
    format!(
        "a string of at most {max_chars} characters, with no {controls}, bidirectional or \
         invisible characters"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(text: &str, lines: Lines) -> String {
        check(text, 50, lines)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    }

    #[test]
    fn a_tidied_text_passes_the_rule() {
        let stored = format!("\u{202E}gpj.exe {}", "é".repeat(300));
        let tidied = tidy(&stored, 200);
        assert_eq!(check(&tidied, 200, Lines::One), Ok(()));
        assert!(tidied.starts_with("gpj.exe é"), "{tidied}");
        assert_eq!(tidied.chars().count(), 200);
        assert_eq!(tidy("fine", 200), "fine");
    }

    #[test]
    fn an_echo_is_cut_to_its_bound() {
        assert_eq!(cut("abcdef", 3), "abc...");
        assert_eq!(cut("abc", 3), "abc");
        assert_eq!(cut("ééé", 2), "éé...");
    }

    #[test]
    fn the_length_is_counted_in_characters() {
        assert_eq!(check(&"é".repeat(50), 50, Lines::One), Ok(()));
        assert_eq!(
            check(&"é".repeat(51), 50, Lines::One),
            Err(TextError::TooLong { chars: 51, max: 50 })
        );
        assert_eq!(check("", 0, Lines::One), Ok(()));
    }

    #[test]
    fn each_kind_of_hidden_character_is_named_with_its_position() {
        assert_eq!(
            refused("\u{202E}gpj.exe", Lines::One),
            "holds U+202E (a bidirectional control) at character 1; names and labels hold no \
             control, bidirectional or invisible characters"
        );
        assert!(
            refused("a\0b", Lines::One)
                .starts_with("holds U+0000 (a control character) at character 2")
        );
        assert!(refused("ab\u{200B}", Lines::One).starts_with("holds U+200B (an invisible"));
        assert!(refused("\u{FEFF}x", Lines::One).starts_with("holds U+FEFF"));
        assert!(refused("x\u{85}", Lines::One).starts_with("holds U+0085 (a control"));
        assert!(refused("\u{2067}", Lines::One).starts_with("holds U+2067 (a bidirectional"));
        assert!(refused("a\u{2028}b", Lines::Many).starts_with("holds U+2028"));
        for c in [
            '\u{61C}', '\u{200E}', '\u{200F}', '\u{202A}', '\u{2066}', '\u{2069}',
        ] {
            assert_eq!(forbidden(c, Lines::Many), Some("a bidirectional control"));
        }
    }

    #[test]
    fn a_paragraph_may_hold_line_feeds_and_tabs_and_a_line_may_not() {
        assert_eq!(check("one\n\ttwo", 50, Lines::Many), Ok(()));
        assert!(
            refused("one\ntwo", Lines::One)
                .starts_with("holds U+000A (a control character) at character 4")
        );
        assert!(refused("a\tb", Lines::One).starts_with("holds U+0009"));
        assert!(refused("one\r\ntwo", Lines::Many).starts_with("holds U+000D"));
        // Letters of every script, emoji and combining marks are text.
        assert_eq!(check("Ä Ωμ 試料 🙂 é", 50, Lines::One), Ok(()));
    }
}
