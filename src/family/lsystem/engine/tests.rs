//! Tests of the L-system engine: rule text, derivation, and the turtle,
//! against systems whose results are known (ABOP's figures, counting
//! arguments, geometry).

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;
use proptest::prelude::*;

use super::{LSystem, Skeleton, Turtle, TurtleOptions, Word};
use crate::rng::Seed;

const FIELD: &str = "layers[0].lsystem[0]";

fn system_with(axiom: &str, rules: &[&str], constants: &[(&str, f64)], ignore: &str) -> LSystem {
    let constants: BTreeMap<String, f64> =
        constants.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    LSystem::parse(axiom, rules, &constants, ignore, FIELD)
        .unwrap_or_else(|e| panic!("{axiom} {rules:?}: {e}"))
}

fn system(axiom: &str, rules: &[&str]) -> LSystem {
    system_with(axiom, rules, &[], "")
}

fn derive(s: &LSystem, n: usize) -> Word {
    s.derive(n, &mut Seed(1).stream(), 50_000_000)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The message of the error `s` gives when derived `n` steps within a
/// budget of `max` modules.
fn derive_error(s: &LSystem, n: usize, max: usize) -> String {
    s.derive(n, &mut Seed(1).stream(), max)
        .unwrap_err()
        .to_string()
}

fn words(axiom: &str, rules: &[&str], n: usize) -> Vec<String> {
    words_of(&system(axiom, rules), n)
}

/// The words of `s` from its axiom through `n` steps.
fn words_of(s: &LSystem, n: usize) -> Vec<String> {
    let mut rng = Seed(1).stream();
    let mut w = s.axiom(&mut rng).unwrap();
    let mut out = vec![w.to_string()];
    for _ in 0..n {
        w = s.step(&w, &mut rng, 1_000_000).unwrap();
        out.push(w.to_string());
    }
    out
}

/// The error message of parsing (the whole `field: message` line).
fn parse_error(axiom: &str, rules: &[&str]) -> String {
    match LSystem::parse(axiom, rules, &BTreeMap::new(), "", FIELD) {
        Ok(_) => panic!("{axiom} {rules:?} parsed"),
        Err(e) => e.to_string(),
    }
}

fn draw(word: &Word, angle: f64) -> Skeleton {
    Turtle::new(TurtleOptions::DEFAULT.with_angle(angle))
        .interpret(word)
        .unwrap()
}

fn near(a: DVec3, b: DVec3) -> bool {
    a.distance(b) < 1e-9
}

fn drawn_length(s: &Skeleton) -> f64 {
    s.limbs
        .iter()
        .flat_map(|l| l.points.windows(2))
        .map(|w| w[0].distance(w[1]))
        .sum()
}

// ---- Derivation -------------------------------------------------------

#[test]
fn algae_lengths_are_fibonacci_numbers() {
    let s = system("A", &["A -> AB", "B -> A"]);
    let (mut a, mut b) = (1, 2);
    for n in 0..20 {
        assert_eq!(derive(&s, n).len(), a, "n = {n}");
        (a, b) = (b, a + b);
    }
    assert_eq!(derive(&s, 4).to_string(), "ABAABABA");
}

#[test]
fn fig_1_24a_has_five_to_the_n_segments() {
    let s = system("F", &["F -> F[+F]F[-F]F"]);
    for n in 0..7u32 {
        let w = derive(&s, n as usize);
        let f = 5usize.pow(n);
        assert_eq!(w.count('F'), f);
        // Each rewritten F adds two branches.
        assert_eq!(w.count('['), (f - 1) / 2);
        assert_eq!(w.count(']'), (f - 1) / 2);
        // Per rewritten F: two branches, a `+` and a `-`.
        assert_eq!(w.len(), f + (f - 1) + (f - 1) / 2);
        assert_eq!(w.iteration(), n as usize);
        let sk = draw(&w, 25.7);
        let segments: usize = sk.limbs.iter().map(|l| l.points.len() - 1).sum();
        assert_eq!(segments, f);
        assert!((drawn_length(&sk) - f as f64).abs() < 1e-6);
    }
}

#[test]
fn the_triangle_koch_curve_grows_by_four_thirds() {
    // ABOP fig. 1.7's generator on a line: F → F+F--F+F, δ = 60°, each
    // step a third as long; the curve keeps its ends.
    let s = system("F", &["F -> F+F--F+F"]);
    for n in 0..7 {
        let w = derive(&s, n);
        let sk = Turtle::new(
            TurtleOptions::DEFAULT
                .with_angle(60.0)
                .with_step(3f64.powi(-(n as i32))),
        )
        .interpret(&w)
        .unwrap();
        assert_eq!(sk.limbs.len(), 1);
        let len = drawn_length(&sk);
        assert!(
            (len - (4.0f64 / 3.0).powi(n as i32)).abs() < 1e-9,
            "n = {n}: {len}"
        );
        let end = *sk.limbs[0].points.last().unwrap();
        assert!(near(end, DVec3::Y), "{end}");
    }
}

#[test]
fn the_hilbert_curve_visits_every_cell_once() {
    let s = system("A", &["A -> +BF-AFA-FB+", "B -> -AF+BFB+FA-"]);
    for n in 1..7 {
        let sk = draw(&derive(&s, n), 90.0);
        assert_eq!(sk.limbs.len(), 1);
        let points = &sk.limbs[0].points;
        let side = 1i64 << n;
        assert_eq!(points.len() as i64, side * side);
        let cells: Vec<(i64, i64)> = points
            .iter()
            .map(|p| {
                assert!(p.z.abs() < 1e-9);
                let (x, y) = (p.x.round(), p.y.round());
                assert!((p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9, "{p}");
                (x as i64, y as i64)
            })
            .collect();
        let x0 = cells.iter().map(|c| c.0).min().unwrap();
        let y0 = cells.iter().map(|c| c.1).min().unwrap();
        let distinct: BTreeSet<(i64, i64)> = cells.iter().map(|&(x, y)| (x - x0, y - y0)).collect();
        assert_eq!(
            distinct.len() as i64,
            side * side,
            "n = {n}: a cell visited twice"
        );
        assert!(distinct.iter().all(|&(x, y)| x < side && y < side));
        // Unit steps between neighbours.
        assert!(points
            .windows(2)
            .all(|w| (w[0].distance(w[1]) - 1.0).abs() < 1e-9));
    }
}

#[test]
fn the_dragon_curve_ends_at_one_plus_i_to_the_n() {
    // ABOP fig. 1.10b. Each order is the previous one followed by its copy
    // turned a quarter left about its end: the end point, as a complex
    // number in (heading, left), is (1 + i)^n.
    let s = system("Fl", &["l -> l+rF+", "r -> -Fl-r"]);
    let (mut re, mut im) = (1.0f64, 0.0f64);
    for n in 0..14 {
        let sk = draw(&derive(&s, n), 90.0);
        let end = *sk.limbs.last().unwrap().points.last().unwrap();
        // Heading +y, left −x.
        let want = DVec3::new(-im, re, 0.0);
        assert!(near(end, want), "n = {n}: {end} ≠ {want}");
        (re, im) = (re - im, re + im);
    }
}

#[test]
fn stochastic_choices_follow_the_weights() {
    let axiom = "F".repeat(10_000);
    let s = system(&axiom, &["F ->(1) A", "F ->(3) B"]);
    let w = derive(&s, 1);
    let a = w.count('A') as f64;
    assert_eq!(w.count('A') + w.count('B'), 10_000);
    // Binomial(10 000, 1/4): σ ≈ 43.3.
    let sigma = (10_000.0f64 * 0.25 * 0.75).sqrt();
    assert!((a - 2500.0).abs() < 5.0 * sigma, "{a}");

    // Weights from constants, three ways, normalised.
    let s = system_with(
        &axiom,
        &["F ->(P) A", "F ->(P) B", "F ->(2*P) C"],
        &[("P", 0.1)],
        "",
    );
    let w = derive(&s, 1);
    let c = w.count('C') as f64;
    assert!((c - 5000.0).abs() < 5.0 * 50.0, "{c}");
}

#[test]
fn a_seed_decides_the_choices_and_no_choice_draws_nothing() {
    let s = system("F", &["F ->(1) F[+F]F", "F ->(1) F[-F]F"]);
    let run = |seed| {
        s.derive(4, &mut Seed(seed).stream(), 1_000_000)
            .unwrap()
            .to_string()
    };
    assert_eq!(run(3), run(3));
    assert_ne!(run(3), run(4));

    // A deterministic system leaves the stream where it was.
    let s = system("A", &["A -> AB", "B -> A", "C ->(1) D"]);
    let mut rng = Seed(9).stream();
    s.derive(10, &mut rng, 1_000_000).unwrap();
    assert_eq!(rng.next_u64(), Seed(9).stream().next_u64());
}

#[test]
fn abop_parametric_example_derives_as_in_the_book() {
    // ABOP §1.10.1.
    let got = words(
        "B(2)A(4,4)",
        &[
            "A(x,y) : y <= 3 -> A(x*2, x+y)",
            "A(x,y) : y > 3 -> B(x)A(x/y, 0)",
            "B(x) : x < 1 -> C",
            "B(x) : x >= 1 -> B(x-1)",
        ],
        4,
    );
    assert_eq!(
        got,
        [
            "B(2)A(4,4)",
            "B(1)B(4)A(1,0)",
            "B(0)B(3)A(2,1)",
            "CB(2)A(4,3)",
            "CB(1)A(8,7)",
        ]
    );
}

#[test]
fn a_production_applies_only_where_its_condition_holds() {
    let got = words(
        "A(0)",
        &["A(x) : x < 3 -> A(x+1)", "A(x) : x >= 3 -> B(x)"],
        5,
    );
    assert_eq!(got, ["A(0)", "A(1)", "A(2)", "A(3)", "B(3)", "B(3)"]);
    // `&&` does not evaluate its right side when the left is false.
    let got = words("A(0)A(0.25)A(1)", &["A(x) : x != 0 && 1/x > 2 -> B"], 1);
    assert_eq!(got[1], "A(0)BA(1)");
    // The first matching production wins.
    let got = words("A(5)", &["A(x) : x > 1 -> B", "A(x) -> C"], 1);
    assert_eq!(got[1], "B");
}

#[test]
fn expressions_follow_precedence_and_degrees() {
    let w = derive(
        &system(
            "A(2+3*4, -2^2, 2^3^2, (1+2)*3, 7-2-1, 8/2/2, sin(30), cos(60), atan2(1,1), \
             asin(1), min(3,1), max(3,1), log(1000), ln(1), exp(0), sqrt(16), abs(-2), \
             floor(2.7), ceil(2.2), round(2.5), 1<2 && 2<3, !(1>2), 1==2 || 2!=3, 2^-1, \
             1e3, .5)",
            &[],
        ),
        0,
    );
    let (_, p) = w.modules().next().unwrap();
    let want = [
        14.0, -4.0, 512.0, 9.0, 4.0, 2.0, 0.5, 0.5, 45.0, 90.0, 1.0, 3.0, 3.0, 0.0, 1.0, 4.0, 2.0,
        2.0, 3.0, 3.0, 1.0, 1.0, 1.0, 0.5, 1000.0, 0.5,
    ];
    assert_eq!(p.len(), want.len());
    for (k, (g, w)) in p.iter().zip(want).enumerate() {
        assert!((g - w).abs() < 1e-12, "parameter {k}: {g} ≠ {w}");
    }
}

#[test]
fn rand_draws_from_the_stream_within_its_range() {
    let s = system("A", &["A -> F(rand(1, 2))A"]);
    let w = derive(&s, 200);
    let values: Vec<f64> = w.modules().filter(|m| m.0 == 'F').map(|m| m.1[0]).collect();
    assert_eq!(values.len(), 200);
    assert!(values.iter().all(|v| (1.0..2.0).contains(v)));
    assert!(values.windows(2).any(|w| w[0] != w[1]));
    assert_eq!(derive(&s, 200).to_string(), w.to_string());
}

#[test]
fn constants_serve_the_axiom_and_the_rules() {
    let s = system_with(
        "A(L0, W0)",
        &["A(l, w) : l > MIN -> F(l)!(w)A(l*R, w*R)"],
        &[("L0", 10.0), ("W0", 2.0), ("R", 0.5), ("MIN", 2.0)],
        "",
    );
    assert_eq!(derive(&s, 0).to_string(), "A(10,2)");
    assert_eq!(
        derive(&s, 4).to_string(),
        "F(10)!(2)F(5)!(1)F(2.5)!(0.5)A(1.25,0.25)"
    );
    // A parameter shadows a constant of the same name.
    let s = system_with("A(1)", &["A(R) -> B(R)"], &[("R", 7.0)], "");
    assert_eq!(derive(&s, 1).to_string(), "B(1)");
}

#[test]
fn a_signal_travels_up_a_bracketed_string_one_step_a_derivation() {
    // ABOP §1.8 (fig. 1.31's signals): `b < a -> b` passes b on towards
    // the tips, `+ -` ignored; the left context skips whole branches and
    // climbs out of the current one.
    let s = system_with("b[+a]a[-a]a", &["b < a -> b", "b -> a"], &[], "+-");
    assert_eq!(
        words_of(&s, 3)[1..],
        ["a[+b]b[-a]a", "a[+a]a[-b]b", "a[+a]a[-a]a"]
    );

    // Without ignoring `+`, the branch's `a` sees `+` before it.
    let s = system("b[+a]a", &["b < a -> b", "b -> a"]);
    assert_eq!(derive(&s, 1).to_string(), "a[+a]b");
}

#[test]
fn a_signal_travels_down_with_right_context() {
    // Right context passes over branches the pattern does not name, and
    // does not leave the current branch.
    let s = system_with("a[+a]a[-a]b", &["a > b -> b", "b -> a"], &[], "+-");
    assert_eq!(words_of(&s, 2)[1..], ["a[+a]b[-a]a", "b[+a]a[-a]a"]);

    // A bracket in the pattern enters a branch.
    let s = system_with("A[+B]CA[+D]CA C", &["A > [B]C -> X"], &[], "+");
    assert_eq!(derive(&s, 1).to_string(), "X[+B]CA[+D]CAC");
    let s = system("A[B[E]D]C", &["A > [B]C -> X", "B > [E]D -> Y"]);
    assert_eq!(derive(&s, 1).to_string(), "X[Y[E]D]C");
}

#[test]
fn contexts_bind_parameters() {
    let s = system(
        "B(1)A(0.5)C(2)B(0)A(0.5)C(1)",
        &["B(x) < A(y) > C(z) : x + y > 1 -> A(x+y+z)"],
    );
    assert_eq!(derive(&s, 1).to_string(), "B(1)A(3.5)C(2)B(0)A(0.5)C(1)");
    // Two modules of left context, nearest last.
    let s = system("X(1)Y(2)A", &["X(a) Y(b) < A -> A(a*10+b)"]);
    assert_eq!(derive(&s, 1).to_string(), "X(1)Y(2)A(12)");
}

#[test]
fn cut_removes_the_rest_of_the_branch() {
    let s = system("F[A]F", &["A -> F%XY[Z]W"]);
    assert_eq!(derive(&s, 1).to_string(), "F[F%]F");
    // A cut at the top level of a successor inside a branch cuts the rest
    // of the word's branch; one inside the successor's own brackets only
    // that bracket.
    let s = system("F[AXY[Z]]W", &["A -> [B%C]%D"]);
    assert_eq!(derive(&s, 1).to_string(), "F[[B%]%]W");
    // The axiom is cut too, and the turtle ends the limb there.
    let s = system("F[+F%FF]F%F", &[]);
    let w = derive(&s, 0);
    assert_eq!(w.to_string(), "F[+F%]F%");
    let sk = draw(&w, 90.0);
    let limbs: Vec<(usize, bool)> = sk.limbs.iter().map(|l| (l.points.len(), l.tip)).collect();
    assert_eq!(limbs, [(3, true), (2, true)]);
}

#[test]
fn every_arrow_reads_the_same() {
    for rule in ["F -> F+F", "F→F+F", "F = F+F", "F->F + F"] {
        assert_eq!(
            derive(&system("F", &[rule]), 2).to_string(),
            "F+F+F+F",
            "{rule}"
        );
    }
    // `=` is the arrow only without `->` or `→`, so conditions compare.
    let got = words("A(1)A(0)", &["A(x) : x >= 1 && x == 1 = B"], 1);
    assert_eq!(got[1], "BA(0)");
    let got = words("A(1)A(0)", &["A(x) : x != 1 -> B(x == 0)"], 1);
    assert_eq!(got, ["A(1)A(0)", "A(1)B(1)"]);
}

#[test]
fn displayed_words_read_back() {
    let s = system_with("A(1/3, -0, 2e6)F[+G]", &[], &[], "");
    let text = derive(&s, 0).to_string();
    assert_eq!(text, "A(0.333333,0,2000000)F[+G]");
    let again = system(&text, &[]);
    assert_eq!(derive(&again, 0).to_string(), text);
}

// ---- Errors -----------------------------------------------------------

#[test]
fn syntax_errors_give_the_column() {
    let rule = |text: &str| parse_error("F", &[text]);
    let at = |text: &str, want: &str| {
        let e = rule(text);
        let expected = format!("{FIELD}.rules[0]: {want}");
        assert!(e.starts_with(&expected), "{text}\n→ {e}\nwanted {expected}");
    };
    at(
        "A(l, w) -> F(l)!(w)[+A(l*0.7",
        "column 29: expected ')' to close the parameters of A",
    );
    at(
        "A(l,w : l > 2 -> F",
        "column 7: expected ',' or ')' to close the parameters of A opened at column 2, found ':'",
    );
    at("F -> F[+F", "column 7: '[' is not closed");
    at("F -> F]", "column 7: ']' closes no '['");
    at("F -> {[}]", "column 8: '}' closes the '[' at column 7");
    at("A(x) : y > 1 -> B", "column 8: unknown name 'y'");
    at("F F", "column 4: expected an arrow");
    at(
        "AB -> C",
        "column 2: expected '<', '>', ':' or the arrow after the predecessor",
    );
    at(" -> C", "column 2: expected a predecessor module");
    at("A -> B(1/0)", "column 9: division by zero");
    at(
        "A -> B(sqrt(-1))",
        "column 8: sqrt gives a result that is not a finite number",
    );
    at(
        "F -> F(sin(1, 2))",
        "column 8: sin takes 1 argument, found 2",
    );
    at("F -> F(foo(1))", "column 8: unknown function 'foo'");
    at("F ->(x) F", "column 6: unknown name 'x'");
    at(
        "F ->(0.5 F",
        "column 10: expected ')' to close the weight opened at column 5",
    );
    at("F ->(-1) F", "column 6: a weight must be a number ≥ 0");
    at("F ->(rand(0,1)) F", "column 6: rand is not allowed here");
    at(
        "A(l) : l = 2 -> B",
        "column 10: expected an operator or the arrow after the condition (compare with '==')",
    );
    at(
        "A(l) : 1 < l < 2 -> B",
        "column 14: comparisons do not chain",
    );
    at("A(1) -> B", "column 3: expected a parameter name of A");
    at("A(x, x) -> B", "column 6: parameter 'x' is named twice");
    at(
        "[ -> B",
        "column 1: expected a predecessor module, found a bracket",
    );
    at(
        "A [B] < C -> D",
        "column 3: a left context cannot contain brackets",
    );
    at(
        "A > B] -> C",
        "column 6: ']' closes no '[' in the right context",
    );
    at(
        "F -> F (1)",
        "column 8: expected a module name before '(' (write the parameters",
    );
    at(
        "F -> F(1,)",
        "column 10: expected parameter 2 of F, found ')'",
    );
    at(
        "F -> F(1 2)",
        "column 10: expected ',' or ')' after parameter 1 of F",
    );
    at("F -> [(1)", "column 7: '[' takes no parameters");
    at(
        "F -> F(1.2.3)",
        "column 11: expected ',' or ')' after parameter 1 of F",
    );
    at(
        "F -> F(2 & 3)",
        "column 10: expected ',' or ')' after parameter 1 of F",
    );
    // The axiom and the other fields.
    let e = parse_error("A(1", &[]);
    assert!(
        e.starts_with(&format!("{FIELD}.axiom: column 4: expected ')'")),
        "{e}"
    );
    let e = parse_error("A(x)", &[]);
    assert!(
        e.starts_with(&format!("{FIELD}.axiom: column 3: unknown name 'x'")),
        "{e}"
    );
    let e = parse_error("F", &["F -> F", "G -> F[", "H -> G"]);
    assert!(e.starts_with(&format!("{FIELD}.rules[1]: column 7")), "{e}");
    let e = LSystem::parse("F", &[], &BTreeMap::new(), "+[", FIELD)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!("{FIELD}.ignore: column 2: brackets")),
        "{e}"
    );
    let bad: BTreeMap<String, f64> = [("2x".to_string(), 1.0)].into();
    let e = LSystem::parse("F", &[], &bad, "", FIELD)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!("{FIELD}.constants.2x: is not a name")),
        "{e}"
    );
    // Deep nesting is refused, not a stack overflow.
    let deep = format!("F -> F({}1{})", "(".repeat(10_000), ")".repeat(10_000));
    assert!(rule(&deep).contains("nested more than 64 deep"));
}

