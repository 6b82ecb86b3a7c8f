//! The top module's port list, read from its Verilog declarations.
//!
//! Understands both header styles: rust-hdl's non-ANSI `module top(a,b); input wire [31:0] a; …`
//! and ANSI `module top(input wire [31:0] a, output reg b);`. Ranges must be integer literals
//! (`[31:0]`); parameterised widths are rejected with the line that holds them.

use crate::SimError;

/// Direction of a port, seen from the module.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    Input,
    Output,
}

/// One port of the top module.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Port {
    pub name: String,
    pub direction: Direction,
    pub width: u32,
}

impl Port {
    pub fn new(name: impl Into<String>, direction: Direction, width: u32) -> Self {
        Port {
            name: name.into(),
            direction,
            width,
        }
    }

    /// 32-bit words this port occupies in the packed input/output buffers.
    pub fn words(&self) -> usize {
        self.width.div_ceil(32) as usize
    }
}

#[derive(Clone, Debug, PartialEq)]
struct Token {
    text: String,
    line: usize,
}

/// Splits Verilog into identifiers/numbers and single punctuation characters, dropping comments.
fn tokenize(src: &str) -> Vec<Token> {
    let chars: Vec<char> = src.chars().collect();
    let mut tokens = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < chars.len() {
        let c = chars[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && chars.get(i + 1) == Some(&'/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && chars.get(i + 1) == Some(&'*') {
            i += 2;
            while i < chars.len() && !(chars[i] == '*' && chars.get(i + 1) == Some(&'/')) {
                line += usize::from(chars[i] == '\n');
                i += 1;
            }
            i += 2;
        } else if c == '\\' {
            // Escaped identifier: everything up to white space.
            let start = i;
            while i < chars.len() && !chars[i].is_whitespace() {
                i += 1;
            }
            tokens.push(Token {
                text: chars[start..i].iter().collect(),
                line,
            });
        } else if c.is_alphanumeric() || c == '_' || c == '$' || c == '\'' {
            let start = i;
            while i < chars.len()
                && (chars[i].is_alphanumeric() || matches!(chars[i], '_' | '$' | '\''))
            {
                i += 1;
            }
            tokens.push(Token {
                text: chars[start..i].iter().collect(),
                line,
            });
        } else {
            tokens.push(Token {
                text: c.to_string(),
                line,
            });
            i += 1;
        }
    }
    tokens
}

struct Parser<'a> {
    tokens: &'a [Token],
    pos: usize,
    module: &'a str,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<&'a str> {
        self.tokens.get(self.pos).map(|t| t.text.as_str())
    }

    fn line(&self) -> usize {
        self.tokens
            .get(self.pos)
            .or(self.tokens.last())
            .map_or(1, |t| t.line)
    }

    fn error(&self, message: impl Into<String>) -> SimError {
        SimError::Ports {
            module: self.module.to_string(),
            line: self.line(),
            message: message.into(),
        }
    }

    fn next(&mut self) -> Result<&'a str, SimError> {
        let t = self
            .peek()
            .ok_or_else(|| self.error("unexpected end of file"))?;
        self.pos += 1;
        Ok(t)
    }

    fn expect(&mut self, what: &str) -> Result<(), SimError> {
        match self.peek() {
            Some(t) if t == what => {
                self.pos += 1;
                Ok(())
            }
            other => Err(self.error(format!(
                "expected `{what}`, found `{}`",
                other.unwrap_or("end of file")
            ))),
        }
    }

    fn skip_balanced(&mut self, open: &str, close: &str) -> Result<(), SimError> {
        self.expect(open)?;
        let mut depth = 1;
        while depth > 0 {
            let t = self.next()?;
            depth += i32::from(t == open) - i32::from(t == close);
        }
        Ok(())
    }

    fn integer(&mut self) -> Result<i64, SimError> {
        let t = self.next()?;
        t.replace('_', "")
            .parse()
            .map_err(|_| self.error(format!("expected an integer in a port range, found `{t}` (parameterised widths are not supported)")))
    }

    /// `[wire|reg|logic] [signed] [[msb:lsb]]` after a direction keyword; returns the width.
    fn port_type(&mut self) -> Result<u32, SimError> {
        while matches!(
            self.peek(),
            Some("wire" | "reg" | "logic" | "signed" | "unsigned")
        ) {
            self.pos += 1;
        }
        if self.peek() != Some("[") {
            return Ok(1);
        }
        self.expect("[")?;
        let msb = self.integer()?;
        self.expect(":")?;
        let lsb = self.integer()?;
        self.expect("]")?;
        u32::try_from((msb - lsb).abs() + 1).map_err(|_| self.error("port range too wide"))
    }

    fn direction(&mut self) -> Result<Option<Direction>, SimError> {
        let dir = match self.peek() {
            Some("input") => Direction::Input,
            Some("output") => Direction::Output,
            Some("inout") => {
                return Err(self.error("inout ports are not supported by the simulator"))
            }
            _ => return Ok(None),
        };
        self.pos += 1;
        Ok(Some(dir))
    }

    fn identifier(&mut self) -> Result<String, SimError> {
        let t = self.next()?;
        if t.chars()
            .next()
            .is_some_and(|c| c.is_alphabetic() || c == '_' || c == '\\')
        {
            Ok(t.to_string())
        } else {
            self.pos -= 1;
            Err(self.error(format!("expected a port name, found `{t}`")))
        }
    }
}

