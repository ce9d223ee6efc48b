//! Text from a file, made safe to echo in a message.

/// `text` with every control character (`char::is_control`: C0, DEL, C1) escaped as Rust's
/// `escape_debug` writes it (`\u{1b}`, `\t`, `\n`, `\r`, `\0`), everything else as it is:
/// the one escape of text from a file (a token, a tag name, a file name) before it is
/// echoed in a message, so that `ESC[2J` in a file cannot clear the terminal. Idempotent on
/// its own output, which has no control characters.
///
/// ```
/// use halfedge::io::escape_controls;
/// assert_eq!(escape_controls("\u{1b}[2Jevil"), "\\u{1b}[2Jevil");
/// assert_eq!(escape_controls("tab\there"), "tab\\there");
/// assert_eq!(escape_controls("plain `ok` é"), "plain `ok` é");
/// ```
pub fn escape_controls(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}
