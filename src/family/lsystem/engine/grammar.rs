//! Rule text: the axiom, the productions, the constants and the ignored
//! symbols of an L-system, read into the engine's alphabet and compiled
//! expressions.
//!
//! A production is one string (ABOP's notation):
//!
//! ```text
//! [left <] pred [> right] [: condition] arrow [(weight)] successor
//! ```
//!
//! - `arrow` is `->`, `→` or `=` (a lone `=` only when the rule has no
//!   `->` or `→`, so that a condition may still compare with `==`);
//! - `pred` is one module, with formal parameters `A(l, w)`;
//! - `left` is modules (`B(x)`), `right` modules and brackets (`C[D]E`);
//! - the weight is a number or an expression of constants;
//! - the successor is modules with parameter expressions, `F(l*0.7)`.
//!
//! A module is one character (not white space, `(`, `)` or `,`), with an
//! optional parameter list right after it. Modules with the same character
//! and a different number of parameters are different letters of the
//! alphabet; the alphabet has at most 256 letters, so a word stores one
//! byte per module.

use std::collections::BTreeMap;

use super::expr::{self, is_name_char, is_name_start, Cursor, Expr, Scope, SyntaxError, Tok};
use crate::error::{Error, Result};

/// The most parameters one module may have.
const MAX_ARITY: usize = 255;

/// The letters of a system: a character with its parameter count.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Alphabet {
    /// By id: the character and the parameter count.
    pub(crate) letters: Vec<(char, u8)>,
    index: BTreeMap<(char, u8), u8>,
}

impl Alphabet {
    /// The id of a letter, added if new.
    fn id(&mut self, c: char, arity: usize, at: usize) -> Result<u8, SyntaxError> {
        if arity > MAX_ARITY {
            return Err(SyntaxError::at(
                at,
                format!("{c} has {arity} parameters, more than {MAX_ARITY}"),
            ));
        }
        let key = (c, arity as u8);
        if let Some(&id) = self.index.get(&key) {
            return Ok(id);
        }
        let Ok(id) = u8::try_from(self.letters.len()) else {
            return Err(SyntaxError::at(
                at,
                "the system uses more than 256 different modules (a symbol with \
                 its number of parameters)",
            ));
        };
        self.letters.push(key);
        self.index.insert(key, id);
        Ok(id)
    }

    /// The id of a parameterless symbol, if the system uses it.
    pub(crate) fn find(&self, c: char) -> Option<u8> {
        self.index.get(&(c, 0)).copied()
    }

    pub(crate) fn len(&self) -> usize {
        self.letters.len()
    }

    pub(crate) fn arity(&self, id: u8) -> usize {
        usize::from(self.letters[usize::from(id)].1)
    }

    pub(crate) fn char(&self, id: u8) -> char {
        self.letters[usize::from(id)].0
    }
}

/// A sequence of modules to write: the axiom or a successor.
#[derive(Debug, Clone, Default)]
pub(crate) struct Successor {
    /// Module ids.
    pub(crate) syms: Vec<u8>,
    /// The parameter expressions, module after module.
    pub(crate) args: Vec<Expr>,
    /// Whether a `%` is among the modules.
    pub(crate) cuts: bool,
}

/// A module of a pattern (predecessor or context), with the first of the
/// variable slots its formal parameters bind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Formal {
    pub(crate) id: u8,
    pub(crate) slot: u16,
}

/// An item of a right context.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Pattern {
    Module(Formal),
    Open,
    Close,
}

/// One production, compiled.
#[derive(Debug, Clone)]
pub(crate) struct Production {
    /// Its index among the rules (for error fields).
    pub(crate) rule: usize,
    pub(crate) pred: Formal,
    /// The predecessor as written, for messages.
    pub(crate) pred_text: String,
    /// Left context, in text order (the nearest module last).
    pub(crate) left: Vec<Formal>,
    pub(crate) right: Vec<Pattern>,
    pub(crate) condition: Option<Expr>,
    /// The weight as written, when there is one (not yet normalised).
    pub(crate) weight: Option<f64>,
    pub(crate) successor: Successor,
    /// Number of variable slots (all formal parameters).
    pub(crate) slots: usize,
    /// Predecessor, context and condition without white space: productions
    /// with the same key are alternatives of one stochastic choice.
    pub(crate) key: String,
}

