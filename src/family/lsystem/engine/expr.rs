//! Arithmetic and conditions inside rules: the tokens, the parser, and the
//! small stack programs the parser compiles them to.
//!
//! An expression is parsed once, its constant parts folded, and the rest
//! turned into a [`Expr`]: a constant, one variable, or a flat list of
//! stack operations. Derivations evaluate these millions of times, so the
//! common shapes (a number, a parameter passed on) skip the stack machine
//! altogether.
//!
//! Values are `f64`; comparisons and `&&`, `||`, `!` give 1 or 0, and a
//! value is true when it is not 0. Trigonometry is in degrees, as in ABOP.
//! Every operation checks that its result is a finite number, so a
//! division by zero or an overflow stops the derivation with a message
//! instead of drawing NaN.

use std::collections::BTreeMap;

use crate::rng::RandomStream;

/// Expressions nest at most this deep: deeper text is refused rather than
/// risking the parser's stack.
const MAX_DEPTH: usize = 64;

/// A syntax error: the column (1-based, in characters) and what was
/// expected there.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SyntaxError {
    pub(crate) column: usize,
    pub(crate) message: String,
}

impl SyntaxError {
    pub(crate) fn at(pos: usize, message: impl Into<String>) -> SyntaxError {
        SyntaxError {
            column: pos + 1,
            message: message.into(),
        }
    }
}

/// Why an evaluation stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum EvalError {
    /// A division by zero.
    DivisionByZero,
    /// An operation (named) gave NaN or an infinity.
    NotFinite(&'static str),
}

impl std::fmt::Display for EvalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EvalError::DivisionByZero => f.write_str("division by zero"),
            EvalError::NotFinite(what) => {
                write!(f, "{what} gives a result that is not a finite number")
            }
        }
    }
}

/// A compiled expression.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Expr {
    /// A number known when parsing.
    Const(f64),
    /// The value of a variable slot.
    Var(u16),
    /// Anything else: a stack program.
    Code(Box<[Op]>),
}

/// One stack operation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Op {
    Num(f64),
    Var(u16),
    Neg,
    Not,
    Bin(Bin),
    Fn1(Fn1),
    Fn2(Fn2),
    Rand,
    /// Pop; when false push 0 and jump (the right side of `&&` is skipped).
    JumpIfFalse(u32),
    /// Pop; when true push 1 and jump (the right side of `||` is skipped).
    JumpIfTrue(u32),
    /// Replace the top by 1 or 0.
    Truth,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Bin {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Fn1 {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sqrt,
    Abs,
    Exp,
    Ln,
    Log,
    Floor,
    Ceil,
    Round,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Fn2 {
    Atan2,
    Min,
    Max,
}

/// The functions, with their argument counts, as listed in messages.
const FUNCTIONS: &str = "sin cos tan asin acos atan atan2 sqrt abs exp ln log floor ceil \
                         round min max rand";

enum Function {
    One(Fn1),
    Two(Fn2),
    Rand,
}

fn function(name: &str) -> Option<Function> {
    use Function::{One, Two};
    Some(match name {
        "sin" => One(Fn1::Sin),
        "cos" => One(Fn1::Cos),
        "tan" => One(Fn1::Tan),
        "asin" => One(Fn1::Asin),
        "acos" => One(Fn1::Acos),
        "atan" => One(Fn1::Atan),
        "sqrt" => One(Fn1::Sqrt),
        "abs" => One(Fn1::Abs),
        "exp" => One(Fn1::Exp),
        "ln" => One(Fn1::Ln),
        "log" => One(Fn1::Log),
        "floor" => One(Fn1::Floor),
        "ceil" => One(Fn1::Ceil),
        "round" => One(Fn1::Round),
        "atan2" => Two(Fn2::Atan2),
        "min" => Two(Fn2::Min),
        "max" => Two(Fn2::Max),
        "rand" => Function::Rand,
        _ => return None,
    })
}

impl Fn1 {
    fn name(self) -> &'static str {
        match self {
            Fn1::Sin => "sin",
            Fn1::Cos => "cos",
            Fn1::Tan => "tan",
            Fn1::Asin => "asin",
            Fn1::Acos => "acos",
            Fn1::Atan => "atan",
            Fn1::Sqrt => "sqrt",
            Fn1::Abs => "abs",
            Fn1::Exp => "exp",
            Fn1::Ln => "ln",
            Fn1::Log => "log",
            Fn1::Floor => "floor",
            Fn1::Ceil => "ceil",
            Fn1::Round => "round",
        }
    }

    fn apply(self, x: f64) -> Result<f64, EvalError> {
        let r = match self {
            Fn1::Sin => x.to_radians().sin(),
            Fn1::Cos => x.to_radians().cos(),
            Fn1::Tan => x.to_radians().tan(),
            Fn1::Asin => x.asin().to_degrees(),
            Fn1::Acos => x.acos().to_degrees(),
            Fn1::Atan => x.atan().to_degrees(),
            Fn1::Sqrt => x.sqrt(),
            Fn1::Abs => x.abs(),
            Fn1::Exp => x.exp(),
            Fn1::Ln => x.ln(),
            Fn1::Log => x.log10(),
            Fn1::Floor => x.floor(),
            Fn1::Ceil => x.ceil(),
            Fn1::Round => x.round(),
        };
        finite(r, self.name())
    }
}

impl Fn2 {
    fn name(self) -> &'static str {
        match self {
            Fn2::Atan2 => "atan2",
            Fn2::Min => "min",
            Fn2::Max => "max",
        }
    }

    fn apply(self, a: f64, b: f64) -> Result<f64, EvalError> {
        let r = match self {
            Fn2::Atan2 => a.atan2(b).to_degrees(),
            Fn2::Min => a.min(b),
            Fn2::Max => a.max(b),
        };
        finite(r, self.name())
    }
}

