//! The token reader shared by the `.sod`, `.ood` and `.geo` parsers: whitespace-separated
//! tokens, `//` comments to the end of the line dropped, each token knowing its line so that
//! every error can point at the place in the file.

use std::fmt::Display;
use std::ops::RangeInclusive;
use std::path::Path;

use glam::{Vec2, Vec3};

use crate::scene::{Mat44, SceneError};

#[derive(Clone, Copy, Debug)]
pub struct Token<'a> {
    pub text: &'a str,
    /// 1-based.
    pub line: usize,
}

/// What `Syntax` errors report as the found token when the file ran out.
pub const END_OF_FILE: &str = "end of file";

pub struct Tokens<'a> {
    path: &'a Path,
    tokens: Vec<Token<'a>>,
    next: usize,
    /// Where "end of file" errors point: the file's last line.
    last_line: usize,
}

impl<'a> Tokens<'a> {
    pub fn new(text: &'a str, path: &'a Path) -> Tokens<'a> {
        let mut tokens = Vec::new();
        let mut last_line = 1;
        for (index, line) in text.lines().enumerate() {
            last_line = index + 1;
            let code = line.split("//").next().unwrap_or("");
            tokens.extend(code.split_whitespace().map(|text| Token {
                text,
                line: last_line,
            }));
        }
        Tokens {
            path,
            tokens,
            next: 0,
            last_line,
        }
    }

    /// How many tokens are left to read.
    pub fn remaining(&self) -> usize {
        self.tokens.len() - self.next
    }

    /// A `Syntax` error at `token`: "expected {what}".
    pub fn error_at(&self, token: Token<'_>, what: impl Display) -> SceneError {
        self.problem_at(token, format!("expected {what}"))
    }

    /// A `Syntax` error at `token` with a message of its own.
    pub fn problem_at(&self, token: Token<'_>, message: String) -> SceneError {
        SceneError::Syntax {
            path: self.path.to_path_buf(),
            line: token.line,
            token: token.text.to_string(),
            what: message,
        }
    }

    /// The token read last, if any.
    pub fn previous(&self) -> Option<Token<'a>> {
        self.tokens.get(self.next.checked_sub(1)?).copied()
    }

    /// The next token, or an error saying `what` was expected at the end of the file.
    pub fn token(&mut self, what: impl Display) -> Result<Token<'a>, SceneError> {
        match self.tokens.get(self.next) {
            Some(&token) => {
                self.next += 1;
                Ok(token)
            }
            None => Err(self.error_at(
                Token {
                    text: END_OF_FILE,
                    line: self.last_line,
                },
                what,
            )),
        }
    }

    /// A number for which `accept` holds; `what` describes it, including the accepted range.
    pub fn number_where(
        &mut self,
        accept: impl Fn(f32) -> bool,
        what: impl Display,
    ) -> Result<f32, SceneError> {
        let token = self.token(&what)?;
        match token.text.parse::<f32>() {
            Ok(x) if x.is_finite() && accept(x) => Ok(x),
            _ => Err(self.error_at(token, what)),
        }
    }

    /// Any finite number.
    pub fn number(&mut self, what: impl Display) -> Result<f32, SceneError> {
        self.number_where(|_| true, format_args!("{what} (a finite number)"))
    }

    /// A whole number written with digits only (no sign, point or exponent) inside `range`;
    /// `what` describes it, including the accepted range.
    pub fn whole(
        &mut self,
        range: RangeInclusive<u64>,
        what: impl Display,
    ) -> Result<u64, SceneError> {
        let token = self.token(&what)?;
        let digits_only = !token.text.is_empty() && token.text.bytes().all(|b| b.is_ascii_digit());
        match token.text.parse::<u64>() {
            Ok(n) if digits_only && range.contains(&n) => Ok(n),
            _ => Err(self.error_at(token, what)),
        }
    }

    pub fn vec2(&mut self, what: impl Display) -> Result<Vec2, SceneError> {
        let x = self.number(format_args!("component 1 of 2 of {what}"))?;
        let y = self.number(format_args!("component 2 of 2 of {what}"))?;
        Ok(Vec2::new(x, y))
    }

    pub fn vec3(&mut self, what: impl Display) -> Result<Vec3, SceneError> {
        let x = self.number(format_args!("component 1 of 3 of {what}"))?;
        let y = self.number(format_args!("component 2 of 3 of {what}"))?;
        let z = self.number(format_args!("component 3 of 3 of {what}"))?;
        Ok(Vec3::new(x, y, z))
    }

    /// 16 numbers, row-major.
    pub fn mat44(&mut self, what: impl Display) -> Result<Mat44, SceneError> {
        let mut values = [0.0; 16];
        for (i, value) in values.iter_mut().enumerate() {
            *value = self.number(format_args!("element {} of 16 of {what}", i + 1))?;
        }
        Ok(Mat44::from_row_major(values))
    }

    /// Succeeds only if nothing but whitespace and comments follows; `last` names what was read
    /// last, for the message.
    pub fn finish(mut self, last: impl Display) -> Result<(), SceneError> {
        match self.remaining() {
            0 => Ok(()),
            _ => {
                let token = self.token("")?;
                Err(self.error_at(token, format_args!("the end of the file after {last}")))
            }
        }
    }
}
