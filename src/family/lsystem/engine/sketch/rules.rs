//! The rules of a sketch: the branches `a` and `c` are rewritten into, with
//! their handles; the rule text (`a -> b(40) b(-40) c(30, 0, 0.7, 0.7) a`)
//! and its checks.

use crate::{Error, Result};

/// The three kinds of branch of the paper's rules.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The branch that follows the stroke: its direction comes from the
    /// stroke, not from its handle.
    A,
    /// A branch that does not grow: drawn once, never rewritten.
    B,
    /// A branch that grows: rewritten by `c`'s rule at every later step.
    C,
}

impl Kind {
    fn letter(self) -> char {
        match self {
            Kind::A => 'a',
            Kind::B => 'b',
            Kind::C => 'c',
        }
    }
}

/// Where and how a branch leaves its parent, relative to the parent's
/// frame (see the [module documentation](super) for the frames).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Handle {
    /// Branching angle from the parent's heading, degrees (−360–360):
    /// 0 goes straight on; positive leaves towards the side `roll` picks,
    /// negative towards the opposite side. Must be 0 for `a`.
    pub angle: f64,
    /// Roll about the parent's axis, degrees (−360–360): which side the
    /// branch leaves on. 0 is the parent's left (in the page, for a parent
    /// that lies in it with its up towards the viewer), 90 its up (towards
    /// the viewer), 180 its right. For `a`, the roll of the next `a`'s
    /// frame about the stroke: 180 puts the side branches of successive
    /// steps on alternate sides.
    pub roll: f64,
    /// Width as a ratio of the parent's (more than 0, at most 1.5).
    pub width: f64,
    /// Length as a ratio of the parent's (more than 0, at most 1.5). Must
    /// be 1 for `a`, whose length is the module.
    pub length: f64,
    /// Where along the parent the branch leaves: 0 at its base, 1 (the
    /// default) at its tip. Must be 1 for `a`.
    pub at: f64,
}

impl Handle {
    /// The handle of a branch whose text gives none of its numbers
    /// (the angle aside: see [`SketchRules::parse`]).
    const fn default_for(kind: Kind) -> Handle {
        let (width, length) = match kind {
            Kind::A => (1.0, 1.0),
            Kind::B => (0.5, 0.5),
            Kind::C => (0.7, 0.7),
        };
        Handle {
            angle: 0.0,
            roll: 0.0,
            width,
            length,
            at: 1.0,
        }
    }

    /// The value of handle number `slot` (in the text's order).
    fn slot(&mut self, slot: usize) -> &mut f64 {
        match slot {
            0 => &mut self.angle,
            1 => &mut self.roll,
            2 => &mut self.width,
            3 => &mut self.length,
            _ => &mut self.at,
        }
    }

    /// The first handle of a `kind` branch out of its range: its slot
    /// (in the text's order) and what is wrong.
    fn problem(&self, kind: Kind) -> Option<(usize, String)> {
        let angle = |name: &str, v: f64| {
            (!(-360.0..=360.0).contains(&v))
                .then(|| format!("{name} must be between -360 and 360 degrees, got {v}"))
        };
        let ratio = |name: &str, v: f64| {
            (!(v > 0.0 && v <= 1.5))
                .then(|| format!("{name} ratio must be more than 0 and at most 1.5, got {v}"))
        };
        let problems = [
            if kind == Kind::A && self.angle != 0.0 {
                Some(format!(
                    "`a` follows the stroke, so its angle must be 0, got {}: \
                     give its roll and width by name, e.g. `a(roll=180, width=0.95)`",
                    self.angle
                ))
            } else {
                angle("angle", self.angle)
            },
            angle("roll", self.roll),
            ratio("width", self.width),
            if kind == Kind::A && self.length != 1.0 {
                Some(format!(
                    "`a` is one module long, so its length ratio must be 1, got {}",
                    self.length
                ))
            } else {
                ratio("length", self.length)
            },
            if kind == Kind::A && self.at != 1.0 {
                Some(format!(
                    "`a` continues from the tip of the last, so its `at` must be 1, got {}",
                    self.at
                ))
            } else {
                (!(0.0..=1.0).contains(&self.at)).then(|| {
                    format!(
                        "at (where along the parent the branch leaves: 0 its base, \
                         1 its tip) must be between 0 and 1, got {}",
                        self.at
                    )
                })
            },
        ];
        problems
            .into_iter()
            .enumerate()
            .find_map(|(slot, p)| p.map(|p| (slot, p)))
    }
}

