//! Diagnostics: source positions and the rendering of user-facing errors.
//!
//! Every error a user can trigger from a `.comm` file goes through
//! [`Diagnostic`], so that all of them name the file, line and column, the
//! command and the keyword path, and show the offending source line with a
//! caret. Spans are byte offsets; lines and columns are computed only when
//! rendering, as starlark and rustc do.

use std::fmt::Write as _;

/// A byte range in one source file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    pub start: usize,
    pub end: usize,
}

impl Span {
    pub fn new(start: usize, end: usize) -> Self {
        Span { start, end }
    }
    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span {
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }
}

/// A source file held in memory with its line table.
#[derive(Debug, Clone)]
pub struct Source {
    pub name: String,
    pub text: String,
    line_starts: Vec<usize>,
}

impl Source {
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Self {
        let text = text.into();
        let mut line_starts = vec![0];
        for (i, b) in text.bytes().enumerate() {
            if b == b'\n' {
                line_starts.push(i + 1);
            }
        }
        Source {
            name: name.into(),
            text,
            line_starts,
        }
    }

    /// Reads a file, refusing binary and non-UTF-8 input with a clear message.
    pub fn read(path: &std::path::Path) -> Result<Source, Diagnostic> {
        let name = path.display().to_string();
        let bytes = std::fs::read(path)
            .map_err(|e| Diagnostic::error(format!("cannot read command file '{name}': {e}")))?;
        Source::from_bytes(name, bytes)
    }

    /// Builds a source from raw bytes (binary and invalid UTF-8 are errors).
    pub fn from_bytes(name: String, bytes: Vec<u8>) -> Result<Source, Diagnostic> {
        if let Some(pos) = bytes.iter().position(|&b| b == 0) {
            return Err(Diagnostic::error(format!(
                "'{name}' looks like a binary file (NUL byte at offset {pos}); a command file must be UTF-8 text"
            )));
        }
        match String::from_utf8(bytes) {
            Ok(text) => Ok(Source::new(name, text)),
            Err(e) => {
                let off = e.utf8_error().valid_up_to();
                let valid = String::from_utf8_lossy(&e.as_bytes()[..off]).into_owned();
                let line = valid.matches('\n').count() + 1;
                let col = valid.len() - valid.rfind('\n').map(|p| p + 1).unwrap_or(0) + 1;
                Err(Diagnostic::error(format!(
                    "'{name}' is not valid UTF-8 (invalid byte at line {line}, column {col}, offset {off}); save the command file as UTF-8"
                )))
            }
        }
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let line = match self.line_starts.binary_search(&offset) {
            Ok(l) => l,
            Err(l) => l - 1,
        };
        let start = self.line_starts[line];
        let col = self.text[start..offset].chars().count() + 1;
        (line + 1, col)
    }

    /// The text of a 1-based line, without its newline.
    pub fn line_text(&self, line: usize) -> &str {
        let start = self.line_starts[line - 1];
        let end = self
            .line_starts
            .get(line)
            .map(|&e| e - 1)
            .unwrap_or(self.text.len());
        self.text[start..end].trim_end_matches('\r')
    }