#[test]
fn alternatives_need_weights() {
    let e = parse_error("F", &["F -> A", "G -> B", "F -> C"]);
    assert!(
        e.starts_with(&format!(
            "{FIELD}.rules[2]: has the same predecessor, context and condition as rules[0]"
        )),
        "{e}"
    );
    let e = parse_error("F", &["F ->(0) A", "F ->(0) B"]);
    assert!(e.contains("add up to 0"), "{e}");
    // Different conditions are not alternatives.
    system("A(1)", &["A(x) : x > 0 -> B", "A(x) : x <= 0 -> C"]);
}

#[test]
fn runtime_errors_name_the_production_and_the_module() {
    let s = system("A(1,2)", &["B -> C", "A(x) -> A(x+1)"]);
    let e = derive_error(&s, 1, 1000);
    assert_eq!(
        e,
        format!(
            "{FIELD}.rules[1]: iteration 1: module A(1,2) (number 1 of the word) has 2 \
             parameters, but the predecessor A(x) of this production has 1"
        )
    );
    let s = system("FA(0)", &["A(x) -> A(1/x)"]);
    let e = derive_error(&s, 1, 1000);
    assert_eq!(
        e,
        format!(
            "{FIELD}.rules[0]: iteration 1: rewriting A(0) (module 2 of the word): parameter 1 \
             of A in the successor: division by zero"
        )
    );
    let s = system("A(1e200)", &["A(x) : x*x > 1 -> B"]);
    let e = derive_error(&s, 1, 1000);
    assert!(
        e.contains("the condition: '*' gives a result that is not a finite number"),
        "{e}"
    );
    // Known when parsing: a syntax error.
    let e = parse_error("A(1/0)", &[]);
    assert_eq!(e, format!("{FIELD}.axiom: column 4: division by zero"));
    // A word of one system cannot be rewritten by another.
    let (a, b) = (system("F", &[]), system("F", &[]));
    let w = derive(&a, 0);
    assert!(b.step(&w, &mut Seed(1).stream(), 10).is_err());
}

