//! A Part 21 (ISO 10303-21) tokenizer and parser: the header's schema and every entity
//! instance of the DATA sections as a typed parameter tree, nothing dropped.
//!
//! Bounded: at most [`MAX_INPUT_BYTES`] of input, [`MAX_ENTITIES`] instances and
//! [`MAX_NESTING`] levels of parentheses; one pass over the bytes, memory linear in the input.

use crate::io::step::error::StepError;
use std::collections::HashMap;

/// Largest input read (bytes): 256 MiB.
pub const MAX_INPUT_BYTES: usize = 256 << 20;
/// Largest number of entity instances (a million): past it the reader stops with
/// [`StepError::TooLarge`] before reading further.
pub const MAX_ENTITIES: usize = 1_000_000;
/// Deepest nesting of parameter lists.
pub const MAX_NESTING: usize = 32;

/// One parameter of an entity instance.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Param {
    /// An integer.
    Int(i64),
    /// A real number.
    Real(f64),
    /// A string, with `''` and the `\X\`-style escapes left as written.
    Str(String),
    /// An enumeration value `.NAME.` (without the dots).
    Enum(String),
    /// A reference `#id`.
    Ref(u64),
    /// A list `( ... )`.
    List(Vec<Param>),
    /// The unset value `$`.
    Null,
    /// The derived value `*`.
    Derived,
    /// A typed value `NAME(params)` such as `LENGTH_MEASURE(1.0)`.
    Typed(String, Vec<Param>),
    /// A binary value `"..."`.
    Binary,
}

impl Param {
    /// Every `#id` this parameter references, depth first.
    pub(crate) fn refs(&self, out: &mut Vec<u64>) {
        match self {
            Self::Ref(id) => out.push(*id),
            Self::List(items) | Self::Typed(_, items) => {
                for item in items {
                    item.refs(out);
                }
            }
            _ => {}
        }
    }
}

/// One entity instance: a simple instance has one part, a complex one (`#1 = (A(...) B(...))`)
/// several, in file order.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Record {
    /// 1-based line where the instance starts.
    pub line: usize,
    /// (type name, parameters) of each part.
    pub parts: Vec<(String, Vec<Param>)>,
}

impl Record {
    /// The type name: the only part's, or the parts' names joined by `+`.
    pub(crate) fn type_name(&self) -> String {
        let names: Vec<&str> = self.parts.iter().map(|(n, _)| n.as_str()).collect();
        names.join("+")
    }

    /// The parameters of the part named `name`.
    pub(crate) fn part(&self, name: &str) -> Option<&[Param]> {
        self.parts
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_slice())
    }

    /// True when the instance has a part named `name`.
    pub(crate) fn has(&self, name: &str) -> bool {
        self.parts.iter().any(|(n, _)| n == name)
    }
}

/// A parsed exchange structure.
#[derive(Debug, Default)]
pub(crate) struct Part21 {
    /// The schema names of the header's FILE_SCHEMA.
    pub schema: Vec<String>,
    /// Every instance of the DATA sections by id.
    pub records: HashMap<u64, Record>,
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Keyword(String),
    Id(u64),
    Int(i64),
    Real(f64),
    Str(String),
    Enum(String),
    Binary,
    Open,
    Close,
    Comma,
    Semicolon,
    Equals,
    Dollar,
    Star,
}