/// The names of the handles, in the text's order.
const NAMES: [&str; 5] = ["angle", "roll", "width", "length", "at"];

/// One branch of a rule: its kind and its handle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Branch {
    /// What the branch does at later steps.
    pub kind: Kind,
    /// How it leaves its parent.
    pub handle: Handle,
}

impl Branch {
    /// A branch with these handles, leaving from the parent's tip.
    pub fn new(kind: Kind, angle: f64, roll: f64, width: f64, length: f64) -> Branch {
        Branch {
            kind,
            handle: Handle {
                angle,
                roll,
                width,
                length,
                at: 1.0,
            },
        }
    }
}

/// The rules of a Sketching L-System: what `a` and `c` are rewritten
/// into, the module (stroke length per step) and the first `a`'s width.
#[derive(Debug, Clone, PartialEq)]
pub struct SketchRules {
    /// The rule of `a`: exactly one `a` (the continuation along the
    /// stroke) and any number of `b` and `c`.
    pub a: Vec<Branch>,
    /// The rule of `c`: any number of `b` and `c`, no `a`. The first `c`
    /// leaving from the tip (`at` = 1) continues its parent's limb.
    pub c: Vec<Branch>,
    /// Stroke length per rule application, mm (more than 0).
    pub module: f64,
    /// Width of the first `a`, mm (0 or more).
    pub width: f64,
    /// The field path that errors found while growing name (the budget,
    /// a stroke point that is not finite, a rule set in code out of
    /// range): [`parse`](Self::parse) sets it to its `field`,
    /// [`paper`](Self::paper) to `sketch`.
    pub field: String,
}

impl SketchRules {
    /// The paper's rules, `a → b, b, c, a` and `c → b, b, c`, with handles
    /// chosen so that the structure reads as a plant (its fig. 4's growth
    /// steps, drawn as a botanist would), all in the page plane: at every
    /// node a short leaflet on each side and a side branch that leaves at
    /// 55°, leafy in turn. The branch grows by one segment per module of
    /// stroke after its node, each 0.88 of the one before and turned 5°
    /// towards the stroke's end, so that it lengthens with the stroke
    /// still to come (the lowest branches are the longest) and sweeps
    /// upwards; it stops where a segment would be shorter than the pen
    /// allows ([`Sketch::with_pen`](super::Sketch::with_pen)). The side
    /// branches alternate sides from step to step (`a`'s roll 180), as
    /// the shoots of many plants do; the stroke thins by 0.97 per step.
    /// Leaflets are thin (a quarter to two fifths of their parent's
    /// width), so that a pen draws them as single strokes.
    ///
    /// ```text
    /// a -> b(40, 0, 0.25, 0.45) b(-40, 0, 0.25, 0.45) c(55, 0, 0.7, 0.7) a(0, 180, 0.97, 1)
    /// c -> b(50, 0, 0.4, 0.6) b(-50, 0, 0.4, 0.6) c(-5, 0, 0.9, 0.88)
    /// ```
    ///
    /// Module 8 mm, first width 1.5 mm.
    pub fn paper() -> SketchRules {
        use Kind::{A, B, C};
        SketchRules {
            a: vec![
                Branch::new(B, 40.0, 0.0, 0.25, 0.45),
                Branch::new(B, -40.0, 0.0, 0.25, 0.45),
                Branch::new(C, 55.0, 0.0, 0.7, 0.7),
                Branch::new(A, 0.0, 180.0, 0.97, 1.0),
            ],
            c: vec![
                Branch::new(B, 50.0, 0.0, 0.4, 0.6),
                Branch::new(B, -50.0, 0.0, 0.4, 0.6),
                Branch::new(C, -5.0, 0.0, 0.9, 0.88),
            ],
            module: 8.0,
            width: 1.5,
            field: "sketch".to_string(),
        }
    }