impl Bin {
    fn name(self) -> &'static str {
        match self {
            Bin::Add => "'+'",
            Bin::Sub => "'-'",
            Bin::Mul => "'*'",
            Bin::Div => "'/'",
            Bin::Pow => "'^'",
            Bin::Lt => "'<'",
            Bin::Le => "'<='",
            Bin::Gt => "'>'",
            Bin::Ge => "'>='",
            Bin::Eq => "'=='",
            Bin::Ne => "'!='",
        }
    }

    fn apply(self, a: f64, b: f64) -> Result<f64, EvalError> {
        let truth = |c: bool| if c { 1.0 } else { 0.0 };
        let r = match self {
            Bin::Add => a + b,
            Bin::Sub => a - b,
            Bin::Mul => a * b,
            Bin::Div if b == 0.0 => return Err(EvalError::DivisionByZero),
            Bin::Div => a / b,
            Bin::Pow => a.powf(b),
            Bin::Lt => truth(a < b),
            Bin::Le => truth(a <= b),
            Bin::Gt => truth(a > b),
            Bin::Ge => truth(a >= b),
            Bin::Eq => truth(a == b),
            Bin::Ne => truth(a != b),
        };
        finite(r, self.name())
    }
}

fn finite(r: f64, what: &'static str) -> Result<f64, EvalError> {
    if r.is_finite() {
        Ok(r)
    } else {
        Err(EvalError::NotFinite(what))
    }
}

fn rand(a: f64, b: f64, rng: &mut RandomStream) -> Result<f64, EvalError> {
    finite(rng.range(a, b), "rand")
}

impl Expr {
    /// The value, with `vars` in the variable slots; `stack` is scratch
    /// space kept by the caller between calls.
    pub(crate) fn eval(
        &self,
        vars: &[f64],
        rng: &mut RandomStream,
        stack: &mut Vec<f64>,
    ) -> Result<f64, EvalError> {
        match self {
            Expr::Const(v) => Ok(*v),
            Expr::Var(k) => Ok(vars[usize::from(*k)]),
            Expr::Code(ops) => run(ops, vars, rng, stack),
        }
    }

    /// The value when it is known without evaluating.
    pub(crate) fn constant(&self) -> Option<f64> {
        match self {
            Expr::Const(v) => Some(*v),
            _ => None,
        }
    }
}