#[test]
fn budgets_refuse_before_the_work() {
    let s = system("F", &["F -> FFFFFFFFFF"]);
    let e = derive_error(&s, 4, 1000);
    assert_eq!(
        e,
        format!(
            "{FIELD}: iteration 4 would make 10000 modules, more than the limit of 1000: \
             lower the iterations"
        )
    );
    // 10^40 modules: refused from the count alone, nothing is allocated.
    let e = derive_error(&s, 40, 50_000_000);
    assert!(
        e.contains("iteration 8 would make 100000000 modules"),
        "{e}"
    );
    // Parameters count too.
    let s = system("A(1)", &["A(x) -> A(x)A(x)"]);
    let e = derive_error(&s, 12, 1000);
    assert!(e.contains("iteration 10 would make 1024 modules"), "{e}");
    // With a choice the size is known only as it grows: the step stops
    // at the limit.
    let s = system("F", &["F ->(1) FF", "F ->(1) FFF"]);
    let e = derive_error(&s, 30, 100);
    assert!(e.contains("makes more than 100 modules (the limit)"), "{e}");
    // The turtle's limit.
    let w = derive(&system("F", &["F -> F[+F]F[-F]F"]), 3);
    let e = Turtle::new(TurtleOptions::DEFAULT.with_max_segments(100))
        .interpret(&w)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        format!(
            "{FIELD}: the drawing has more than 100 segments, vertices and marks (the limit): \
             lower the iterations"
        )
    );
    let sk = Turtle::new(TurtleOptions::DEFAULT.with_max_segments(125))
        .interpret(&w)
        .unwrap();
    assert_eq!(
        sk.limbs.iter().map(|l| l.points.len() - 1).sum::<usize>(),
        125
    );
}