    /// Rules from their text, `a`'s and `c`'s, e.g.
    ///
    /// ```text
    /// a -> b(40, 0, 0.6, 0.5) b(-40, 0, 0.6, 0.5) c(30, 90, 0.7, 0.7) a(roll=180)
    /// c -> b b c(-15)
    /// ```
    ///
    /// A rule is its head (`a` or `c`), `->` (or `→`), then branches
    /// separated by spaces or commas. A branch is `a`, `b` or `c`,
    /// optionally with its handle in parentheses: up to five numbers in
    /// the order angle, roll (degrees), width ratio, length ratio, `at`,
    /// then any of them by name (`c(30, length=0.8)`, `b(at=0.5)`). What
    /// is left out has the default of its kind: roll 0, `at` 1, width and
    /// length ratios 0.5 for `b`, 0.7 for `c`, 1 for `a`; the angle of a
    /// `b` (a `c`) given none is 45° (30°) for the first such in the rule,
    /// −45° (−30°) for the second, and so on alternately, so that the
    /// paper's bare `a -> b b c a` spreads its leaflets both ways. `a`'s
    /// rule has exactly one `a`, whose angle must be 0, its length ratio
    /// and `at` 1; `c`'s rule has no `a`. Module 8 mm, first width 1.5 mm
    /// (set the fields to change them).
    ///
    /// # Errors
    /// [`Error::Invalid`] at `{field}.a` or `{field}.c`, the message
    /// starting `column N: ` (in characters, from 1), for text that does
    /// not parse or a handle out of its range (given in the message).
    pub fn parse(a_rule: &str, c_rule: &str, field: &str) -> Result<SketchRules> {
        Ok(SketchRules {
            a: parse_rule(a_rule, Kind::A, &format!("{field}.a"))?,
            c: parse_rule(c_rule, Kind::C, &format!("{field}.c"))?,
            field: field.to_string(),
            ..SketchRules::paper()
        })
    }

    /// `a`'s rule as text that [`parse`](Self::parse) reads back to the
    /// same branches.
    pub fn a_text(&self) -> String {
        rule_text('a', &self.a)
    }

    /// `c`'s rule as text that [`parse`](Self::parse) reads back to the
    /// same branches.
    pub fn c_text(&self) -> String {
        rule_text('c', &self.c)
    }

    /// Checks rules that may have been set in code: one `a` in `a`'s
    /// rule, none in `c`'s, every handle, the module and width in range.
    pub(crate) fn check(&self) -> Result<()> {
        let f = &self.field;
        for (name, rule, head) in [("a", &self.a, Kind::A), ("c", &self.c, Kind::C)] {
            let field = format!("{f}.{name}");
            let count = rule.iter().filter(|b| b.kind == Kind::A).count();
            if let Some(message) = a_count_problem(head, count) {
                return Err(Error::invalid(field, message));
            }
            for (i, b) in rule.iter().enumerate() {
                if let Some((_, message)) = b.handle.problem(b.kind) {
                    return Err(Error::invalid(
                        field,
                        format!("branch {} (`{}`): {message}", i + 1, b.kind.letter()),
                    ));
                }
            }
        }
        if !(self.module > 0.0 && self.module.is_finite()) {
            return Err(Error::invalid(
                format!("{f}.module"),
                format!("must be more than 0 mm (and finite), got {}", self.module),
            ));
        }
        if !(self.width >= 0.0 && self.width.is_finite()) {
            return Err(Error::invalid(
                format!("{f}.width"),
                format!("must be 0 mm or more (and finite), got {}", self.width),
            ));
        }
        Ok(())
    }
}