fn run(
    ops: &[Op],
    vars: &[f64],
    rng: &mut RandomStream,
    stack: &mut Vec<f64>,
) -> Result<f64, EvalError> {
    stack.clear();
    // The compiler only emits balanced programs; popping an empty stack
    // would be its defect, and gives NaN (refused below) rather than a panic.
    fn pop(stack: &mut Vec<f64>) -> f64 {
        stack.pop().unwrap_or(f64::NAN)
    }
    let mut pc = 0;
    while let Some(op) = ops.get(pc) {
        pc += 1;
        match *op {
            Op::Num(v) => stack.push(v),
            Op::Var(k) => stack.push(vars[usize::from(k)]),
            Op::Neg => {
                let a = pop(stack);
                stack.push(-a);
            }
            Op::Not => {
                let a = pop(stack);
                stack.push(if a == 0.0 { 1.0 } else { 0.0 });
            }
            Op::Truth => {
                let a = pop(stack);
                stack.push(if a != 0.0 { 1.0 } else { 0.0 });
            }
            Op::Bin(b) => {
                let y = pop(stack);
                let x = pop(stack);
                stack.push(b.apply(x, y)?);
            }
            Op::Fn1(f) => {
                let x = pop(stack);
                stack.push(f.apply(x)?);
            }
            Op::Fn2(f) => {
                let y = pop(stack);
                let x = pop(stack);
                stack.push(f.apply(x, y)?);
            }
            Op::Rand => {
                let b = pop(stack);
                let a = pop(stack);
                stack.push(rand(a, b, rng)?);
            }
            Op::JumpIfFalse(to) => {
                if pop(stack) == 0.0 {
                    stack.push(0.0);
                    pc = to as usize;
                }
            }
            Op::JumpIfTrue(to) => {
                if pop(stack) != 0.0 {
                    stack.push(1.0);
                    pc = to as usize;
                }
            }
        }
    }
    let r = pop(stack);
    finite(r, "the expression")
}

/// The tokens of expressions.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Tok {
    Num(f64),
    Name(String),
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LParen,
    RParen,
    Comma,
    Lt,
    Le,
    Gt,
    Ge,
    EqEq,
    Ne,
    AndAnd,
    OrOr,
    Bang,
    End,
    Other(char),
}

impl Tok {
    fn describe(&self) -> String {
        match self {
            Tok::Num(v) => format!("the number {v}"),
            Tok::Name(n) => format!("'{n}'"),
            Tok::Plus => "'+'".into(),
            Tok::Minus => "'-'".into(),
            Tok::Star => "'*'".into(),
            Tok::Slash => "'/'".into(),
            Tok::Caret => "'^'".into(),
            Tok::LParen => "'('".into(),
            Tok::RParen => "')'".into(),
            Tok::Comma => "','".into(),
            Tok::Lt => "'<'".into(),
            Tok::Le => "'<='".into(),
            Tok::Gt => "'>'".into(),
            Tok::Ge => "'>='".into(),
            Tok::EqEq => "'=='".into(),
            Tok::Ne => "'!='".into(),
            Tok::AndAnd => "'&&'".into(),
            Tok::OrOr => "'||'".into(),
            Tok::Bang => "'!'".into(),
            Tok::End => "the end".into(),
            Tok::Other(c) => format!("'{c}'"),
        }
    }
}

/// A position in rule text, read character by character (rules) or token
/// by token (expressions).
#[derive(Debug, Clone)]
pub(crate) struct Cursor<'a> {
    pub(crate) text: &'a [char],
    pub(crate) pos: usize,
}

impl<'a> Cursor<'a> {
    pub(crate) fn new(text: &'a [char]) -> Cursor<'a> {
        Cursor { text, pos: 0 }
    }

    pub(crate) fn peek(&self) -> Option<char> {
        self.text.get(self.pos).copied()
    }

    pub(crate) fn peek_at(&self, ahead: usize) -> Option<char> {
        self.text.get(self.pos + ahead).copied()
    }

    pub(crate) fn skip_space(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.pos += 1;
        }
    }

