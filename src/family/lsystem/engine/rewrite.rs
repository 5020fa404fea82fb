//! Derivation: the [`LSystem`] (a parsed grammar with its productions
//! grouped for matching) rewrites a [`Word`] in parallel, step by step.
//!
//! A word is one byte per module (its letter in the system's alphabet)
//! plus, only for modules that have them, their parameters in one flat
//! list; a system without parameters never touches that list. Before a
//! step the engine counts the letters of the word and works out how long
//! the next word will be (exactly, when no choice, condition or context
//! is involved; otherwise at most), so that a runaway system is refused
//! before the memory is taken.
//!
//! Matching follows ABOP: productions are tried in the order written; the
//! first whose predecessor, context and condition match applies, and
//! productions sharing all three are the alternatives of a stochastic
//! choice, drawn by weight (no number is drawn when there is no choice).
//! A module no production matches is copied. Context skips the ignored
//! symbols; a left context passes over whole branches and climbs out of
//! the current one, a right context passes over branches the pattern does
//! not name and enters one when the pattern opens a bracket. After each
//! step, a `%` cuts the rest of its branch from the word.

use std::collections::BTreeMap;
use std::fmt;
use std::sync::Arc;

use super::expr::EvalError;
use super::grammar::{self, Alphabet, Formal, Pattern, Production, Successor};
use crate::error::{Error, Result};
use crate::rng::RandomStream;

/// Modules rewritten between two looks at whether the render was called
/// off (`crate::cancel::checkpoint`): some microseconds of work.
const CHECK_EVERY: usize = 4096;

/// An L-system: axiom, productions, constants and ignored symbols, parsed
/// and ready to derive.
///
/// ```
/// use std::collections::BTreeMap;
/// use moyo::lsystem::LSystem;
/// use moyo::Seed;
///
/// // ABOP's algae: the lengths are Fibonacci numbers.
/// let algae = LSystem::parse("A", &["A -> AB", "B -> A"], &BTreeMap::new(), "", "algae")?;
/// let word = algae.derive(5, &mut Seed(1).stream(), 1000)?;
/// assert_eq!(word.to_string(), "ABAABABAABAAB");
/// # Ok::<(), moyo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct LSystem {
    shared: Arc<Shared>,
    axiom: Successor,
    productions: Vec<Production>,
    groups: Vec<Group>,
    /// What to do with each letter.
    actions: Vec<Action>,
    /// Per letter: the most modules and parameters it can become, and
    /// whether that is exactly what it becomes.
    growth: Vec<Growth>,
    /// Every letter is copied or rewritten by one fixed successor without
    /// parameters: the next word is a concatenation of byte strings.
    simple: bool,
    /// Some production has a context.
    context: bool,
    /// Some successor (or the axiom) has a `%`.
    cuts: bool,
    /// Variable slots the largest production needs.
    slots: usize,
}

/// What the system and its words share: the alphabet and where errors go.
#[derive(Debug)]
pub(crate) struct Shared {
    pub(crate) alphabet: Alphabet,
    /// The caller's field: budget errors and the turtle's errors name it.
    pub(crate) field: String,
    /// `rules[i]` under the field, by rule.
    rule_fields: Vec<String>,
    ignored: Vec<bool>,
    open: Option<u8>,
    close: Option<u8>,
    cut: Option<u8>,
}

/// Productions with the same predecessor, context and condition: one is
/// drawn by weight.
#[derive(Debug, Clone)]
struct Group {
    members: Vec<usize>,
    /// Normalised running sums of the weights (the last is 1).
    cumulative: Vec<f64>,
}

#[derive(Debug, Clone)]
enum Action {
    Copy,
    /// One production, no context, no condition, no parameters in its
    /// successor.
    Fixed(usize),
    /// The groups to try, in order.
    Try(Vec<usize>),
    /// No production has this letter's parameter count, but one has its
    /// character: an error when met.
    Mismatch(usize),
}