/// What is wrong with a rule of `head` holding `count` branches `a`.
fn a_count_problem(head: Kind, count: usize) -> Option<String> {
    match (head, count) {
        (Kind::A, 1) | (Kind::C, 0) => None,
        (Kind::A, n) => Some(format!(
            "`a`'s rule needs exactly one `a` (the branch that follows the stroke), found {n}"
        )),
        _ => {
            Some("`c`'s rule may not contain `a`: only `a`'s rule continues the stroke".to_string())
        }
    }
}

fn rule_text(head: char, rule: &[Branch]) -> String {
    let mut s = format!("{head} ->");
    for b in rule {
        let h = &b.handle;
        s.push_str(&format!(
            " {}({}, {}, {}, {}",
            b.kind.letter(),
            h.angle,
            h.roll,
            h.width,
            h.length
        ));
        if h.at != 1.0 {
            s.push_str(&format!(", {}", h.at));
        }
        s.push(')');
    }
    s
}

/// A branch as read, with the columns (0-based) its errors point at.
struct Read {
    branch: Branch,
    column: usize,
    /// Where each handle was given, by slot.
    given: [Option<usize>; 5],
}

/// A cursor over a rule's characters; errors name `field` and the column.
struct Cursor<'f> {
    chars: Vec<char>,
    pos: usize,
    field: &'f str,
}

impl Cursor<'_> {
    fn error(&self, at: usize, message: impl std::fmt::Display) -> Error {
        Error::invalid(self.field, format!("column {}: {message}", at + 1))
    }

    fn peek(&self) -> Option<char> {
        self.chars.get(self.pos).copied()
    }

    fn skip_space(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.pos += 1;
        }
    }

    /// What stands at the cursor, for messages.
    fn found(&self) -> String {
        match self.peek() {
            Some(c) => format!("`{c}`"),
            None => "the end of the rule".to_string(),
        }
    }

    fn expect(&mut self, c: char, what: &str) -> Result<()> {
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(self.error(self.pos, format!("expected {what}, found {}", self.found())))
        }
    }

    fn take_while(&mut self, keep: impl Fn(char) -> bool) -> String {
        let start = self.pos;
        while self.peek().is_some_and(&keep) {
            self.pos += 1;
        }
        self.chars[start..self.pos].iter().collect()
    }

    fn number(&mut self) -> Result<f64> {
        let start = self.pos;
        let text = self.take_while(|c| c.is_ascii_digit() || "+-.eE".contains(c));
        if text.is_empty() {
            return Err(self.error(start, format!("expected a number, found {}", self.found())));
        }
        text.parse()
            .map_err(|_| self.error(start, format!("`{text}` is not a number")))
    }

    /// The handle in parentheses after a branch letter (the cursor on
    /// `(`), into `read`.
    fn handle(&mut self, read: &mut Read) -> Result<()> {
        self.pos += 1;
        self.skip_space();
        if self.peek() == Some(')') {
            self.pos += 1;
            return Ok(());
        }
        let mut next = 0;
        let mut named = false;
        loop {
            self.skip_space();
            let start = self.pos;
            let slot = if self.peek().is_some_and(char::is_alphabetic) {
                let name = self.take_while(|c| c.is_alphanumeric() || c == '_');
                let slot = NAMES.iter().position(|&n| n == name).ok_or_else(|| {
                    self.error(
                        start,
                        format!("unknown handle `{name}` (angle, roll, width, length, at)"),
                    )
                })?;
                self.skip_space();
                self.expect('=', &format!("`=` after `{name}`"))?;
                named = true;
                slot
            } else if named {
                return Err(self.error(
                    start,
                    "expected a handle's name (a number by position cannot follow one by name)",
                ));
            } else if next == NAMES.len() {
                return Err(self.error(
                    start,
                    "a branch has at most 5 numbers: angle, roll, width, length, at",
                ));
            } else {
                next += 1;
                next - 1
            };
            if read.given[slot].is_some() {
                return Err(self.error(start, format!("`{}` is given twice", NAMES[slot])));
            }
            self.skip_space();
            read.given[slot] = Some(self.pos);
            *read.branch.handle.slot(slot) = self.number()?;
            self.skip_space();
            match self.peek() {
                Some(',') => self.pos += 1,
                Some(')') => {
                    self.pos += 1;
                    return Ok(());
                }
                _ => {
                    return Err(self.error(
                        self.pos,
                        format!("expected `,` or `)`, found {}", self.found()),
                    ))
                }
            }
        }
    }
}