/// Everything parsed.
#[derive(Debug, Clone)]
pub(crate) struct Grammar {
    pub(crate) alphabet: Alphabet,
    pub(crate) axiom: Successor,
    pub(crate) productions: Vec<Production>,
    /// Which letters context matching passes over, by id.
    pub(crate) ignored: Vec<bool>,
}

/// Reads a whole system; errors name `{field}.axiom`, `{field}.rules[i]`,
/// `{field}.constants.NAME` or `{field}.ignore`.
pub(crate) fn parse(
    axiom: &str,
    rules: &[&str],
    constants: &BTreeMap<String, f64>,
    ignore: &str,
    field: &str,
) -> Result<Grammar> {
    for (name, value) in constants {
        let mut chars = name.chars();
        let is_name = chars.next().is_some_and(is_name_start) && chars.all(is_name_char);
        if !is_name {
            return Err(Error::invalid(
                format!("{field}.constants.{name}"),
                "is not a name: use letters, digits and '_', starting with a letter or '_'",
            ));
        }
        if !value.is_finite() {
            return Err(Error::invalid(
                format!("{field}.constants.{name}"),
                format!("must be a finite number, got {value}"),
            ));
        }
    }
    let mut alphabet = Alphabet::default();
    let located = |what: String| {
        move |e: SyntaxError| Error::invalid(what, format!("column {}: {}", e.column, e.message))
    };
    let mut productions = Vec::with_capacity(rules.len());
    for (i, text) in rules.iter().enumerate() {
        let p = production(text, i, constants, &mut alphabet)
            .map_err(located(format!("{field}.rules[{i}]")))?;
        productions.push(p);
    }
    let chars: Vec<char> = axiom.chars().collect();
    let scope = Scope {
        vars: &[],
        constants,
        rand: true,
        place: "a constant (the axiom has no parameters to use)",
    };
    let mut cursor = Cursor::new(&chars);
    let axiom =
        word(&mut cursor, &scope, &mut alphabet).map_err(located(format!("{field}.axiom")))?;
    let mut ignored = vec![false; alphabet.len()];
    for (i, c) in ignore.chars().enumerate() {
        if c.is_whitespace() {
            continue;
        }
        if c == '[' || c == ']' {
            return Err(Error::invalid(
                format!("{field}.ignore"),
                format!(
                    "column {}: brackets cannot be ignored: context matching follows them",
                    i + 1
                ),
            ));
        }
        for (id, &(letter, _)) in alphabet.letters.iter().enumerate() {
            if letter == c {
                ignored[id] = true;
            }
        }
    }
    Ok(Grammar {
        alphabet,
        axiom,
        productions,
        ignored,
    })
}

/// Where the arrow is: the first `->` or `→`, else the first `=` that is
/// not part of `==`, `<=`, `>=` or `!=`. Returns its position and length.
fn find_arrow(text: &[char]) -> Option<(usize, usize)> {
    let arrow = (0..text.len()).find_map(|i| match (text[i], text.get(i + 1)) {
        ('-', Some('>')) => Some((i, 2)),
        ('→', _) => Some((i, 1)),
        _ => None,
    });
    arrow.or_else(|| {
        (0..text.len()).find_map(|i| {
            let before = i.checked_sub(1).map(|b| text[b]);
            let lone = text[i] == '='
                && !matches!(before, Some('=' | '<' | '>' | '!'))
                && text.get(i + 1) != Some(&'=');
            lone.then_some((i, 1))
        })
    })
}

