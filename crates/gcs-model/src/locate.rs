//! Positions of the items and fields of a RON model, for error messages.
//!
//! serde does not report where a value came from, so once the RON parser has accepted the text,
//! this small tokenizer walks it again and records where each entity and constraint starts and
//! where each of their field values starts. It never fails: anything it does not understand just
//! leaves a position unknown.

use std::collections::HashMap;

use crate::error::Position;

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Str,
    Num,
    Punct(char),
    Other,
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    pos: Position,
}

fn tokenize(text: &str) -> Vec<Token> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line, mut col) = (0usize, 1usize, 1usize);
    let advance = |i: &mut usize, line: &mut usize, col: &mut usize, n: usize| {
        for _ in 0..n {
            if *i < chars.len() {
                if chars[*i] == '\n' {
                    *line += 1;
                    *col = 1;
                } else {
                    *col += 1;
                }
                *i += 1;
            }
        }
    };
    while i < chars.len() {
        let c = chars[i];
        let pos = Position { line, column: col };
        if c.is_whitespace() {
            advance(&mut i, &mut line, &mut col, 1);
        } else if c == '/' && chars.get(i + 1) == Some(&'/') {
            while i < chars.len() && chars[i] != '\n' {
                advance(&mut i, &mut line, &mut col, 1);
            }
        } else if c == '/' && chars.get(i + 1) == Some(&'*') {
            // RON block comments nest.
            let mut depth = 0usize;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    advance(&mut i, &mut line, &mut col, 2);
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    advance(&mut i, &mut line, &mut col, 2);
                    if depth == 0 {
                        break;
                    }
                } else {
                    advance(&mut i, &mut line, &mut col, 1);
                }
            }
        } else if c == '"' {
            advance(&mut i, &mut line, &mut col, 1);
            while i < chars.len() && chars[i] != '"' {
                let n = if chars[i] == '\\' { 2 } else { 1 };
                advance(&mut i, &mut line, &mut col, n);
            }
            advance(&mut i, &mut line, &mut col, 1);
            out.push(Token { tok: Tok::Str, pos });
        } else if c == 'r' && matches!(chars.get(i + 1), Some('"') | Some('#')) {
            // Raw string r#"..."#.
            let mut j = i + 1;
            let mut hashes = 0;
            while chars.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if chars.get(j) != Some(&'"') {
                advance(&mut i, &mut line, &mut col, 1);
                out.push(Token { tok: Tok::Other, pos });
                continue;
            }
            let skip = j + 1 - i;
            advance(&mut i, &mut line, &mut col, skip);
            loop {
                if i >= chars.len() {
                    break;
                }
                if chars[i] == '"' && (1..=hashes).all(|k| chars.get(i + k) == Some(&'#')) {
                    advance(&mut i, &mut line, &mut col, hashes + 1);
                    break;
                }
                advance(&mut i, &mut line, &mut col, 1);
            }
            out.push(Token { tok: Tok::Str, pos });
        } else if c.is_ascii_digit()
            || ((c == '-' || c == '+' || c == '.')
                && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit() || *d == '.'))
        {
            advance(&mut i, &mut line, &mut col, 1);
            while i < chars.len()
                && (chars[i].is_ascii_alphanumeric()
                    || chars[i] == '.'
                    || chars[i] == '_'
                    || ((chars[i] == '-' || chars[i] == '+') && matches!(chars[i - 1], 'e' | 'E')))
            {
                advance(&mut i, &mut line, &mut col, 1);
            }
            out.push(Token { tok: Tok::Num, pos });
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                advance(&mut i, &mut line, &mut col, 1);
            }
            out.push(Token { tok: Tok::Ident(chars[start..i].iter().collect()), pos });
        } else if "()[]{},:#!".contains(c) {
            advance(&mut i, &mut line, &mut col, 1);
            out.push(Token { tok: Tok::Punct(c), pos });
        } else {
            advance(&mut i, &mut line, &mut col, 1);
            out.push(Token { tok: Tok::Other, pos });
        }
    }
    out
}

/// Where an entity or constraint is written, and where each of its field values starts.
#[derive(Clone, Debug, Default)]
pub(crate) struct ItemLoc {
    pub(crate) start: Option<Position>,
    pub(crate) fields: HashMap<String, Position>,
}

impl ItemLoc {
    /// The position of a field's value, or the item's start.
    pub(crate) fn field_or_start(&self, field: Option<&str>) -> Option<Position> {
        field.and_then(|f| self.fields.get(f).copied()).or(self.start)
    }
}

/// Positions in a model file.
#[derive(Clone, Debug, Default)]
pub(crate) struct Located {
    pub(crate) fields: HashMap<String, Position>,
    pub(crate) entities: Vec<ItemLoc>,
    pub(crate) constraints: Vec<ItemLoc>,
    pub(crate) groups: Vec<ItemLoc>,
}

struct Walker {
    toks: Vec<Token>,
    i: usize,
}