    /// The next token and where it starts, without consuming it.
    pub(crate) fn peek_token(&mut self) -> Result<(Tok, usize, usize), SyntaxError> {
        self.skip_space();
        let start = self.pos;
        let Some(c) = self.peek() else {
            return Ok((Tok::End, start, 0));
        };
        let two = |second: char, yes: Tok, no: Tok| {
            if self.peek_at(1) == Some(second) {
                (yes, 2)
            } else {
                (no, 1)
            }
        };
        let (tok, len) = match c {
            '+' => (Tok::Plus, 1),
            '-' => (Tok::Minus, 1),
            '*' => (Tok::Star, 1),
            '/' => (Tok::Slash, 1),
            '^' => (Tok::Caret, 1),
            '(' => (Tok::LParen, 1),
            ')' => (Tok::RParen, 1),
            ',' => (Tok::Comma, 1),
            '<' => two('=', Tok::Le, Tok::Lt),
            '>' => two('=', Tok::Ge, Tok::Gt),
            '=' => two('=', Tok::EqEq, Tok::Other('=')),
            '!' => two('=', Tok::Ne, Tok::Bang),
            '&' => two('&', Tok::AndAnd, Tok::Other('&')),
            '|' => two('|', Tok::OrOr, Tok::Other('|')),
            c if c.is_ascii_digit() || c == '.' => return self.number(start),
            c if is_name_start(c) => {
                let mut end = start + 1;
                while self.text.get(end).copied().is_some_and(is_name_char) {
                    end += 1;
                }
                let name: String = self.text[start..end].iter().collect();
                (Tok::Name(name), end - start)
            }
            c => (Tok::Other(c), 1),
        };
        Ok((tok, start, len))
    }

    fn number(&self, start: usize) -> Result<(Tok, usize, usize), SyntaxError> {
        let at = |i: usize| self.text.get(i).copied();
        let digits = |mut i: usize| {
            while at(i).is_some_and(|c| c.is_ascii_digit()) {
                i += 1;
            }
            i
        };
        let mut end = digits(start);
        if at(end) == Some('.') {
            end = digits(end + 1);
        }
        if matches!(at(end), Some('e' | 'E')) {
            let mut e = end + 1;
            if matches!(at(e), Some('+' | '-')) {
                e += 1;
            }
            if at(e).is_some_and(|c| c.is_ascii_digit()) {
                end = digits(e);
            }
        }
        let text: String = self.text[start..end].iter().collect();
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((Tok::Num(v), start, end - start)),
            _ => Err(SyntaxError::at(start, format!("'{text}' is not a number"))),
        }
    }

    /// The next token, consumed.
    pub(crate) fn token(&mut self) -> Result<(Tok, usize), SyntaxError> {
        let (tok, start, len) = self.peek_token()?;
        self.pos = start + len;
        Ok((tok, start))
    }
}

pub(crate) fn is_name_start(c: char) -> bool {
    c.is_ascii_alphabetic() || c == '_'
}

pub(crate) fn is_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// What names an expression may use.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scope<'a> {
    /// Variable names, by slot.
    pub(crate) vars: &'a [String],
    /// Named constants.
    pub(crate) constants: &'a BTreeMap<String, f64>,
    /// Whether `rand` may be called (not in a weight).
    pub(crate) rand: bool,
    /// Says what the names in `vars` are, for the unknown-name message.
    pub(crate) place: &'a str,
}

/// The parse tree, folded and then compiled.
#[derive(Debug, Clone)]
enum Node {
    Num(f64),
    Var(u16),
    Neg(Box<Node>),
    Not(Box<Node>),
    Bin(Bin, Box<Node>, Box<Node>, usize),
    And(Box<Node>, Box<Node>),
    Or(Box<Node>, Box<Node>),
    Fn1(Fn1, Box<Node>, usize),
    Fn2(Fn2, Box<Node>, Box<Node>, usize),
    Rand(Box<Node>, Box<Node>),
}