struct Lexer<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Lexer<'a> {
    fn syntax(&self, message: impl Into<String>) -> StepError {
        StepError::Syntax {
            line: self.line,
            message: message.into(),
        }
    }

    fn skip_space(&mut self) -> Result<(), StepError> {
        loop {
            match self.bytes.get(self.pos) {
                Some(b'\n') => {
                    self.line += 1;
                    self.pos += 1;
                }
                Some(b' ' | b'\t' | b'\r') => self.pos += 1,
                Some(b'/') if self.bytes.get(self.pos + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.pos += 2;
                    loop {
                        match self.bytes.get(self.pos) {
                            None => {
                                return Err(StepError::Truncated {
                                    inside: format!("a comment opened at line {start}"),
                                });
                            }
                            Some(b'*') if self.bytes.get(self.pos + 1) == Some(&b'/') => {
                                self.pos += 2;
                                break;
                            }
                            Some(b'\n') => {
                                self.line += 1;
                                self.pos += 1;
                            }
                            Some(_) => self.pos += 1,
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    /// The next token, or `None` at the end of the input.
    fn next(&mut self) -> Result<Option<Token>, StepError> {
        self.skip_space()?;
        let Some(&c) = self.bytes.get(self.pos) else {
            return Ok(None);
        };
        let token = match c {
            b'(' => {
                self.pos += 1;
                Token::Open
            }
            b')' => {
                self.pos += 1;
                Token::Close
            }
            b',' => {
                self.pos += 1;
                Token::Comma
            }
            b';' => {
                self.pos += 1;
                Token::Semicolon
            }
            b'=' => {
                self.pos += 1;
                Token::Equals
            }
            b'$' => {
                self.pos += 1;
                Token::Dollar
            }
            b'*' => {
                self.pos += 1;
                Token::Star
            }
            b'#' => {
                self.pos += 1;
                let digits = self.take_while(|b| b.is_ascii_digit());
                let id = std::str::from_utf8(digits)
                    .ok()
                    .and_then(|s| s.parse::<u64>().ok())
                    .ok_or_else(|| self.syntax("'#' not followed by an instance number"))?;
                Token::Id(id)
            }
            b'\'' => self.string()?,
            b'"' => {
                self.pos += 1;
                self.take_while(|b| b.is_ascii_hexdigit());
                if self.bytes.get(self.pos) != Some(&b'"') {
                    return Err(if self.pos >= self.bytes.len() {
                        StepError::Truncated {
                            inside: "a binary value".into(),
                        }
                    } else {
                        self.syntax("a binary value holds a non-hexadecimal character")
                    });
                }
                self.pos += 1;
                Token::Binary
            }
            b'.' if self
                .bytes
                .get(self.pos + 1)
                .is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_') =>
            {
                self.pos += 1;
                let name = self.take_while(|b| b.is_ascii_alphanumeric() || b == b'_');
                let name = String::from_utf8_lossy(name).into_owned();
                if self.bytes.get(self.pos) != Some(&b'.') {
                    return Err(self.syntax(format!("enumeration .{name} has no closing '.'")));
                }
                self.pos += 1;
                Token::Enum(name)
            }
            b'0'..=b'9' | b'-' | b'+' | b'.' => self.number()?,
            b'A'..=b'Z' | b'a'..=b'z' | b'_' | b'!' => {
                let word = self.take_while(|b| {
                    b.is_ascii_alphanumeric() || b == b'_' || b == b'-' || b == b'!'
                });
                Token::Keyword(String::from_utf8_lossy(word).to_ascii_uppercase())
            }
            other => {
                return Err(self.syntax(if other.is_ascii_graphic() {
                    format!("unexpected character {:?}", other as char)
                } else {
                    format!("byte 0x{other:02x} is not allowed outside a string (binary or non-ASCII data)")
                }));
            }
        };
        Ok(Some(token))
    }

    fn take_while(&mut self, keep: impl Fn(u8) -> bool) -> &'a [u8] {
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(|&b| keep(b)) {
            self.pos += 1;
        }
        &self.bytes[start..self.pos]
    }

    fn string(&mut self) -> Result<Token, StepError> {
        let start_line = self.line;
        self.pos += 1;
        let mut out = Vec::new();
        loop {
            match self.bytes.get(self.pos) {
                None => {
                    return Err(StepError::Truncated {
                        inside: format!("a string opened at line {start_line}"),
                    });
                }
                Some(b'\'') if self.bytes.get(self.pos + 1) == Some(&b'\'') => {
                    out.push(b'\'');
                    self.pos += 2;
                }
                Some(b'\'') => {
                    self.pos += 1;
                    break;
                }
                Some(&b) => {
                    if b == b'\n' {
                        self.line += 1;
                    } else if b < 0x20 && b != b'\r' && b != b'\t' {
                        return Err(self.syntax(format!(
                            "control byte 0x{b:02x} inside a string (binary data)"
                        )));
                    }
                    out.push(b);
                    self.pos += 1;
                }
            }
        }
        // Part 21 strings are ISO 8859-1 with escapes; bytes above 0x7f are read as Latin-1.
        Ok(Token::Str(out.iter().map(|&b| char::from(b)).collect()))
    }

    fn number(&mut self) -> Result<Token, StepError> {
        let text = self
            .take_while(|b| b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'E' | b'e'));
        let text = std::str::from_utf8(text).map_err(|_| self.syntax("bad number"))?;
        if !text.contains(['.', 'E', 'e']) {
            if let Ok(i) = text.parse::<i64>() {
                return Ok(Token::Int(i));
            }
        }
        let value: f64 = text
            .parse()
            .map_err(|_| self.syntax(format!("{text:?} is not a number")))?;
        if !value.is_finite() {
            return Err(self.syntax(format!("{text:?} is not a finite number")));
        }
        Ok(Token::Real(value))
    }
}

struct Parser<'a> {
    lexer: Lexer<'a>,
    peeked: Option<Token>,
}

impl Parser<'_> {
    fn peek(&mut self) -> Result<Option<&Token>, StepError> {
        if self.peeked.is_none() {
            self.peeked = self.lexer.next()?;
        }
        Ok(self.peeked.as_ref())
    }

    fn next(&mut self, inside: &str) -> Result<Token, StepError> {
        if let Some(t) = self.peeked.take() {
            return Ok(t);
        }
        self.lexer.next()?.ok_or_else(|| StepError::Truncated {
            inside: inside.to_string(),
        })
    }

    fn expect(&mut self, want: &Token, inside: &str) -> Result<(), StepError> {
        let got = self.next(inside)?;
        if &got == want {
            Ok(())
        } else {
            Err(self
                .lexer
                .syntax(format!("expected {want:?} in {inside}, found {got:?}")))
        }
    }

    fn keyword(&mut self, inside: &str) -> Result<String, StepError> {
        match self.next(inside)? {
            Token::Keyword(k) => Ok(k),
            other => Err(self
                .lexer
                .syntax(format!("expected a keyword in {inside}, found {other:?}"))),
        }
    }

    /// The parameters after an opening parenthesis, up to and including its closing one.
    fn params(&mut self, depth: usize, inside: &str) -> Result<Vec<Param>, StepError> {
        if depth > MAX_NESTING {
            return Err(StepError::TooLarge {
                what: "nesting of parameter lists",
                limit: MAX_NESTING,
            });
        }
        let mut out = Vec::new();
        if self.peek()? == Some(&Token::Close) {
            self.next(inside)?;
            return Ok(out);
        }
        loop {
            out.push(self.param(depth, inside)?);
            match self.next(inside)? {
                Token::Comma => {}
                Token::Close => return Ok(out),
                other => {
                    return Err(self
                        .lexer
                        .syntax(format!("expected ',' or ')' in {inside}, found {other:?}")));
                }
            }
        }
    }

    fn param(&mut self, depth: usize, inside: &str) -> Result<Param, StepError> {
        Ok(match self.next(inside)? {
            Token::Int(i) => Param::Int(i),
            Token::Real(r) => Param::Real(r),
            Token::Str(s) => Param::Str(s),
            Token::Enum(e) => Param::Enum(e),
            Token::Id(id) => Param::Ref(id),
            Token::Dollar => Param::Null,
            Token::Star => Param::Derived,
            Token::Binary => Param::Binary,
            Token::Open => Param::List(self.params(depth + 1, inside)?),
            Token::Keyword(name) => {
                self.expect(&Token::Open, inside)?;
                Param::Typed(name, self.params(depth + 1, inside)?)
            }
            other => {
                return Err(self
                    .lexer
                    .syntax(format!("unexpected {other:?} in {inside}")));
            }
        })
    }

    /// `NAME(params)` parts up to the `;` (header entities) or the closing `)` of a complex
    /// instance.
    fn simple(&mut self, inside: &str) -> Result<(String, Vec<Param>), StepError> {
        let name = self.keyword(inside)?;
        self.expect(&Token::Open, inside)?;
        Ok((name, self.params(1, inside)?))
    }
}

/// Parses a Part 21 exchange structure.
///
/// # Errors
/// [`StepError::NotStep`] without the `ISO-10303-21;` opening, [`StepError::Syntax`],
/// [`StepError::Truncated`], [`StepError::TooLarge`] past the limits of this module,
/// [`StepError::DuplicateId`].
pub(crate) fn parse(bytes: &[u8]) -> Result<Part21, StepError> {
    if bytes.len() > MAX_INPUT_BYTES {
        return Err(StepError::TooLarge {
            what: "input bytes",
            limit: MAX_INPUT_BYTES,
        });
    }
    let mut parser = Parser {
        lexer: Lexer {
            bytes,
            pos: 0,
            line: 1,
        },
        peeked: None,
    };
    let magic = match parser.lexer.next() {
        Ok(Some(Token::Keyword(k))) => k,
        Ok(None) => {
            return Err(StepError::NotStep {
                reason: "the input is empty".into(),
            });
        }
        Ok(Some(other)) => {
            return Err(StepError::NotStep {
                reason: format!("it starts with {other:?}"),
            });
        }
        Err(e) => {
            return Err(StepError::NotStep {
                reason: e.to_string(),
            });
        }
    };
    if magic != "ISO-10303-21" {
        return Err(StepError::NotStep {
            reason: format!("it starts with {magic:?}, not ISO-10303-21"),
        });
    }
    parser.expect(&Token::Semicolon, "the opening line")?;
    if parser.keyword("the header")? != "HEADER" {
        return Err(parser.lexer.syntax("expected HEADER;"));
    }
    parser.expect(&Token::Semicolon, "the header")?;
    let mut out = Part21::default();
    loop {
        let name = parser.keyword("the header")?;
        if name == "ENDSEC" {
            parser.expect(&Token::Semicolon, "the header")?;
            break;
        }
        parser.expect(&Token::Open, "the header")?;
        let params = parser.params(1, "the header")?;
        parser.expect(&Token::Semicolon, "the header")?;
        if name == "FILE_SCHEMA" {
            if let Some(Param::List(items)) = params.first() {
                out.schema = items
                    .iter()
                    .filter_map(|p| match p {
                        Param::Str(s) => Some(s.clone()),
                        _ => None,
                    })
                    .collect();
            }
        }
    }
    // DATA sections up to END-ISO-10303-21.
    loop {
        let name = parser.keyword("the file after the header")?;
        match name.as_str() {
            "END-ISO-10303-21" => {
                parser.expect(&Token::Semicolon, "the closing line")?;
                break;
            }
            "DATA" => {
                if parser.peek()? == Some(&Token::Open) {
                    parser.next("the DATA line")?;
                    parser.params(1, "the DATA line")?;
                }
                parser.expect(&Token::Semicolon, "the DATA line")?;
                read_data(&mut parser, &mut out)?;
            }
            other => {
                return Err(parser
                    .lexer
                    .syntax(format!("expected DATA or END-ISO-10303-21, found {other}")));
            }
        }
    }
    Ok(out)
}

fn read_data(parser: &mut Parser<'_>, out: &mut Part21) -> Result<(), StepError> {
    loop {
        let line = parser.lexer.line;
        match parser.next("the DATA section")? {
            Token::Keyword(k) if k == "ENDSEC" => {
                parser.expect(&Token::Semicolon, "the DATA section")?;
                return Ok(());
            }
            Token::Id(id) => {
                let inside = format!("entity #{id}");
                parser.expect(&Token::Equals, &inside)?;
                let parts = if parser.peek()? == Some(&Token::Open) {
                    parser.next(&inside)?;
                    let mut parts = Vec::new();
                    while parser.peek()? != Some(&Token::Close) {
                        parts.push(parser.simple(&inside)?);
                        if parser.peek()?.is_none() {
                            return Err(StepError::Truncated { inside });
                        }
                    }
                    parser.next(&inside)?;
                    if parts.is_empty() {
                        return Err(parser.lexer.syntax(format!("{inside} has no type")));
                    }
                    parts
                } else {
                    vec![parser.simple(&inside)?]
                };
                parser.expect(&Token::Semicolon, &inside)?;
                if out.records.len() >= MAX_ENTITIES {
                    return Err(StepError::TooLarge {
                        what: "entity instances",
                        limit: MAX_ENTITIES,
                    });
                }
                if out.records.insert(id, Record { line, parts }).is_some() {
                    return Err(StepError::DuplicateId { id });
                }
            }
            other => {
                return Err(parser.lexer.syntax(format!(
                    "expected an entity instance '#id = ...' or ENDSEC, found {other:?}"
                )));
            }
        }
    }
}