#[derive(Debug, Clone, Copy, Default)]
struct Growth {
    modules: usize,
    params: usize,
    exact: bool,
}

/// A word of an L-system: modules with their parameters.
///
/// `Display` writes it in ABOP's notation, `F[+F]A(1.5,2)`, numbers
/// rounded to 6 decimals.
#[derive(Debug, Clone)]
pub struct Word {
    /// Letters (ids in the alphabet), one per module.
    pub(crate) syms: Vec<u8>,
    /// Parameters of the modules that have them, in order.
    pub(crate) params: Vec<f64>,
    pub(crate) shared: Arc<Shared>,
    iteration: usize,
}

impl LSystem {
    /// Parses a system. `productions` are the rules in ABOP's notation
    /// (`F -> F[+F]F`, `F ->(0.3) F[+F]`, `A(l) : l > 1 -> F(l)A(l/2)`,
    /// `B < A > C -> …`); `constants` may be used in every expression and
    /// in the axiom; `ignore` lists the symbols context matching passes
    /// over (ABOP's `#ignore`). Errors name `{field}.axiom`,
    /// `{field}.rules[i]`, `{field}.constants.NAME` or `{field}.ignore`,
    /// with the column in the text.
    ///
    /// # Errors
    /// [`Error::Invalid`] for a syntax error, an unknown name, unbalanced
    /// brackets or braces, or alternatives without weights.
    pub fn parse(
        axiom: &str,
        productions: &[&str],
        constants: &BTreeMap<String, f64>,
        ignore: &str,
        field: &str,
    ) -> Result<LSystem> {
        let g = grammar::parse(axiom, productions, constants, ignore, field)?;
        let rule_fields: Vec<String> = (0..productions.len())
            .map(|i| format!("{field}.rules[{i}]"))
            .collect();

        // Group the alternatives.
        let mut by_key: BTreeMap<&str, usize> = BTreeMap::new();
        let mut members: Vec<Vec<usize>> = Vec::new();
        for (i, p) in g.productions.iter().enumerate() {
            match by_key.get(p.key.as_str()) {
                Some(&k) => members[k].push(i),
                None => {
                    by_key.insert(&p.key, members.len());
                    members.push(vec![i]);
                }
            }
        }
        let mut groups = Vec::with_capacity(members.len());
        for m in members {
            let first = m[0];
            if m.len() > 1 && m.iter().any(|&i| g.productions[i].weight.is_none()) {
                return Err(Error::invalid(
                    &rule_fields[m[1]],
                    format!(
                        "has the same predecessor, context and condition as rules[{first}]: \
                         give each of them a weight, `->(0.5)`, to choose between them at \
                         random (or make them differ)"
                    ),
                ));
            }
            let weights: Vec<f64> = m
                .iter()
                .map(|&i| g.productions[i].weight.unwrap_or(1.0))
                .collect();
            let total: f64 = weights.iter().sum();
            if !(total > 0.0 && total.is_finite()) {
                return Err(Error::invalid(
                    &rule_fields[first],
                    "the weights of this production and its alternatives add up to 0: \
                     give at least one a weight above 0",
                ));
            }
            let mut sum = 0.0;
            let cumulative = weights
                .iter()
                .map(|w| {
                    sum += w;
                    sum / total
                })
                .collect();
            groups.push(Group {
                members: m,
                cumulative,
            });
        }

        let alphabet = &g.alphabet;
        let mut actions = Vec::with_capacity(alphabet.len());
        let mut growth = Vec::with_capacity(alphabet.len());
        for id in 0..alphabet.len() {
            let own: Vec<usize> = (0..groups.len())
                .filter(|&k| g.productions[groups[k].members[0]].pred.id as usize == id)
                .collect();
            let copy = Growth {
                modules: 1,
                params: alphabet.arity(id as u8),
                exact: true,
            };
            if own.is_empty() {
                let c = alphabet.char(id as u8);
                let other = g
                    .productions
                    .iter()
                    .position(|p| alphabet.char(p.pred.id) == c);
                actions.push(other.map_or(Action::Copy, Action::Mismatch));
                growth.push(copy);
                continue;
            }
            let plain =
                |p: &Production| p.left.is_empty() && p.right.is_empty() && p.condition.is_none();
            let mut most = Growth {
                modules: 0,
                params: 0,
                exact: true,
            };
            let mut lengths = Vec::new();
            for &k in &own {
                for &i in &groups[k].members {
                    let s = &g.productions[i].successor;
                    most.modules = most.modules.max(s.syms.len());
                    most.params = most.params.max(s.args.len());
                    lengths.push((s.syms.len(), s.args.len()));
                }
            }
            let first = &g.productions[groups[own[0]].members[0]];
            let certain = own.len() == 1 && plain(first);
            if !certain {
                // It may be copied when nothing matches.
                most.modules = most.modules.max(1);
                most.params = most.params.max(copy.params);
            }
            most.exact = certain && lengths.windows(2).all(|w| w[0] == w[1]);
            growth.push(most);
            actions.push(
                if certain && groups[own[0]].members.len() == 1 && first.successor.args.is_empty() {
                    Action::Fixed(groups[own[0]].members[0])
                } else {
                    Action::Try(own)
                },
            );
        }

        let cuts = g.axiom.cuts || g.productions.iter().any(|p| p.successor.cuts);
        let parametric = alphabet.letters.iter().any(|&(_, a)| a > 0);
        let simple = !parametric
            && !cuts
            && actions
                .iter()
                .all(|a| matches!(a, Action::Copy | Action::Fixed(_)));
        let context = g
            .productions
            .iter()
            .any(|p| !p.left.is_empty() || !p.right.is_empty());
        let slots = g.productions.iter().map(|p| p.slots).max().unwrap_or(0);
        let shared = Shared {
            open: alphabet.find('['),
            close: alphabet.find(']'),
            cut: alphabet.find('%'),
            alphabet: g.alphabet,
            field: field.to_string(),
            rule_fields,
            ignored: g.ignored,
        };
        Ok(LSystem {
            shared: Arc::new(shared),
            axiom: g.axiom,
            productions: g.productions,
            groups,
            actions,
            growth,
            simple,
            context,
            cuts,
            slots,
        })
    }