// ---- Turtle -----------------------------------------------------------

#[test]
fn plus_turns_left_seen_from_the_viewer() {
    let sk = draw(&derive(&system("FF+F-F", &[]), 0), 90.0);
    assert_eq!(sk.limbs.len(), 1);
    let want = [
        DVec3::ZERO,
        DVec3::Y,
        DVec3::new(0.0, 2.0, 0.0),
        DVec3::new(-1.0, 2.0, 0.0),
        DVec3::new(-1.0, 3.0, 0.0),
    ];
    assert_eq!(sk.limbs[0].points.len(), want.len());
    for (p, w) in sk.limbs[0].points.iter().zip(want) {
        assert!(near(*p, w), "{:?}", sk.limbs[0].points);
    }
}

#[test]
fn pitch_roll_and_turn_around_move_the_frame() {
    let end = |axiom: &str| {
        let sk = draw(&derive(&system(axiom, &[]), 0), 90.0);
        *sk.limbs.last().unwrap().points.last().unwrap()
    };
    // & pitches the heading down, towards −U = −z.
    assert!(near(end("F&F"), DVec3::new(0.0, 1.0, -1.0)));
    assert!(near(end("F^F"), DVec3::new(0.0, 1.0, 1.0)));
    // \ rolls L towards U: then + turns towards +z.
    assert!(near(end("F\\+F"), DVec3::new(0.0, 1.0, 1.0)));
    assert!(near(end("F/+F"), DVec3::new(0.0, 1.0, -1.0)));
    // | turns around.
    assert!(near(end("FF|F"), DVec3::Y));
    // A parameter is the angle in degrees, or the length in steps.
    assert!(near(end("+(90)F(2.5)"), DVec3::new(-2.5, 0.0, 0.0)));
}