/// Parses one expression at the cursor, up to (not including) the first
/// token that cannot continue it, and compiles it.
pub(crate) fn parse(cursor: &mut Cursor<'_>, scope: &Scope<'_>) -> Result<Expr, SyntaxError> {
    let mut p = Parser {
        cursor,
        scope,
        depth: 0,
    };
    let node = p.or()?;
    let node = fold(node)?;
    Ok(compile(node))
}

struct Parser<'c, 'a, 's> {
    cursor: &'c mut Cursor<'a>,
    scope: &'s Scope<'s>,
    depth: usize,
}

impl Parser<'_, '_, '_> {
    fn peek(&mut self) -> Result<(Tok, usize), SyntaxError> {
        let (t, start, _) = self.cursor.peek_token()?;
        Ok((t, start))
    }

    fn next(&mut self) -> Result<(Tok, usize), SyntaxError> {
        self.cursor.token()
    }

    fn nest(&mut self, at: usize) -> Result<(), SyntaxError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(SyntaxError::at(
                at,
                format!("expression nested more than {MAX_DEPTH} deep"),
            ));
        }
        Ok(())
    }

    fn or(&mut self) -> Result<Node, SyntaxError> {
        let mut left = self.and()?;
        while self.peek()?.0 == Tok::OrOr {
            self.next()?;
            let right = self.and()?;
            left = Node::Or(Box::new(left), Box::new(right));
        }
        Ok(left)
    }

    fn and(&mut self) -> Result<Node, SyntaxError> {
        let mut left = self.comparison()?;
        while self.peek()?.0 == Tok::AndAnd {
            self.next()?;
            let right = self.comparison()?;
            left = Node::And(Box::new(left), Box::new(right));
        }
        Ok(left)
    }

    fn comparison(&mut self) -> Result<Node, SyntaxError> {
        let left = self.sum()?;
        let op = |t: &Tok| match t {
            Tok::Lt => Some(Bin::Lt),
            Tok::Le => Some(Bin::Le),
            Tok::Gt => Some(Bin::Gt),
            Tok::Ge => Some(Bin::Ge),
            Tok::EqEq => Some(Bin::Eq),
            Tok::Ne => Some(Bin::Ne),
            _ => None,
        };
        let (t, at) = self.peek()?;
        let Some(b) = op(&t) else {
            return Ok(left);
        };
        self.next()?;
        let right = self.sum()?;
        let (t, second) = self.peek()?;
        if op(&t).is_some() {
            return Err(SyntaxError::at(
                second,
                "comparisons do not chain: join them with '&&'",
            ));
        }
        Ok(Node::Bin(b, Box::new(left), Box::new(right), at))
    }

    fn sum(&mut self) -> Result<Node, SyntaxError> {
        let mut left = self.product()?;
        loop {
            let (t, at) = self.peek()?;
            let b = match t {
                Tok::Plus => Bin::Add,
                Tok::Minus => Bin::Sub,
                _ => return Ok(left),
            };
            self.next()?;
            let right = self.product()?;
            left = Node::Bin(b, Box::new(left), Box::new(right), at);
        }
    }

    fn product(&mut self) -> Result<Node, SyntaxError> {
        let mut left = self.unary()?;
        loop {
            let (t, at) = self.peek()?;
            let b = match t {
                Tok::Star => Bin::Mul,
                Tok::Slash => Bin::Div,
                _ => return Ok(left),
            };
            self.next()?;
            let right = self.unary()?;
            left = Node::Bin(b, Box::new(left), Box::new(right), at);
        }
    }

    fn unary(&mut self) -> Result<Node, SyntaxError> {
        let (t, at) = self.peek()?;
        match t {
            Tok::Minus | Tok::Plus | Tok::Bang => {
                self.next()?;
                self.nest(at)?;
                let inner = self.unary()?;
                self.depth -= 1;
                Ok(match t {
                    Tok::Minus => Node::Neg(Box::new(inner)),
                    Tok::Bang => Node::Not(Box::new(inner)),
                    _ => inner,
                })
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<Node, SyntaxError> {
        let base = self.primary()?;
        let (t, at) = self.peek()?;
        if t != Tok::Caret {
            return Ok(base);
        }
        self.next()?;
        // Right-associative, and the exponent may carry a sign: 2^-1.
        self.nest(at)?;
        let exponent = self.unary()?;
        self.depth -= 1;
        Ok(Node::Bin(Bin::Pow, Box::new(base), Box::new(exponent), at))
    }

    fn primary(&mut self) -> Result<Node, SyntaxError> {
        let (t, at) = self.next()?;
        match t {
            Tok::Num(v) => Ok(Node::Num(v)),
            Tok::LParen => {
                self.nest(at)?;
                let inner = self.or()?;
                self.depth -= 1;
                self.close(at, "to close the '(' at column")?;
                Ok(inner)
            }
            Tok::Name(name) => {
                if self.peek()?.0 == Tok::LParen {
                    return self.call(&name, at);
                }
                if let Some(k) = self.scope.vars.iter().position(|v| *v == name) {
                    // Slots are few (parameters of one production).
                    return Ok(Node::Var(k as u16));
                }
                if let Some(v) = self.scope.constants.get(&name) {
                    return Ok(Node::Num(*v));
                }
                Err(SyntaxError::at(
                    at,
                    format!(
                        "unknown name '{name}': expected {}, or a constant",
                        self.scope.place
                    ),
                ))
            }
            other => Err(SyntaxError::at(
                at,
                format!(
                    "expected a number, a name or '(', found {}",
                    other.describe()
                ),
            )),
        }
    }

    /// Expects `)`; `what` says what it closes, followed by the column of
    /// `open`.
    fn close(&mut self, open: usize, what: &str) -> Result<(), SyntaxError> {
        let (t, at) = self.next()?;
        if t == Tok::RParen {
            Ok(())
        } else {
            Err(SyntaxError::at(
                at,
                format!("expected ')' {what} {}, found {}", open + 1, t.describe()),
            ))
        }
    }

    fn call(&mut self, name: &str, at: usize) -> Result<Node, SyntaxError> {
        let Some(f) = function(name) else {
            return Err(SyntaxError::at(
                at,
                format!("unknown function '{name}': expected one of {FUNCTIONS}"),
            ));
        };
        let (_, open) = self.next()?; // the '('
        self.nest(open)?;
        let mut args = vec![self.or()?];
        while self.peek()?.0 == Tok::Comma {
            self.next()?;
            args.push(self.or()?);
        }
        self.depth -= 1;
        let wanted = match f {
            Function::One(_) => 1,
            Function::Two(_) | Function::Rand => 2,
        };
        let (t, end) = self.peek()?;
        if t == Tok::RParen && args.len() != wanted {
            return Err(SyntaxError::at(
                at,
                format!(
                    "{name} takes {wanted} argument{}, found {}",
                    if wanted == 1 { "" } else { "s" },
                    args.len()
                ),
            ));
        }
        if t != Tok::RParen {
            return Err(SyntaxError::at(
                end,
                format!(
                    "expected ',' or ')' to close the arguments of {name}, found {}",
                    t.describe()
                ),
            ));
        }
        self.next()?;
        let mut args = args.into_iter();
        let mut arg = || Box::new(args.next().unwrap_or(Node::Num(0.0)));
        Ok(match f {
            Function::One(f) => Node::Fn1(f, arg(), at),
            Function::Two(f) => {
                let (a, b) = (arg(), arg());
                Node::Fn2(f, a, b, at)
            }
            Function::Rand if !self.scope.rand => {
                return Err(SyntaxError::at(
                    at,
                    "rand is not allowed here: a weight is a fixed number",
                ))
            }
            Function::Rand => {
                let (a, b) = (arg(), arg());
                Node::Rand(a, b)
            }
        })
    }
}

/// Folds the constant parts of a tree; a constant part that is not a
/// finite number (`1/0`) is a syntax error at its operator.
fn fold(node: Node) -> Result<Node, SyntaxError> {
    let failed = |at: usize, e: EvalError| SyntaxError::at(at, e.to_string());
    Ok(match node {
        Node::Num(_) | Node::Var(_) => node,
        Node::Neg(a) => match fold(*a)? {
            Node::Num(v) => Node::Num(-v),
            a => Node::Neg(Box::new(a)),
        },
        Node::Not(a) => match fold(*a)? {
            Node::Num(v) => Node::Num(if v == 0.0 { 1.0 } else { 0.0 }),
            a => Node::Not(Box::new(a)),
        },
        Node::Bin(b, x, y, at) => match (fold(*x)?, fold(*y)?) {
            (Node::Num(x), Node::Num(y)) => Node::Num(b.apply(x, y).map_err(|e| failed(at, e))?),
            (x, y) => Node::Bin(b, Box::new(x), Box::new(y), at),
        },
        Node::And(x, y) => match (fold(*x)?, fold(*y)?) {
            (Node::Num(0.0), _) => Node::Num(0.0),
            (Node::Num(_), Node::Num(y)) => Node::Num(if y != 0.0 { 1.0 } else { 0.0 }),
            (x, y) => Node::And(Box::new(x), Box::new(y)),
        },
        Node::Or(x, y) => match (fold(*x)?, fold(*y)?) {
            (Node::Num(x), _) if x != 0.0 => Node::Num(1.0),
            (Node::Num(_), Node::Num(y)) => Node::Num(if y != 0.0 { 1.0 } else { 0.0 }),
            (x, y) => Node::Or(Box::new(x), Box::new(y)),
        },
        Node::Fn1(f, x, at) => match fold(*x)? {
            Node::Num(x) => Node::Num(f.apply(x).map_err(|e| failed(at, e))?),
            x => Node::Fn1(f, Box::new(x), at),
        },
        Node::Fn2(f, x, y, at) => match (fold(*x)?, fold(*y)?) {
            (Node::Num(x), Node::Num(y)) => Node::Num(f.apply(x, y).map_err(|e| failed(at, e))?),
            (x, y) => Node::Fn2(f, Box::new(x), Box::new(y), at),
        },
        Node::Rand(x, y) => Node::Rand(Box::new(fold(*x)?), Box::new(fold(*y)?)),
    })
}

fn compile(node: Node) -> Expr {
    match node {
        Node::Num(v) => Expr::Const(v),
        Node::Var(k) => Expr::Var(k),
        node => {
            let mut ops = Vec::new();
            emit(node, &mut ops);
            Expr::Code(ops.into_boxed_slice())
        }
    }
}

fn emit(node: Node, ops: &mut Vec<Op>) {
    match node {
        Node::Num(v) => ops.push(Op::Num(v)),
        Node::Var(k) => ops.push(Op::Var(k)),
        Node::Neg(a) => {
            emit(*a, ops);
            ops.push(Op::Neg);
        }
        Node::Not(a) => {
            emit(*a, ops);
            ops.push(Op::Not);
        }
        Node::Bin(b, x, y, _) => {
            emit(*x, ops);
            emit(*y, ops);
            ops.push(Op::Bin(b));
        }
        Node::Fn1(f, x, _) => {
            emit(*x, ops);
            ops.push(Op::Fn1(f));
        }
        Node::Fn2(f, x, y, _) => {
            emit(*x, ops);
            emit(*y, ops);
            ops.push(Op::Fn2(f));
        }
        Node::Rand(x, y) => {
            emit(*x, ops);
            emit(*y, ops);
            ops.push(Op::Rand);
        }
        Node::And(x, y) => short_circuit(*x, *y, ops, Op::JumpIfFalse),
        Node::Or(x, y) => short_circuit(*x, *y, ops, Op::JumpIfTrue),
    }
}

/// `x && y` or `x || y`: `y` is evaluated only when `x` does not decide.
fn short_circuit(x: Node, y: Node, ops: &mut Vec<Op>, jump: fn(u32) -> Op) {
    emit(x, ops);
    let at = ops.len();
    ops.push(jump(0));
    emit(y, ops);
    ops.push(Op::Truth);
    // Programs are short (one expression of one rule).
    ops[at] = jump(ops.len() as u32);
}