    /// The start word, its parameters evaluated (they may draw `rand`).
    ///
    /// # Errors
    /// [`Error::Invalid`] at `{field}.axiom` when a parameter is not a
    /// finite number.
    pub fn axiom(&self, rng: &mut RandomStream) -> Result<Word> {
        let mut word = Word {
            syms: self.axiom.syms.clone(),
            params: Vec::with_capacity(self.axiom.args.len()),
            shared: self.shared.clone(),
            iteration: 0,
        };
        let mut stack = Vec::new();
        for (k, arg) in self.axiom.args.iter().enumerate() {
            let v = arg.eval(&[], rng, &mut stack).map_err(|e| {
                let (module, p) = self.argument_of(&self.axiom, k);
                Error::invalid(
                    format!("{}.axiom", self.shared.field),
                    format!("parameter {p} of module {module}: {e}"),
                )
            })?;
            word.params.push(v);
        }
        if self.cuts {
            word.cut();
        }
        Ok(word)
    }

    /// The word after `n` derivation steps from the axiom.
    ///
    /// # Errors
    /// [`Error::Invalid`] when a word would have more than `max_modules`
    /// modules (or parameters), naming the step, before it is made; when
    /// an expression gives no finite number (at the production's field);
    /// when a module's parameter count differs from that of the
    /// production for its symbol.
    pub fn derive(&self, n: usize, rng: &mut RandomStream, max_modules: usize) -> Result<Word> {
        let mut word = self.axiom(rng)?;
        if word.len() > max_modules {
            return Err(Error::invalid(
                format!("{}.axiom", self.shared.field),
                format!(
                    "has {} modules, more than the limit of {max_modules}",
                    word.len()
                ),
            ));
        }
        for _ in 0..n {
            word = self.step(&word, rng, max_modules)?;
        }
        Ok(word)
    }