#[test]
fn dollar_levels_the_left_vector() {
    let opts = TurtleOptions::DEFAULT.with_angle(33.0).with_marks("X");
    let mark = |axiom: &str| {
        let w = derive(&system(axiom, &[]), 0);
        Turtle::new(opts.clone()).interpret(&w).unwrap().marks[0]
    };
    let before = mark("&\\\\+&/X");
    let after = mark("&\\\\+&/$X");
    let left = |m: &super::Mark| m.up.cross(m.heading);
    assert!(left(&before).y.abs() > 0.1);
    assert!(left(&after).y.abs() < 1e-12, "{}", left(&after));
    // The heading stays, the frame stays right-handed and unit.
    assert!(near(before.heading, after.heading));
    assert!((after.up.length() - 1.0).abs() < 1e-12);
    assert!(after.up.dot(after.heading).abs() < 1e-12);
    // U is on the side of the sky.
    assert!(after.up.y >= 0.0);
}

#[test]
fn tropism_bends_branches_towards_its_direction() {
    let w = derive(&system("+(90)FFFFFFFF", &[]), 0);
    let plain = draw(&w, 90.0);
    let weeping = Turtle::new(TurtleOptions::DEFAULT.with_tropism(DVec3::new(0.0, -3.0, 0.0), 0.2))
        .interpret(&w)
        .unwrap();
    let end = |s: &Skeleton| *s.limbs[0].points.last().unwrap();
    assert!(near(end(&plain), DVec3::new(-8.0, 0.0, 0.0)));
    let e = end(&weeping);
    assert!(e.y < -2.0 && e.x > -8.0, "{e}");
    // Ever steeper: each step bends further down.
    let pts = &weeping.limbs[0].points;
    let slopes: Vec<f64> = pts.windows(2).map(|w| (w[1] - w[0]).y).collect();
    assert!(slopes.windows(2).all(|s| s[1] < s[0]), "{slopes:?}");
    // Steps keep their length.
    assert!((drawn_length(&weeping) - 8.0).abs() < 1e-9);
}