/// The branches of a rule whose head must be `head`.
fn parse_rule(text: &str, head: Kind, field: &str) -> Result<Vec<Branch>> {
    let mut cur = Cursor {
        chars: text.chars().collect(),
        pos: 0,
        field,
    };
    cur.skip_space();
    if cur.peek() != Some(head.letter()) {
        return Err(cur.error(
            cur.pos,
            format!(
                "expected the rule's head `{h}` (`{h} -> …`), found {}",
                cur.found(),
                h = head.letter()
            ),
        ));
    }
    cur.pos += 1;
    cur.skip_space();
    match cur.peek() {
        Some('→') => cur.pos += 1,
        Some('-') if cur.chars.get(cur.pos + 1) == Some(&'>') => cur.pos += 2,
        _ => return Err(cur.error(cur.pos, format!("expected `->`, found {}", cur.found()))),
    }
    let mut read: Vec<Read> = Vec::new();
    loop {
        while cur.peek().is_some_and(|c| c.is_whitespace() || c == ',') {
            cur.pos += 1;
        }
        let column = cur.pos;
        let kind = match cur.peek() {
            None => break,
            Some('a') => Kind::A,
            Some('b') => Kind::B,
            Some('c') => Kind::C,
            Some(_) => {
                return Err(cur.error(
                    column,
                    format!("expected a branch (`a`, `b` or `c`), found {}", cur.found()),
                ))
            }
        };
        cur.pos += 1;
        let mut r = Read {
            branch: Branch {
                kind,
                handle: Handle::default_for(kind),
            },
            column,
            given: [None; 5],
        };
        let after = cur.pos;
        cur.skip_space();
        if cur.peek() == Some('(') {
            cur.handle(&mut r)?;
        } else if cur
            .chars
            .get(after)
            .is_some_and(|&c| !c.is_whitespace() && c != ',')
        {
            cur.pos = after;
            return Err(cur.error(
                cur.pos,
                format!("expected `(`, `,` or a space, found {}", cur.found()),
            ));
        }
        read.push(r);
    }
    // Unset angles alternate sides per kind, so that `b b` is a pair.
    for kind in [Kind::B, Kind::C] {
        let base = if kind == Kind::B { 45.0 } else { 30.0 };
        let unset = read
            .iter_mut()
            .filter(|r| r.branch.kind == kind && r.given[0].is_none());
        for (i, r) in unset.enumerate() {
            r.branch.handle.angle = if i % 2 == 0 { base } else { -base };
        }
    }
    let a_count = read.iter().filter(|r| r.branch.kind == Kind::A).count();
    if let Some(message) = a_count_problem(head, a_count) {
        // The second `a` of `a`'s rule (the end when there is none), the
        // first of `c`'s.
        let mut columns = read
            .iter()
            .filter(|r| r.branch.kind == Kind::A)
            .map(|r| r.column);
        let at = match head {
            Kind::A => columns.nth(1),
            _ => columns.next(),
        }
        .unwrap_or(cur.chars.len());
        return Err(cur.error(at, message));
    }
    for r in &read {
        if let Some((slot, message)) = r.branch.handle.problem(r.branch.kind) {
            return Err(cur.error(r.given[slot].unwrap_or(r.column), message));
        }
    }
    Ok(read.into_iter().map(|r| r.branch).collect())
}