    /// One derivation step: every module of `word` rewritten at once.
    ///
    /// # Errors
    /// As [`LSystem::derive`]; also when `word` comes from another system.
    pub fn step(&self, word: &Word, rng: &mut RandomStream, max_modules: usize) -> Result<Word> {
        let shared = &self.shared;
        if !Arc::ptr_eq(&word.shared, shared) {
            return Err(Error::invalid(
                &shared.field,
                "the word to rewrite was derived by another L-system",
            ));
        }
        let iteration = word.iteration + 1;
        let (modules, params, exact) = self.next_size(word);
        if exact && (modules > max_modules as u128 || params > max_modules as u128) {
            let (n, what) = if modules > max_modules as u128 {
                (modules, "modules")
            } else {
                (params, "parameters")
            };
            return Err(Error::invalid(
                &shared.field,
                format!(
                    "iteration {iteration} would make {n} {what}, more than the limit of \
                     {max_modules}: lower the iterations"
                ),
            ));
        }
        // The exact size, or a guess below the bound (which may be far
        // above the truth when conditions decide); the step stops once the
        // word passes the limit.
        let cap = |n: u128, now: usize| {
            let guess = if exact {
                n
            } else {
                n.min(2 * now as u128 + 64)
            };
            guess.min(max_modules as u128) as usize
        };
        let mut out = Word {
            syms: Vec::with_capacity(cap(modules, word.syms.len())),
            params: Vec::with_capacity(cap(params, word.params.len())),
            shared: shared.clone(),
            iteration,
        };
        if self.simple {
            self.simple_step(word, &mut out)?;
        } else {
            self.general_step(word, &mut out, rng, max_modules)?;
        }
        if self.cuts {
            out.cut();
        }
        Ok(out)
    }

    /// The size of the next word: modules, parameters, and whether these
    /// are exact (otherwise they are upper bounds).
    fn next_size(&self, word: &Word) -> (u128, u128, bool) {
        let mut counts = [0u64; 256];
        for &s in &word.syms {
            counts[usize::from(s)] += 1;
        }
        let (mut modules, mut params, mut exact) = (0u128, 0u128, true);
        for (id, g) in self.growth.iter().enumerate() {
            let c = u128::from(counts[id]);
            modules += c * g.modules as u128;
            params += c * g.params as u128;
            exact &= c == 0 || g.exact;
        }
        (modules, params, exact)
    }

    fn simple_step(&self, word: &Word, out: &mut Word) -> Result<()> {
        // Each letter becomes a fixed byte string: itself or its successor.
        let mut table: Vec<&[u8]> = Vec::with_capacity(self.actions.len());
        let letters: Vec<u8> = (0..=255u8).collect();
        for (id, a) in self.actions.iter().enumerate() {
            table.push(match a {
                Action::Fixed(p) => &self.productions[*p].successor.syms,
                _ => &letters[id..=id],
            });
        }
        for chunk in word.syms.chunks(CHECK_EVERY) {
            crate::cancel::checkpoint()?;
            for &s in chunk {
                out.syms.extend_from_slice(table[usize::from(s)]);
            }
        }
        Ok(())
    }