fn production(
    text: &str,
    rule: usize,
    constants: &BTreeMap<String, f64>,
    alphabet: &mut Alphabet,
) -> Result<Production, SyntaxError> {
    let chars: Vec<char> = text.chars().collect();
    let Some((arrow, arrow_len)) = find_arrow(&chars) else {
        return Err(SyntaxError::at(
            chars.len(),
            "expected an arrow ('->', '→' or '=') between the predecessor and the successor",
        ));
    };
    let lhs = &chars[..arrow];
    let mut names: Vec<String> = Vec::new();
    let mut cursor = Cursor::new(lhs);

    // Left context and predecessor.
    let (first, first_end) = items(&mut cursor, &mut names, alphabet)?;
    let (left, pred, pred_at, pred_end) = if cursor.peek() == Some('<') {
        cursor.pos += 1;
        if let Some(&(_, at)) = first.iter().find(|(i, _)| !matches!(i, Pattern::Module(_))) {
            return Err(SyntaxError::at(
                at,
                "a left context cannot contain brackets",
            ));
        }
        if first.is_empty() {
            return Err(SyntaxError::at(
                cursor.pos - 1,
                "expected the left context before '<'",
            ));
        }
        let left = first
            .iter()
            .filter_map(|(i, _)| match i {
                Pattern::Module(f) => Some(*f),
                _ => None,
            })
            .collect();
        let (second, end) = items(&mut cursor, &mut names, alphabet)?;
        let (pred, at) = one_predecessor(&second, &cursor)?;
        (left, pred, at, end)
    } else {
        let (pred, at) = one_predecessor(&first, &cursor)?;
        (Vec::new(), pred, at, first_end)
    };
    let pred_text: String = chars[pred_at..pred_end].iter().collect();

    // Right context.
    let mut right = Vec::new();
    if cursor.peek() == Some('>') {
        let gt = cursor.pos;
        cursor.pos += 1;
        let (items, _) = items(&mut cursor, &mut names, alphabet)?;
        if items.is_empty() {
            return Err(SyntaxError::at(gt, "expected the right context after '>'"));
        }
        let mut depth = 0usize;
        for &(item, at) in &items {
            match item {
                Pattern::Open => depth += 1,
                Pattern::Close if depth == 0 => {
                    return Err(SyntaxError::at(
                        at,
                        "']' closes no '[' in the right context",
                    ))
                }
                Pattern::Close => depth -= 1,
                Pattern::Module(_) => {}
            }
        }
        right = items.into_iter().map(|(i, _)| i).collect();
    }

    // Condition.
    let mut condition = None;
    match cursor.peek() {
        None => {}
        Some(':') => {
            cursor.pos += 1;
            let scope = Scope {
                vars: &names,
                constants,
                rand: true,
                place: "a parameter of the predecessor or its context",
            };
            let c = expr::parse(&mut cursor, &scope)?;
            let (t, at) = cursor.token()?;
            if t != Tok::End {
                let hint = if t == Tok::Other('=') {
                    " (compare with '==')"
                } else {
                    ""
                };
                return Err(SyntaxError::at(
                    at,
                    format!("expected an operator or the arrow after the condition{hint}"),
                ));
            }
            condition = Some(c);
        }
        Some(c) => {
            return Err(SyntaxError::at(
                cursor.pos,
                format!(
                    "expected '<', '>', ':' or the arrow after the predecessor {pred_text}, \
                     found '{c}' (a predecessor is one module)"
                ),
            ))
        }
    }
    let key: String = lhs.iter().filter(|c| !c.is_whitespace()).collect();

    // Weight and successor.
    let mut cursor = Cursor::new(&chars);
    cursor.pos = arrow + arrow_len;
    cursor.skip_space();
    let mut weight = None;
    if cursor.peek() == Some('(') {
        let open = cursor.pos;
        cursor.pos += 1;
        let scope = Scope {
            vars: &[],
            constants,
            rand: false,
            place: "a constant (a weight is a fixed number)",
        };
        let w = expr::parse(&mut cursor, &scope)?;
        let (t, at) = cursor.token()?;
        if t != Tok::RParen {
            return Err(SyntaxError::at(
                at,
                format!(
                    "expected ')' to close the weight opened at column {}",
                    open + 1
                ),
            ));
        }
        // Constants are folded: a weight is always known here.
        let w = w.constant().unwrap_or(f64::NAN);
        if !(w >= 0.0 && w.is_finite()) {
            return Err(SyntaxError::at(
                open + 1,
                format!("a weight must be a number ≥ 0, got {w}"),
            ));
        }
        weight = Some(w);
    }
    let scope = Scope {
        vars: &names,
        constants,
        rand: true,
        place: "a parameter of the predecessor or its context",
    };
    let successor = word(&mut cursor, &scope, alphabet)?;
    Ok(Production {
        rule,
        pred,
        pred_text,
        left,
        right,
        condition,
        weight,
        successor,
        slots: names.len(),
        key,
    })
}