    pub fn slice(&self, span: Span) -> &str {
        &self.text[span.start.min(self.text.len())..span.end.min(self.text.len())]
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

/// One message for the user.
#[derive(Debug, Clone)]
pub struct Diagnostic {
    pub severity: Severity,
    pub message: String,
    pub span: Option<Span>,
    /// The command being checked or run, e.g. `DYNA_NON_LINE`.
    pub command: Option<String>,
    /// The keyword path inside the command, e.g. `SCHEMA_TEMPS/ALPHA`.
    pub keyword: Option<String>,
    /// A closed list of valid choices, shown when the value is not one of them.
    pub choices: Vec<String>,
    /// The closest valid choice ("did you mean").
    pub suggestion: Option<String>,
    pub notes: Vec<String>,
}

impl Diagnostic {
    pub fn error(message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            span: None,
            command: None,
            keyword: None,
            choices: Vec::new(),
            suggestion: None,
            notes: Vec::new(),
        }
    }
    pub fn warning(message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(message)
        }
    }
    pub fn at(mut self, span: Span) -> Self {
        self.span = Some(span);
        self
    }
    /// Locates a diagnostic built where no position was known, keeping a
    /// more precise one.
    pub fn at_if_none(mut self, span: Span) -> Self {
        self.span.get_or_insert(span);
        self
    }
    pub fn in_command(mut self, command: impl Into<String>) -> Self {
        self.command = Some(command.into());
        self
    }
    pub fn keyword(mut self, path: impl Into<String>) -> Self {
        self.keyword = Some(path.into());
        self
    }
    /// Adds the valid choices and, if one is close to `given`, a suggestion.
    pub fn choices<S: AsRef<str>>(mut self, given: &str, choices: &[S]) -> Self {
        self.choices = choices.iter().map(|c| c.as_ref().to_string()).collect();
        self.suggestion = closest(given, &self.choices);
        self
    }
    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }

    /// `COMMAND/KEY/SUB` as printed in messages (command alone if no keyword).
    pub fn location_path(&self) -> Option<String> {
        match (&self.command, &self.keyword) {
            (Some(c), Some(k)) => Some(format!("{c}/{k}")),
            (Some(c), None) => Some(c.clone()),
            (None, Some(k)) => Some(k.clone()),
            (None, None) => None,
        }
    }

    /// Renders the message in the rustc-like layout used everywhere:
    ///
    /// ```text
    /// error: DYNA_NON_LINE/SCHEMA_TEMPS/SCHEMA: 'NEWMAK' is not an allowed value
    ///   --> study.comm:12:30
    ///    |
    /// 12 |     SCHEMA_TEMPS=_F(SCHEMA='NEWMAK',
    ///    |                            ^^^^^^^^
    ///    = expected one of: 'DIFF_CENT', 'TCHAMWA', 'NEWMARK', 'HHT'
    ///    = help: did you mean 'NEWMARK'?
    /// ```
    pub fn render(&self, src: Option<&Source>) -> String {
        let mut out = String::new();
        let sev = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        match self.location_path() {
            Some(p) => {
                let _ = writeln!(out, "{sev}: {p}: {}", self.message);
            }
            None => {
                let _ = writeln!(out, "{sev}: {}", self.message);
            }
        }
        let mut gutter = 2;
        if let (Some(src), Some(span)) = (src, self.span) {
            let (line, col) = src.line_col(span.start);
            let text = src.line_text(line);
            let lnum = line.to_string();
            gutter = lnum.len() + 1;
            let pad = " ".repeat(gutter);
            let _ = writeln!(out, "{pad}--> {}:{line}:{col}", src.name);
            let _ = writeln!(out, "{pad}|");
            let _ = writeln!(out, "{lnum} | {text}");
            // Caret under the span, limited to the first line of the span.
            let line_end_byte = src.line_starts[line - 1] + text.len();
            let end = span.end.min(line_end_byte).max(span.start);
            let width = src.text[span.start..end].chars().count().max(1);
            let lead: String = text
                .chars()
                .take(col - 1)
                .map(|c| if c == '\t' { '\t' } else { ' ' })
                .collect();
            let _ = writeln!(out, "{pad}| {lead}{}", "^".repeat(width));
        } else if let Some(src) = src {
            let _ = writeln!(out, "  --> {}", src.name);
        }
        let pad = " ".repeat(gutter);
        if !self.choices.is_empty() {
            let list: Vec<String> = self.choices.iter().map(|c| format!("'{c}'")).collect();
            let _ = writeln!(out, "{pad}= expected one of: {}", list.join(", "));
        }
        if let Some(s) = &self.suggestion {
            let _ = writeln!(out, "{pad}= help: did you mean '{s}'?");
        }
        for n in &self.notes {
            let _ = writeln!(out, "{pad}= note: {n}");
        }
        out
    }
}

impl std::fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.render(None).trim_end())
    }
}

impl std::error::Error for Diagnostic {}

/// A list of diagnostics (the checker reports all errors of a file at once).
pub type Diagnostics = Vec<Diagnostic>;

/// Levenshtein distance, for "did you mean".
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        cur[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            cur[j] = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// The closest candidate, if it is close enough to be a plausible typo
/// (case-insensitive; at most a third of the longer length).
pub fn closest<S: AsRef<str>>(given: &str, candidates: &[S]) -> Option<String> {
    let g = given.to_uppercase();
    candidates
        .iter()
        .map(|c| (edit_distance(&g, &c.as_ref().to_uppercase()), c.as_ref()))
        .filter(|(d, c)| *d <= (g.chars().count().max(c.chars().count()) / 3).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_and_render() {
        let src = Source::new("t.comm", "DEBUT()\nA = F(X='NEWMAK')\n");
        let off = src.text.find("'NEWMAK'").unwrap();
        assert_eq!(src.line_col(off), (2, 9));
        let d = Diagnostic::error("'NEWMAK' is not an allowed value")
            .at(Span::new(off, off + 8))
            .in_command("F")
            .keyword("X")
            .choices("NEWMAK", &["NEWMARK", "HHT"]);
        let r = d.render(Some(&src));
        assert!(r.contains("t.comm:2:9"), "{r}");
        assert!(r.contains("^^^^^^^^"), "{r}");
        assert!(r.contains("did you mean 'NEWMARK'"), "{r}");
    }

    #[test]
    fn rejects_binary_and_bad_utf8() {
        assert!(Source::from_bytes("b".into(), vec![b'A', 0, 1]).is_err());
        let e = Source::from_bytes("u".into(), b"DEBUT()\n\xff".to_vec()).unwrap_err();
        assert!(e.message.contains("line 2"), "{}", e.message);
    }

    #[test]
    fn closest_choice() {
        assert_eq!(
            closest("NEWMAK", &["NEWMARK", "HHT"]).as_deref(),
            Some("NEWMARK")
        );
        assert_eq!(closest("XYZ", &["NEWMARK", "HHT"]), None);
    }
}