#[test]
fn an_axis_stays_one_limb_through_its_branches() {
    let sk = draw(&derive(&system("F[+F]F[-F[+F]]F", &[]), 0), 90.0);
    let summary: Vec<(usize, u32, bool)> = sk
        .limbs
        .iter()
        .map(|l| (l.points.len(), l.order, l.tip))
        .collect();
    // The axis (4 points, order 0, a tip), then its branches in the order
    // drawn; the `-F` branch has a branch at its end, so it is no tip.
    assert_eq!(
        summary,
        [(4, 0, true), (2, 1, true), (2, 1, false), (2, 2, true)]
    );
    assert!(near(sk.limbs[0].points[3], DVec3::new(0.0, 3.0, 0.0)));
    assert!(near(sk.limbs[1].points[1], DVec3::new(-1.0, 1.0, 0.0)));

    // A branch at the end of the axis: the axis is no tip.
    let sk = draw(&derive(&system("FF[+F]", &[]), 0), 90.0);
    assert_eq!(sk.limbs.len(), 2);
    assert!(!sk.limbs[0].tip && sk.limbs[1].tip);
    // Pen up, colour: new limbs.
    let sk = draw(&derive(&system("FfF'F", &[]), 0), 90.0);
    let colours: Vec<(usize, u32, bool)> = sk
        .limbs
        .iter()
        .map(|l| (l.points.len(), l.colour, l.tip))
        .collect();
    assert_eq!(colours, [(2, 0, true), (2, 0, false), (2, 1, true)]);
    let sk = draw(&derive(&system("F'(3)F'(3)F", &[]), 0), 90.0);
    let colours: Vec<u32> = sk.limbs.iter().map(|l| l.colour).collect();
    assert_eq!(colours, [0, 3]);
}