/// The one module of `items` (the predecessor), and where it starts.
fn one_predecessor(
    items: &[(Pattern, usize)],
    cursor: &Cursor<'_>,
) -> Result<(Formal, usize), SyntaxError> {
    match items {
        [(Pattern::Module(f), at)] => Ok((*f, *at)),
        [] => Err(SyntaxError::at(cursor.pos, "expected a predecessor module")),
        [(Pattern::Module(_), _), (_, at), ..] => Err(SyntaxError::at(
            *at,
            "expected '<', '>', ':' or the arrow after the predecessor (a predecessor is \
             one module)",
        )),
        [(_, at), ..] => Err(SyntaxError::at(
            *at,
            "expected a predecessor module, found a bracket",
        )),
    }
}

/// Pattern items (modules with formal parameters, brackets) up to `<`,
/// `>`, `:` or the end of the left-hand side; also where the last item
/// ends.
fn items(
    cursor: &mut Cursor<'_>,
    names: &mut Vec<String>,
    alphabet: &mut Alphabet,
) -> Result<(Vec<(Pattern, usize)>, usize), SyntaxError> {
    let mut out = Vec::new();
    let mut end = cursor.pos;
    loop {
        cursor.skip_space();
        let at = cursor.pos;
        let Some(c) = cursor.peek() else { break };
        match c {
            '<' | '>' | ':' => break,
            '(' | ')' | ',' => {
                return Err(SyntaxError::at(
                    at,
                    format!("expected a module, found '{c}'"),
                ))
            }
            '[' | ']' => {
                cursor.pos += 1;
                if cursor.peek() == Some('(') {
                    return Err(SyntaxError::at(
                        cursor.pos,
                        format!("'{c}' takes no parameters"),
                    ));
                }
                out.push((
                    if c == '[' {
                        Pattern::Open
                    } else {
                        Pattern::Close
                    },
                    at,
                ));
            }
            _ => {
                cursor.pos += 1;
                let slot = names.len();
                let mut arity = 0;
                if cursor.peek() == Some('(') {
                    arity = formals(cursor, c, names)?;
                }
                let id = alphabet.id(c, arity, at)?;
                out.push((
                    Pattern::Module(Formal {
                        id,
                        slot: slot as u16,
                    }),
                    at,
                ));
            }
        }
        end = cursor.pos;
    }
    Ok((out, end))
}

/// Formal parameters `(a, b)` of module `c`, added to `names`; the cursor
/// is at the `(`.
fn formals(
    cursor: &mut Cursor<'_>,
    c: char,
    names: &mut Vec<String>,
) -> Result<usize, SyntaxError> {
    let open = cursor.pos;
    cursor.pos += 1;
    let mut count = 0;
    loop {
        let (t, at) = cursor.token()?;
        let Tok::Name(name) = t else {
            return Err(SyntaxError::at(
                at,
                format!(
                    "expected a parameter name of {c} (a formal parameter is a name), found {}",
                    describe(&t)
                ),
            ));
        };
        if names.contains(&name) {
            return Err(SyntaxError::at(
                at,
                format!("parameter '{name}' is named twice in the predecessor and its context"),
            ));
        }
        if names.len() >= usize::from(u16::MAX) {
            return Err(SyntaxError::at(at, "too many parameters"));
        }
        names.push(name);
        count += 1;
        let (t, at) = cursor.token()?;
        match t {
            Tok::Comma => {}
            Tok::RParen => return Ok(count),
            t => {
                return Err(SyntaxError::at(
                    at,
                    format!(
                        "expected ',' or ')' to close the parameters of {c} opened at column \
                         {}, found {}",
                        open + 1,
                        describe(&t)
                    ),
                ))
            }
        }
    }
}