/// Reads the ports of module `top` from `verilog`, in header order.
pub fn parse_ports(verilog: &str, top: &str) -> Result<Vec<Port>, SimError> {
    let tokens = tokenize(verilog);
    let mut p = Parser {
        tokens: &tokens,
        pos: 0,
        module: top,
    };
    let start = tokens
        .windows(2)
        .position(|w| w[0].text == "module" && w[1].text == top)
        .ok_or_else(|| SimError::Ports {
            module: top.to_string(),
            line: 1,
            message: "no `module` of that name in the Verilog".into(),
        })?;
    p.pos = start + 2;
    if p.peek() == Some("#") {
        p.pos += 1;
        p.skip_balanced("(", ")")?;
    }
    if p.peek() == Some(";") {
        return Ok(Vec::new());
    }
    p.expect("(")?;
    let mut ansi: Vec<Port> = Vec::new();
    let mut names: Vec<(String, usize)> = Vec::new();
    let mut current: Option<(Direction, u32)> = None;
    while p.peek() != Some(")") {
        if let Some(dir) = p.direction()? {
            current = Some((dir, p.port_type()?));
        }
        let line = p.line();
        let name = p.identifier()?;
        match current {
            Some((direction, width)) => ansi.push(Port {
                name,
                direction,
                width,
            }),
            None => names.push((name, line)),
        }
        if p.peek() == Some(",") {
            p.pos += 1;
        } else if p.peek() != Some(")") {
            return Err(p.error(format!(
                "expected `,` or `)` in the port list, found `{}`",
                p.peek().unwrap_or("end of file")
            )));
        }
    }
    p.expect(")")?;
    p.expect(";")?;
    if !ansi.is_empty() && !names.is_empty() {
        return Err(p.error("port list mixes ANSI declarations with bare names"));
    }
    if names.is_empty() {
        return Ok(ansi);
    }
    body_declarations(&mut p, names)
}

/// Non-ANSI style: finds the `input`/`output` declaration of every header name in the body.
fn body_declarations(p: &mut Parser, names: Vec<(String, usize)>) -> Result<Vec<Port>, SimError> {
    let mut declared: Vec<Option<(Direction, u32)>> = vec![None; names.len()];
    while p.peek() != Some("endmodule") {
        let Some(dir) = p.direction()? else {
            p.next()?;
            continue;
        };
        let width = p.port_type()?;
        loop {
            let name = p.identifier()?;
            let idx = names.iter().position(|(n, _)| *n == name).ok_or_else(|| {
                p.error(format!(
                    "`{name}` is declared as a port but is not in the module header"
                ))
            })?;
            declared[idx] = Some((dir, width));
            match p.next()? {
                "," => continue,
                ";" => break,
                t => {
                    p.pos -= 1;
                    return Err(p.error(format!(
                        "expected `,` or `;` after port `{name}`, found `{t}`"
                    )));
                }
            }
        }
    }
    names
        .into_iter()
        .zip(declared)
        .map(|((name, line), decl)| match decl {
            Some((direction, width)) => Ok(Port {
                name,
                direction,
                width,
            }),
            None => Err(SimError::Ports {
                module: p.module.to_string(),
                line,
                message: format!("port `{name}` has no input/output declaration"),
            }),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rust_hdl_style_header() {
        let v =
            "// generated\nmodule top(clock,a,b$x,sum);\n// Module arguments\ninput wire  clock;\n\
                 input wire  [31:0] a;\ninput wire signed [7:0] b$x;\noutput reg  [32:0] sum;\n\
                 reg [3:0] local;\nendmodule\nmodule other(q); output wire q; endmodule";
        let ports = parse_ports(v, "top").unwrap();
        assert_eq!(
            ports,
            vec![
                Port::new("clock", Direction::Input, 1),
                Port::new("a", Direction::Input, 32),
                Port::new("b$x", Direction::Input, 8),
                Port::new("sum", Direction::Output, 33),
            ]
        );
        assert_eq!(ports[3].words(), 2);
    }

    #[test]
    fn ansi_header_with_parameters_and_shared_types() {
        let v = "module top #(parameter W = 4) (input wire ap_clk, input [63:0] x, y,\n\
                 /* c */ output logic [0:95] z);\nendmodule";
        let ports = parse_ports(v, "top").unwrap();
        assert_eq!(
            ports,
            vec![
                Port::new("ap_clk", Direction::Input, 1),
                Port::new("x", Direction::Input, 64),
                Port::new("y", Direction::Input, 64),
                Port::new("z", Direction::Output, 96),
            ]
        );
    }

    #[test]
    fn errors_name_the_line() {
        let err =
            parse_ports("module top(a);\ninput wire [W-1:0] a;\nendmodule", "top").unwrap_err();
        assert!(matches!(err, SimError::Ports { line: 2, .. }), "{err}");
        let err = parse_ports("module top(a, b);\ninput a;\nendmodule", "top").unwrap_err();
        assert!(
            err.to_string()
                .contains("port `b` has no input/output declaration"),
            "{err}"
        );
        let err = parse_ports("module other(a); endmodule", "top").unwrap_err();
        assert!(
            err.to_string().contains("no `module` of that name"),
            "{err}"
        );
        let err = parse_ports("module top(inout x);\nendmodule", "top").unwrap_err();
        assert!(err.to_string().contains("inout"), "{err}");
        assert!(parse_ports("module top(a,", "top").is_err());
    }
}