#[test]
fn widths_follow_bang() {
    let w = derive(&system("F!F!(0.25)F[!F]F", &[]), 0);
    let sk = Turtle::new(
        TurtleOptions::DEFAULT
            .with_width(2.0)
            .with_width_factor(0.5),
    )
    .interpret(&w)
    .unwrap();
    assert_eq!(sk.limbs[0].widths, [2.0, 2.0, 1.0, 0.25, 0.25]);
    assert_eq!(sk.limbs[1].widths, [0.125, 0.125]);
}

#[test]
fn braces_trace_polygons_not_limbs() {
    // Vertices from `.`, with G moving without one (ABOP's leaf).
    let sk = draw(&derive(&system("F{[+G.][G.][-G.]}", &[]), 0), 90.0);
    assert_eq!(sk.limbs.len(), 1);
    assert_eq!(sk.polygons.len(), 1);
    let want = [
        DVec3::new(-1.0, 1.0, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
    ];
    assert_eq!(sk.polygons[0].len(), 3);
    for (p, w) in sk.polygons[0].iter().zip(want) {
        assert!(near(*p, w), "{:?}", sk.polygons[0]);
    }
    // From the steps of F and f, starting where the first step starts; a
    // closing vertex on the first is dropped.
    let sk = draw(&derive(&system("{F+f+F+F}", &[]), 0), 90.0);
    assert!(sk.limbs.is_empty());
    assert_eq!(sk.polygons.len(), 1);
    assert_eq!(sk.polygons[0].len(), 4);
    // Fewer than three vertices: no polygon.
    assert!(draw(&derive(&system("{.F.}", &[]), 0), 90.0)
        .polygons
        .is_empty());
}

#[test]
fn marks_record_the_turtle_where_asked() {
    let w = derive(&system("F[+FL]F!L(2)K", &[]), 0);
    let sk = Turtle::new(TurtleOptions::DEFAULT.with_angle(90.0).with_marks("L"))
        .interpret(&w)
        .unwrap();
    assert_eq!(sk.marks.len(), 2);
    let (a, b) = (sk.marks[0], sk.marks[1]);
    assert_eq!((a.symbol, a.order, b.order), ('L', 1, 0));
    assert!(near(a.at, DVec3::new(-1.0, 1.0, 0.0)) && near(a.heading, DVec3::NEG_X));
    assert!(near(b.at, DVec3::new(0.0, 2.0, 0.0)) && (b.width - 0.7).abs() < 1e-12);
    assert!(near(b.up, DVec3::Z));
}

// ---- Robustness -------------------------------------------------------

fn rule_text() -> impl Strategy<Value = String> {
    let pieces = prop::sample::select(vec![
        "F", "f", "G", "A", "B", "x", "l", "(", ")", ",", "[", "]", "{", "}", "+", "-", "*", "/",
        "^", "&", "|", "!", "'", "%", "$", ".", "\\", "<", ">", ":", "=", "==", "->", "→", " ",
        "0", "1", "2.5", "1e9", "rand", "sin", "&&", "||", "K", "é", "\u{0}",
    ]);
    prop::collection::vec(pieces, 0..24).prop_map(|v| v.concat())
}

/// Rules that mostly parse: a predecessor, maybe a context and a
/// condition, an arrow, and random successor text.
fn likely_rule() -> impl Strategy<Value = String> {
    let lhs = prop::sample::select(vec![
        "F",
        "A(x)",
        "A(x,y)",
        "B < A(x)",
        "A(x) > [B]C",
        "F : 1",
        "A(x) : x > 1",
        "A(x) : rand(0,1) < 0.5",
        "+",
        "[",
        "B(y) < A(x) > C(z) : x+y+z > 0",
    ]);
    let arrow = prop::sample::select(vec![" -> ", " ->(0.5) ", "→", " = ", " ->(x) "]);
    (
        lhs,
        arrow,
        prop_oneof![1 => rule_text(), 6 => likely_word()],
    )
        .prop_map(|(l, a, r)| format!("{l}{a}{r}"))
}

/// Words that parse (with `x` a constant or a parameter).
fn likely_word() -> impl Strategy<Value = String> {
    let modules = prop::sample::select(vec![
        "F",
        "F(x)",
        "A(x+1)",
        "A(x,x)",
        "A(-x)",
        "B",
        "C(x)",
        "+",
        "-(x)",
        "&",
        "^",
        "\\",
        "/",
        "|",
        "$",
        "!",
        "!(x)",
        "'",
        "'(x)",
        "%",
        ".",
        "G",
        "f",
        "[+F]",
        "[A(x)%]",
        "{.F.f.}",
        "{[G.][-G.]}",
        "C(rand(0,x))",
        "A(1/x)",
        "X(x^x)",
        "A(x*1e300)",
    ]);
    prop::collection::vec(modules, 0..12).prop_map(|v| v.concat())
}

fn any_rule() -> impl Strategy<Value = String> {
    prop_oneof![1 => rule_text(), 6 => likely_rule()]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn no_text_makes_the_engine_panic(
        axiom in prop_oneof![rule_text(), likely_word()],
        rules in prop::collection::vec(any_rule(), 0..4),
        ignore in prop::sample::select(vec!["", "+-", "+-F", "F/\\&^", "["]),
        seed in 0u64..1000,
    ) {
        let rules: Vec<&str> = rules.iter().map(String::as_str).collect();
        let constants: BTreeMap<String, f64> = [("x".to_string(), 0.5)].into();
        if let Ok(s) = LSystem::parse(&axiom, &rules, &constants, ignore, "f") {
            let mut rng = Seed(seed).stream();
            if let Ok(w) = s.derive(3, &mut rng, 5000) {
                let _ = w.to_string();
                let options = TurtleOptions::DEFAULT.with_max_segments(5000).with_marks("AB");
                let _ = Turtle::new(options.with_tropism(DVec3::Y, 0.3)).interpret(&w);
            }
        }
    }

    #[test]
    fn well_formed_parametric_systems_run(
        a in -5.0f64..5.0,
        b in -5.0f64..5.0,
        op in prop::sample::select(vec!["+", "-", "*", "/", "^"]),
    ) {
        let rule = format!("A(x, y) : x {op} y > 0 -> F(x)[+A(x {op} y, y)]A(y, x)");
        let s = system_with("A(a0, b0)", &[&rule], &[("a0", a), ("b0", b)], "");
        // Overflow and division by zero are errors, never NaN in a word.
        if let Ok(w) = s.derive(6, &mut Seed(1).stream(), 100_000) {
            prop_assert!(w.modules().all(|(_, p)| p.iter().all(|v| v.is_finite())));
        }
    }
}

/// A render called off stops the rewriting and the drawing within a few
/// thousand modules: a word of millions is not waited out. Counted in
/// modules: the flag raised once the word has 8,192, both stop.
#[test]
fn rewriting_and_drawing_stop_when_the_render_is_called_off() {
    let simple = system("F", &["F -> FF"]);
    let general = system("F(1)", &["F(x) -> F(x)F(x)"]);
    for s in [&simple, &general] {
        let cancel = crate::cancel::Cancel::default();
        let _entered = cancel.enter();
        let word = derive(s, 13);
        assert_eq!(word.len(), 8192);
        cancel.raise();
        let stopped = s.step(&word, &mut Seed(1).stream(), 50_000_000);
        assert!(matches!(stopped, Err(crate::Error::Cancelled)), "{stopped:?}");
        let drawn = Turtle::new(TurtleOptions::DEFAULT).interpret(&word);
        assert!(matches!(drawn, Err(crate::Error::Cancelled)));
    }
}