fn describe(t: &Tok) -> String {
    match t {
        Tok::End => "the end".into(),
        Tok::Name(n) => format!("'{n}'"),
        Tok::Num(v) => format!("the number {v}"),
        Tok::Other(c) => format!("'{c}'"),
        _ => "an operator".into(),
    }
}

/// A word (axiom or successor): modules with parameter expressions, up to
/// the end of the text. Brackets `[ ]` and braces `{ }` must balance.
fn word(
    cursor: &mut Cursor<'_>,
    scope: &Scope<'_>,
    alphabet: &mut Alphabet,
) -> Result<Successor, SyntaxError> {
    let mut out = Successor::default();
    let mut open: Vec<(char, usize)> = Vec::new();
    loop {
        cursor.skip_space();
        let at = cursor.pos;
        let Some(c) = cursor.peek() else { break };
        cursor.pos += 1;
        match c {
            '(' => {
                let space = at > 0 && cursor.text[at - 1].is_whitespace();
                return Err(SyntaxError::at(
                    at,
                    if space {
                        "expected a module name before '(' (write the parameters right after \
                         the module, without a space)"
                    } else {
                        "expected a module name before '('"
                    },
                ));
            }
            ')' | ',' => {
                return Err(SyntaxError::at(
                    at,
                    format!("'{c}' outside a parameter list"),
                ))
            }
            '[' | '{' => open.push((c, at)),
            ']' | '}' => {
                let want = if c == ']' { '[' } else { '{' };
                match open.pop() {
                    Some((o, _)) if o == want => {}
                    Some((o, o_at)) => {
                        return Err(SyntaxError::at(
                            at,
                            format!(
                            "'{c}' closes the '{o}' at column {}: brackets and braces must nest",
                            o_at + 1
                        ),
                        ))
                    }
                    None => return Err(SyntaxError::at(at, format!("'{c}' closes no '{want}'"))),
                }
            }
            '%' => out.cuts = true,
            _ => {}
        }
        let mut arity = 0;
        if cursor.peek() == Some('(') {
            if matches!(c, '[' | ']' | '{' | '}' | '%') {
                return Err(SyntaxError::at(
                    cursor.pos,
                    format!("'{c}' takes no parameters"),
                ));
            }
            arity = arguments(cursor, c, scope, &mut out.args)?;
        }
        out.syms.push(alphabet.id(c, arity, at)?);
    }
    if let Some((c, at)) = open.pop() {
        let close = if c == '[' { ']' } else { '}' };
        return Err(SyntaxError::at(
            at,
            format!("'{c}' is not closed: expected a '{close}' after it"),
        ));
    }
    Ok(out)
}

/// Parameter expressions `(e1, e2)` of module `c`; the cursor is at `(`.
fn arguments(
    cursor: &mut Cursor<'_>,
    c: char,
    scope: &Scope<'_>,
    args: &mut Vec<Expr>,
) -> Result<usize, SyntaxError> {
    let open = cursor.pos;
    cursor.pos += 1;
    let mut count = 0;
    loop {
        let (t, at, _) = cursor.peek_token()?;
        if t == Tok::RParen || t == Tok::End || t == Tok::Comma {
            return Err(SyntaxError::at(
                at,
                format!(
                    "expected parameter {} of {c}, found {}",
                    count + 1,
                    describe_any(&t)
                ),
            ));
        }
        args.push(expr::parse(cursor, scope)?);
        count += 1;
        let (t, at) = cursor.token()?;
        match t {
            Tok::Comma => {}
            Tok::RParen => return Ok(count),
            Tok::End => {
                return Err(SyntaxError::at(
                    at,
                    format!("expected ')' to close the parameters of {c}"),
                ))
            }
            t => {
                let hint = if t == Tok::Other('=') {
                    " (compare with '==')"
                } else {
                    ""
                };
                return Err(SyntaxError::at(
                    at,
                    format!(
                        "expected ',' or ')' after parameter {count} of {c} (opened at column \
                         {}), found {}{hint}",
                        open + 1,
                        describe_any(&t)
                    ),
                ));
            }
        }
    }
}

fn describe_any(t: &Tok) -> String {
    match t {
        Tok::RParen => "')'".into(),
        Tok::Comma => "','".into(),
        t => describe(t),
    }
}