    fn general_step(
        &self,
        word: &Word,
        out: &mut Word,
        rng: &mut RandomStream,
        max_modules: usize,
    ) -> Result<()> {
        let shared = &self.shared;
        let alphabet = &shared.alphabet;
        let structure = self.context.then(|| Structure::of(word));
        let mut vars = vec![0.0; self.slots];
        let mut stack = Vec::new();
        let mut at = 0;
        for (i, &s) in word.syms.iter().enumerate() {
            if i % CHECK_EVERY == 0 {
                crate::cancel::checkpoint()?;
            }
            let arity = alphabet.arity(s);
            let own = &word.params[at..at + arity];
            match &self.actions[usize::from(s)] {
                Action::Copy => {
                    out.syms.push(s);
                    out.params.extend_from_slice(own);
                }
                Action::Fixed(p) => out
                    .syms
                    .extend_from_slice(&self.productions[*p].successor.syms),
                Action::Try(groups) => {
                    let site = Site {
                        word,
                        index: i,
                        params: at,
                        structure: structure.as_ref(),
                    };
                    let applied = self.apply(groups, &site, &mut vars, &mut stack, rng, out)?;
                    if !applied {
                        out.syms.push(s);
                        out.params.extend_from_slice(own);
                    }
                }
                Action::Mismatch(p) => {
                    let p = &self.productions[*p];
                    return Err(Error::invalid(
                        &shared.rule_fields[p.rule],
                        format!(
                            "iteration {}: module {} (number {} of the word) has {arity} \
                             parameter{}, but the predecessor {} of this production has {}",
                            out.iteration,
                            word.module_text(s, own),
                            i + 1,
                            if arity == 1 { "" } else { "s" },
                            p.pred_text,
                            alphabet.arity(p.pred.id)
                        ),
                    ));
                }
            }
            at += arity;
            if out.syms.len() > max_modules || out.params.len() > max_modules {
                let what = if out.syms.len() > max_modules {
                    "modules"
                } else {
                    "parameters"
                };
                return Err(Error::invalid(
                    &shared.field,
                    format!(
                        "iteration {} makes more than {max_modules} {what} (the limit): lower \
                         the iterations",
                        out.iteration
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Tries the groups at a module; rewrites it into `out` and returns
    /// true when one applies.
    fn apply(
        &self,
        groups: &[usize],
        site: &Site<'_>,
        vars: &mut [f64],
        stack: &mut Vec<f64>,
        rng: &mut RandomStream,
        out: &mut Word,
    ) -> Result<bool> {
        for &k in groups {
            let group = &self.groups[k];
            let p = &self.productions[group.members[0]];
            site.bind(p.pred, site.index, vars);
            if !p.left.is_empty() && !site.left(&p.left, &self.shared, vars) {
                continue;
            }
            if !p.right.is_empty() && !site.right(&p.right, &self.shared, vars) {
                continue;
            }
            if let Some(c) = &p.condition {
                let holds = c
                    .eval(vars, rng, stack)
                    .map_err(|e| self.failure(site, out.iteration, p, "the condition", e))?;
                if holds == 0.0 {
                    continue;
                }
            }
            let chosen = if group.members.len() == 1 {
                p
            } else {
                let u = rng.unit();
                let k = group.cumulative.iter().position(|&c| u < c);
                &self.productions[group.members[k.unwrap_or(group.members.len() - 1)]]
            };
            let s = &chosen.successor;
            out.syms.extend_from_slice(&s.syms);
            for (n, arg) in s.args.iter().enumerate() {
                let v = arg.eval(vars, rng, stack).map_err(|e| {
                    let (module, p) = self.argument_of(s, n);
                    let what = format!("parameter {p} of {module} in the successor");
                    self.failure(site, out.iteration, chosen, &what, e)
                })?;
                out.params.push(v);
            }
            return Ok(true);
        }
        Ok(false)
    }

    fn failure(
        &self,
        site: &Site<'_>,
        iteration: usize,
        p: &Production,
        what: &str,
        e: EvalError,
    ) -> Error {
        let s = site.word.syms[site.index];
        let arity = self.shared.alphabet.arity(s);
        let own = &site.word.params[site.params..site.params + arity];
        Error::invalid(
            &self.shared.rule_fields[p.rule],
            format!(
                "iteration {iteration}: rewriting {} (module {} of the word): {what}: {e}",
                site.word.module_text(s, own),
                site.index + 1
            ),
        )
    }

    /// The module (its character) and the parameter number (from 1) of
    /// argument `n` of a successor.
    fn argument_of(&self, s: &Successor, n: usize) -> (char, usize) {
        let alphabet = &self.shared.alphabet;
        let mut before = 0;
        for &id in &s.syms {
            let a = alphabet.arity(id);
            if n < before + a {
                return (alphabet.char(id), n - before + 1);
            }
            before += a;
        }
        ('?', n + 1)
    }
}

/// The bracket structure of a word, for context matching: where each
/// bracket's partner is, and where each module's parameters start.
struct Structure {
    partner: Vec<usize>,
    params_at: Vec<usize>,
}

impl Structure {
    fn of(word: &Word) -> Structure {
        let shared = &word.shared;
        let n = word.syms.len();
        let mut partner = vec![usize::MAX; n];
        let mut params_at = Vec::with_capacity(n);
        let mut open = Vec::new();
        let mut at = 0;
        for (i, &s) in word.syms.iter().enumerate() {
            params_at.push(at);
            at += shared.alphabet.arity(s);
            if Some(s) == shared.open {
                open.push(i);
            } else if Some(s) == shared.close {
                if let Some(j) = open.pop() {
                    partner[i] = j;
                    partner[j] = i;
                }
            }
        }
        Structure { partner, params_at }
    }
}

/// A module being rewritten.
struct Site<'w> {
    word: &'w Word,
    index: usize,
    /// Where its parameters start.
    params: usize,
    structure: Option<&'w Structure>,
}

impl Site<'_> {
    /// Puts the parameters of module `j` into the slots of `formal`.
    fn bind(&self, formal: Formal, j: usize, vars: &mut [f64]) {
        let arity = self.word.shared.alphabet.arity(formal.id);
        if arity == 0 {
            return;
        }
        let at = if j == self.index {
            self.params
        } else {
            self.structure.map_or(0, |s| s.params_at[j])
        };
        let slot = usize::from(formal.slot);
        vars[slot..slot + arity].copy_from_slice(&self.word.params[at..at + arity]);
    }

    /// Whether the left context matches (binding its parameters): each
    /// pattern module, nearest first, against the modules towards the
    /// root, passing over ignored symbols and whole branches.
    fn left(&self, pattern: &[Formal], shared: &Shared, vars: &mut [f64]) -> bool {
        let Some(st) = self.structure else {
            return false;
        };
        let syms = &self.word.syms;
        let mut j = self.index;
        for f in pattern.iter().rev() {
            // The previous module on the path to the root.
            let found = loop {
                if j == 0 {
                    break None;
                }
                j -= 1;
                let s = syms[j];
                if Some(s) == shared.close {
                    // Pass over the whole branch; the loop steps past its '['.
                    if st.partner[j] != usize::MAX {
                        j = st.partner[j];
                    }
                } else if Some(s) == shared.open || shared.ignored[usize::from(s)] {
                    // Climb out of the current branch, or pass over.
                } else {
                    break Some(j);
                }
            };
            match found {
                Some(j) if syms[j] == f.id => self.bind(*f, j, vars),
                _ => return false,
            }
        }
        true
    }

    /// Whether the right context matches (binding its parameters).
    fn right(&self, pattern: &[Pattern], shared: &Shared, vars: &mut [f64]) -> bool {
        let Some(st) = self.structure else {
            return false;
        };
        let syms = &self.word.syms;
        let n = syms.len();
        let mut j = self.index + 1;
        let ignored = |s: u8| shared.ignored[usize::from(s)];
        for item in pattern {
            match *item {
                Pattern::Module(f) => {
                    // The next module on this branch, passing over ignored
                    // symbols and branches the pattern does not name.
                    while j < n {
                        let s = syms[j];
                        if Some(s) == shared.open && st.partner[j] != usize::MAX {
                            j = st.partner[j] + 1;
                        } else if ignored(s) {
                            j += 1;
                        } else {
                            break;
                        }
                    }
                    if j >= n || syms[j] != f.id {
                        return false;
                    }
                    self.bind(f, j, vars);
                    j += 1;
                }
                Pattern::Open => {
                    while j < n && ignored(syms[j]) {
                        j += 1;
                    }
                    if j >= n || Some(syms[j]) != shared.open {
                        return false;
                    }
                    j += 1;
                }
                Pattern::Close => {
                    // Past the end of the branch the pattern entered.
                    while j < n && Some(syms[j]) != shared.close {
                        if Some(syms[j]) == shared.open && st.partner[j] != usize::MAX {
                            j = st.partner[j];
                        }
                        j += 1;
                    }
                    if j >= n {
                        return false;
                    }
                    j += 1;
                }
            }
        }
        true
    }
}

impl Word {
    /// The number of modules.
    pub fn len(&self) -> usize {
        self.syms.len()
    }

    /// Whether the word has no module.
    pub fn is_empty(&self) -> bool {
        self.syms.is_empty()
    }

    /// How many derivation steps made it from the axiom (0 for the axiom).
    pub fn iteration(&self) -> usize {
        self.iteration
    }

    /// How many modules have the symbol `symbol` (with any number of
    /// parameters).
    pub fn count(&self, symbol: char) -> usize {
        let mut hit = [false; 256];
        for (id, &(c, _)) in self.shared.alphabet.letters.iter().enumerate() {
            hit[id] = c == symbol;
        }
        self.syms.iter().filter(|&&s| hit[usize::from(s)]).count()
    }

    /// The modules in order: each symbol with its parameters.
    pub fn modules(&self) -> impl Iterator<Item = (char, &[f64])> + '_ {
        let alphabet = &self.shared.alphabet;
        let mut at = 0;
        self.syms.iter().map(move |&s| {
            let a = alphabet.arity(s);
            let p = &self.params[at..at + a];
            at += a;
            (alphabet.char(s), p)
        })
    }

    /// One module in ABOP's notation.
    fn module_text(&self, s: u8, params: &[f64]) -> String {
        let mut text = String::new();
        push_module(&mut text, self.shared.alphabet.char(s), params);
        text
    }

    /// Removes, after each `%`, the rest of its branch (up to, not
    /// including, the `]` that closes it, or to the end of the word).
    fn cut(&mut self) {
        let shared = self.shared.clone();
        let Some(cut) = shared.cut else { return };
        if !self.syms.contains(&cut) {
            return;
        }
        let alphabet = &shared.alphabet;
        let (mut w, mut wp, mut rp) = (0, 0, 0);
        let mut i = 0;
        let n = self.syms.len();
        while i < n {
            let s = self.syms[i];
            let a = alphabet.arity(s);
            self.syms[w] = s;
            self.params.copy_within(rp..rp + a, wp);
            w += 1;
            wp += a;
            rp += a;
            i += 1;
            if s == cut {
                let mut depth = 0usize;
                while i < n {
                    let t = self.syms[i];
                    if Some(t) == shared.close {
                        if depth == 0 {
                            break;
                        }
                        depth -= 1;
                    } else if Some(t) == shared.open {
                        depth += 1;
                    }
                    rp += alphabet.arity(t);
                    i += 1;
                }
            }
        }
        self.syms.truncate(w);
        self.params.truncate(wp);
    }
}

fn push_module(text: &mut String, c: char, params: &[f64]) {
    text.push(c);
    if let Some((first, rest)) = params.split_first() {
        text.push('(');
        text.push_str(&number(*first));
        for p in rest {
            text.push(',');
            text.push_str(&number(*p));
        }
        text.push(')');
    }
}

/// A parameter for people: at most 6 decimals, no trailing zeros; huge
/// values with an exponent.
fn number(v: f64) -> String {
    if v.abs() >= 1e15 {
        return format!("{v:e}");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

impl fmt::Display for Word {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut text = String::new();
        for (c, params) in self.modules() {
            push_module(&mut text, c, params);
        }
        f.write_str(&text)
    }
}