impl Walker {
    fn punct(&self, c: char) -> bool {
        self.toks.get(self.i).is_some_and(|t| t.tok == Tok::Punct(c))
    }

    fn ident(&self) -> Option<String> {
        match self.toks.get(self.i) {
            Some(Token { tok: Tok::Ident(s), .. }) => Some(s.clone()),
            _ => None,
        }
    }

    fn pos(&self) -> Option<Position> {
        self.toks.get(self.i).map(|t| t.pos)
    }

    /// Skips one value (a scalar, a group, or `Name(...)`).
    fn skip_value(&mut self) {
        if self.ident().is_some()
            && self.toks.get(self.i + 1).is_some_and(|t| t.tok == Tok::Punct('('))
        {
            self.i += 1;
        }
        match self.toks.get(self.i).map(|t| &t.tok) {
            Some(Tok::Punct('(' | '[' | '{')) => {
                let mut depth = 0usize;
                while let Some(t) = self.toks.get(self.i) {
                    match t.tok {
                        Tok::Punct('(' | '[' | '{') => depth += 1,
                        Tok::Punct(')' | ']' | '}') => {
                            depth -= 1;
                            if depth == 0 {
                                self.i += 1;
                                return;
                            }
                        }
                        _ => {}
                    }
                    self.i += 1;
                }
            }
            Some(_) => self.i += 1,
            None => {}
        }
    }

    /// Walks `( name: value, ... )`, calling `on_field` at each value start; the walker is left
    /// after the closing parenthesis.
    fn fields(&mut self, mut on_field: impl FnMut(&mut Walker, String, Position)) {
        if !self.punct('(') {
            return;
        }
        self.i += 1;
        while self.i < self.toks.len() && !self.punct(')') {
            let Some(name) = self.ident() else {
                self.skip_value();
                if self.punct(',') {
                    self.i += 1;
                }
                continue;
            };
            self.i += 1;
            if !self.punct(':') {
                continue;
            }
            self.i += 1;
            let Some(pos) = self.pos() else { return };
            let before = self.i;
            on_field(self, name, pos);
            if self.i == before {
                self.skip_value();
            }
            if self.punct(',') {
                self.i += 1;
            }
        }
        self.i += 1;
    }

    fn items(&mut self) -> Vec<ItemLoc> {
        let mut out = Vec::new();
        if !self.punct('[') {
            self.skip_value();
            return out;
        }
        self.i += 1;
        while self.i < self.toks.len() && !self.punct(']') {
            let mut item = ItemLoc { start: self.pos(), fields: HashMap::new() };
            if self.ident().is_some() {
                self.i += 1;
            }
            if self.punct('(') {
                self.fields(|w, name, pos| {
                    item.fields.insert(name, pos);
                    w.skip_value();
                });
            } else {
                self.skip_value();
            }
            out.push(item);
            if self.punct(',') {
                self.i += 1;
            }
        }
        self.i += 1;
        out
    }
}

/// Locates the items of a model text. Never fails; unknown positions are left out.
pub(crate) fn locate(text: &str) -> Located {
    let mut w = Walker { toks: tokenize(text), i: 0 };
    // Inner attributes: #![enable(...)]
    while w.punct('#') {
        w.i += 1;
        if w.punct('!') {
            w.i += 1;
        }
        w.skip_value();
    }
    if w.ident().is_some() {
        w.i += 1;
    }
    let mut located = Located::default();
    w.fields(|w, name, pos| {
        located.fields.insert(name.clone(), pos);
        match name.as_str() {
            "entities" => located.entities = w.items(),
            "constraints" => located.constraints = w.items(),
            "groups" => located.groups = w.items(),
            _ => w.skip_value(),
        }
    });
    located
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_items_and_fields() {
        let text = "// header\nSystem(\n  dim: 2,\n  entities: [\n    Point(id: \"p\", at: [1, -2.5]),\n    /* c */ Point(id: \"q\"),\n  ],\n  constraints: [Distance(id: \"d\", a: \"p\", b: \"q\", value: 1e-3)],\n)";
        let l = locate(text);
        assert_eq!(l.fields["dim"], Position { line: 3, column: 8 });
        assert_eq!(l.entities.len(), 2);
        assert_eq!(l.entities[0].start, Some(Position { line: 5, column: 5 }));
        assert_eq!(l.entities[0].fields["at"], Position { line: 5, column: 24 });
        assert_eq!(l.entities[1].start, Some(Position { line: 6, column: 13 }));
        assert_eq!(l.constraints.len(), 1);
        assert_eq!(l.constraints[0].fields["b"], Position { line: 8, column: 46 });
        assert_eq!(l.constraints[0].fields["value"], Position { line: 8, column: 58 });
    }

    #[test]
    fn never_fails_on_garbage() {
        for t in ["", "(", "System(entities: [", "]]]]", "r#\"", "\"unterminated", "/* /* */"] {
            let _ = locate(t);
        }
    }
}
