//! Presentation is exact: every presented component of every bundled
//! derivation (and of chain-3) expands back to the step's canonical value,
//! once the folded abbreviations are replaced by their definitions. The JSON
//! output relies on it (its `canonical` field is the value itself when a
//! step folds nothing).

use hdot_sym::derivation::{Derivation, load};
use hdot_sym::poly::Poly;

pub(crate) fn assert_exact(d: &Derivation) -> usize {
    let mut compared = 0;
    for s in &d.steps {
        let values = s.values();
        let presented = s.presented();
        assert_eq!(values.len(), presented.len(), "{}: {}", d.name, s.name);
        for (value, (c, e)) in values.into_iter().zip(&presented) {
            // An abbreviation's derivatives were folded too (ω̇_z): each
            // becomes the matching derivative of the definition.
            let expanded: Poly = e.to_poly().subst(&mut |a| {
                s.presentation
                    .fold
                    .iter()
                    .find(|(name, _)| a.base() == name.base() && a.order() >= name.order())
                    .map(|(name, def)| def.dt_n(a.order() - name.order()))
            });
            assert_eq!(
                &expanded, value,
                "{}: step {} component {c:?} does not expand back",
                d.name, s.name
            );
            compared += 1;
        }
    }
    compared
}

#[test]
fn every_presented_component_expands_to_its_value() {
    let dir = hdot_tests::repo_root().join("derivations");
    let mut compared = 0;
    let mut files = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml")
            && path.file_name().unwrap() != hdot_sym::course::MANIFEST_FILE
        {
            compared += assert_exact(&load(&path).unwrap());
            files += 1;
        }
    }
    compared += assert_exact(&hdot_sym::chain::derivation(3).unwrap());
    assert!(files >= 16, "only {files} derivation files");
    assert!(compared > 100, "only {compared} components compared");
}

/// Every bundled step's shown result, printed, compared with its printed
/// expectation after whitespace normalisation. The printer never reads
/// the expectation; this test only lists where the derived result's shape
/// (terms, factors, signs, order) differs from the textbook form written
/// in the file. Each remaining entry is argued in
/// docs/presentation.md ("Where the printed shape differs"); the list
/// here must equal the list there, so a fix or a regression shows up.
#[test]
fn printed_shape_matches_the_expectation_or_is_argued() {
    let dir = hdot_tests::repo_root().join("derivations");
    let mut entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| p.file_name().unwrap() != hdot_sym::course::MANIFEST_FILE)
        .collect();
    entries.sort();
    let norm = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut differ = Vec::new();
    for path in entries {
        let d = load(&path).unwrap();
        for s in d.steps.iter().filter(|s| s.show) {
            for c in &s.checks {
                let Some((_, e)) = s.components().iter().find(|(k, _)| *k == c.component) else {
                    continue;
                };
                let printed = norm(&hdot_sym::print::unicode(e));
                let expected = norm(&hdot_sym::print::unicode(&c.expected));
                if printed != expected {
                    let dot = if c.component.is_empty() { "" } else { "." };
                    differ.push(format!("{}: {}{dot}{}", d.name, s.name, c.component));
                }
            }
        }
    }
    let doc =
        std::fs::read_to_string(hdot_tests::repo_root().join("docs/presentation.md")).unwrap();
    let section = doc
        .split("## Where the printed shape differs")
        .nth(1)
        .expect("docs/presentation.md has a section `Where the printed shape differs`");
    let argued: Vec<String> = section
        .lines()
        .filter_map(|l| l.strip_prefix("- `"))
        .filter_map(|l| l.split('`').next())
        .map(str::to_owned)
        .collect();
    assert_eq!(
        differ, argued,
        "steps whose printed result differs in shape from the printed expectation \
         (left) against the entries argued in docs/presentation.md (right)"
    );
}

/// The printer never reads the expectation: writing an expectation in a
/// different order leaves the printed result unchanged.
#[test]
fn editing_an_expectation_leaves_the_printed_result_unchanged() {
    let text = |expect: &str| {
        format!(
            r#"
title = "t"
source = "written for this test"
[symbols]
constants = ["I_x", "I_y", "I_z"]
time = ["w_x", "w_y", "w_z"]
[[frame]]
name = "B"
angular_velocity = "[w_x, w_y, w_z]"
[[step]]
name = "M"
label = "Sigma M"
value = "dt_rel(principal(I_x, I_y, I_z) * angvel(B)) + cross(angvel(B), principal(I_x, I_y, I_z) * angvel(B))"
collect = ["w_x'", "w_y'", "w_z'", "w_x", "w_y", "w_z"]
expect = [{expect}]
"#
        )
    };
    let a = hdot_sym::derivation::load_str(
        "a.toml",
        &text(r#""I_x*w_x' - (I_y - I_z)*w_y*w_z", "I_y*w_y' - (I_z - I_x)*w_z*w_x", "I_z*w_z' - (I_x - I_y)*w_x*w_y""#),
    )
    .unwrap();
    let b = hdot_sym::derivation::load_str(
        "b.toml",
        &text(r#""w_z*w_y*I_z - w_y*w_z*I_y + I_x*w_x'", "w_z*w_x*I_x - I_z*w_z*w_x + I_y*w_y'", "I_y*w_x*w_y + w_z'*I_z - I_x*w_y*w_x""#),
    )
    .unwrap();
    assert!(a.all_hold() && b.all_hold());
    let show = |d: &hdot_sym::derivation::Derivation| {
        d.steps[0]
            .components()
            .iter()
            .map(|(_, e)| hdot_sym::print::unicode(e))
            .collect::<Vec<_>>()
    };
    assert_eq!(show(&a), show(&b));
}

/// Prints the shown components of a derivation written for a test.
fn printed(text: &str) -> Vec<String> {
    let d = hdot_sym::derivation::load_str("new.toml", text).unwrap_or_else(|e| panic!("{e}"));
    d.steps
        .iter()
        .filter(|s| s.show)
        .flat_map(|s| {
            s.components()
                .iter()
                .map(|(_, e)| hdot_sym::print::unicode(e))
        })
        .collect()
}

/// sin² θ or 1 − cos² θ, whichever gives the group fewer terms; constant
/// factors in conventional order (mass, inertia, gravity, lengths).
#[test]
fn new_problems_print_sin_squared_and_m_g_l() {
    let out = printed(
        r#"
title = "A gimbal and a pendulum, written for this test"
source = "test"
[symbols]
constants = ["Ip", "J", "m", "g", "l", "b"]
time = ["phi", "theta"]
[[step]]
name = "p"
value = "(J + Ip*sin(theta)^2)*phi'"
collect = ["phi'"]
[[step]]
name = "T"
value = "Ip*(theta'^2 + phi'^2*sin(theta)^2)/2"
collect = ["Ip"]
[[step]]
name = "M"
value = "l*g*m*sin(theta)"
"#,
    );
    assert_eq!(out[0], "(J + I′ sin² θ) φ\u{307}", "{out:?}");
    assert_eq!(out[1], "(1/2) I′ (φ\u{307}² sin² θ + θ\u{307}²)", "{out:?}");
    assert_eq!(out[2], "m g l sin θ", "{out:?}");
}

/// Euler-type differences in cyclic order, for symbols that are not the
/// bundled ones (J_1, J_2, J_3 and rates w_1, w_2, w_3).
#[test]
fn new_problems_print_euler_differences_in_cyclic_order() {
    let out = printed(
        r#"
title = "Euler's equations with other names, written for this test"
source = "test"
[symbols]
constants = ["J_1", "J_2", "J_3"]
time = ["w_1", "w_2", "w_3"]
[[frame]]
name = "B"
axes = ["1", "2", "3"]
angular_velocity = "[w_1, w_2, w_3]"
[[step]]
name = "M"
label = "Sigma M"
value = "dt_rel(principal(J_1, J_2, J_3) * angvel(B)) + cross(angvel(B), principal(J_1, J_2, J_3) * angvel(B))"
collect = ["w_1'", "w_2'", "w_3'", "w_1", "w_2", "w_3"]
"#,
    );
    assert_eq!(
        out,
        [
            "J_1 w\u{307}_1 − (J_2 − J_3) w_2 w_3",
            "J_2 w\u{307}_2 − (J_3 − J_1) w_3 w_1",
            "J_3 w\u{307}_3 − (J_1 − J_2) w_1 w_2"
        ]
    );
}

/// Rule 3 for a family of letters with one subscript: a platform's
/// moments A_q, B_q, C_q give Euler's differences in cyclic order, and
/// letters of different subscripts are not one family. A file written
/// for this test.
#[test]
fn new_problems_print_euler_differences_of_subscripted_letters() {
    let out = printed(
        r#"
title = "A platform's Euler equations, written for this test"
source = "test"
[symbols]
constants = ["A_q", "B_q", "C_q", "B_r"]
time = ["u_x", "u_y", "u_z"]
[[frame]]
name = "Q"
angular_velocity = "[u_x, u_y, u_z]"
[[step]]
name = "M"
label = "Sigma M"
value = "dt(principal(A_q, B_q, C_q)*angvel(Q))"
collect = ["u_x'", "u_y'", "u_z'", "u_x", "u_y", "u_z"]
[[step]]
name = "other"
value = "(A_q - B_r)*u_x*u_y"
"#,
    );
    assert_eq!(
        out,
        [
            "A_q u\u{307}_x − (B_q − C_q) u_y u_z",
            "B_q u\u{307}_y − (C_q − A_q) u_z u_x",
            "C_q u\u{307}_z − (A_q − B_q) u_x u_y",
            "(A_q − B_r) u_x u_y",
        ]
    );
}

/// A known factor prints as the file writes it, and needs no `collect`;
/// a constant rate named by a Greek letter groups a bracket like a rate
/// (J s + (C − A) Ω), and a difference of the letters A, B, C takes its
/// sign from the cyclic order alone. A gyrostat's stability and a
/// governor, written for this test.
#[test]
fn new_problems_print_known_factors_as_written() {
    let out = printed(
        r#"
title = "A gyrostat and a governor, written for this test"
source = "test"
[symbols]
constants = ["A", "B", "C", "K", "q", "Lambda", "P", "Q"]
time = ["e_1", "e_2", "u"]
[[step]]
name = "k"
value = "(K*q + (C - A)*Lambda)*(K*q + (C - B)*Lambda)*e_1/(A*B)"
factor = ["K*q + (C - A)*Lambda", "K*q + (C - B)*Lambda"]
[[step]]
name = "lin"
value = "B*e_2' - (K*q + (C - A)*Lambda)*e_1"
collect = ["e_2'", "e_1"]
factor = ["K*q + (C - A)*Lambda"]
[[step]]
name = "grouped"
value = "(K*q + (C - A)*Lambda)*e_1"
[[step]]
name = "negative"
value = "B*e_2' - (K*q + (C - A)*Lambda)*e_1"
collect = ["e_2'", "e_1"]
[[step]]
name = "M"
value = "P*u'' - (P - Q)*Lambda^2*sin(u)*cos(u)"
factor = ["P - Q"]
"#,
    );
    assert_eq!(
        out,
        [
            "(K q + (C − A) Λ) (K q + (C − B) Λ) e_1/(A B)",
            "B e\u{307}_2 − (K q + (C − A) Λ) e_1",
            "(K q + (C − A) Λ) e_1",
            "B e\u{307}_2 − (K q + (C − A) Λ) e_1",
            "P u\u{308} − (P − Q) Λ² sin u cos u",
        ]
    );
}

/// A solved form is distributed over its sum when its terms have
/// different constant divisors (the divisor cancelled in some), each term
/// with its own constant ratio; a divisor every term shares, or one that
/// holds sin θ, stays under the bracket. A spherical pendulum with a rod
/// of moment J about the pivot, written for this test.
#[test]
fn new_problems_print_solved_forms_term_by_term() {
    let out = printed(
        r#"
title = "A spherical pendulum, written for this test"
source = "test"
[symbols]
constants = ["J", "m", "g", "l", "F", "G"]
time = ["phi", "theta", "x"]
[[step]]
name = "T"
value = "J*(theta'^2 + phi'^2*sin(theta)^2)/2"
show = false
[[step]]
name = "V"
value = "-l*g*m*cos(theta)"
show = false
[[step]]
name = "L"
value = "lagrange(T, V, [phi, theta])"
show = false
[[step]]
name = "acc"
value = "solve(L, [phi'', theta''])"
[[step]]
name = "push"
value = "solve(J*x'' - F - G, [x''])"
[[step]]
name = "both"
value = "F*x'/J - F*x'/m"
"#,
    );
    assert_eq!(
        out,
        [
            "−2 φ\u{307} θ\u{307} cos θ/sin θ",
            "φ\u{307}² sin θ cos θ − (m g l/J) sin θ",
            "(F + G)/J",
            "F (m − J) x\u{307}/(m J)",
        ]
    );
}

/// The shown components of a derivation written for a test, in LaTeX.
fn printed_latex(text: &str) -> Vec<String> {
    let d = hdot_sym::derivation::load_str("new.toml", text).unwrap_or_else(|e| panic!("{e}"));
    d.steps
        .iter()
        .filter(|s| s.show)
        .flat_map(|s| {
            s.components()
                .iter()
                .map(|(_, e)| hdot_sym::print::latex(e))
        })
        .collect()
}

/// A fraction is written as a textbook writes it: a rational coefficient
/// goes numerator to numerator and denominator to denominator
/// (5 P²/(2 M), never (5/2) P²/M or a fraction inside a fraction), and a
/// numerator that is one sum is not bracketed under a LaTeX fraction bar.
/// A struck bar and a slider, written for this test.
#[test]
fn new_problems_print_fractions_without_nested_fractions() {
    let text = r#"
title = "A struck bar, written for this test"
source = "test"
[symbols]
constants = ["M", "P", "h", "k", "c"]
time = ["x", "y"]
[[step]]
name = "T"
value = "5*P^2/(2*M)"
[[step]]
name = "R"
value = "M*h*(h^2 - c^2)*x'^2/(12*k^3)"
[[step]]
name = "a"
value = "(M*x' - 2*k*y'*cos(y) + c*sin(x))/(h*sin(y))"
[[step]]
name = "half"
value = "x'/(2*M)"
"#;
    assert_eq!(
        printed(text),
        [
            "5 P²/(2 M)",
            "M h (h² − c²) x\u{307}²/(12 k³)",
            "(M x\u{307} − 2 k y\u{307} cos y + c sin x)/(h sin y)",
            "x\u{307}/(2 M)",
        ]
    );
    assert_eq!(
        printed_latex(text),
        [
            r"\frac{5 P^{2}}{2 M}",
            r"\frac{M h \left(h^{2} - c^{2}\right) \dot{x}^{2}}{12 k^{3}}",
            r"\frac{M \dot{x} - 2 k \dot{y} \cos y + c \sin x}{h \sin y}",
            r"\frac{\dot{x}}{2 M}",
        ]
    );
}

/// Bracket order and signs: terms of constants only lead their order of
/// derivative (J + I cos² θ + I′ sin² θ); a minus sign is pulled out of a
/// bracket only when more of its terms are negative than positive, and
/// never over kinds of terms (the `m` terms, the couple) of opposite signs:
/// m z ẍ − m x z̈ + ḣ, not −(m x z̈ − m z ẍ − ḣ); with as many negative
/// terms as positive the bracket leads with a positive one. Names not in any bundled
/// file, written for this test.
#[test]
fn new_problems_print_brackets_with_fewest_negative_terms() {
    let out = printed(
        r#"
title = "Brackets and signs, written for this test"
source = "test"
[symbols]
constants = ["Ip", "Iq", "K", "m"]
time = ["x", "z", "h", "phi", "theta"]
[[step]]
name = "inertia"
value = "Iq*cos(theta)^2 + Ip*sin(theta)^2 + K"
[[step]]
name = "moment"
value = "-m*x*z'' + m*z*x'' + h'"
[[step]]
name = "mixed"
value = "-m*x*z'' - m*z*x'' + h'"
[[step]]
name = "pulled"
value = "-Ip*(phi''*sin(theta) + 2*theta'*phi'*cos(theta)) + Iq*theta'"
collect = ["Ip", "Iq"]
[[step]]
name = "tie"
value = "-x*h + z*h"
"#,
    );
    assert_eq!(
        out,
        [
            "K + I′ sin² θ + Iq cos² θ",
            "m z x\u{308} − m x z\u{308} + h\u{307}",
            "h\u{307} − m x z\u{308} − m z x\u{308}",
            "−I′ (φ\u{308} sin θ + 2 φ\u{307} θ\u{307} cos θ) + Iq θ\u{307}",
            "(z − x) h",
        ]
    );
}

/// Labels that are mathematics: an expression of the symbols, a partial
/// derivative, and `0`, which prints the equation as `… = 0` (every
/// component of a vector, without a subscript on the zero). A file written
/// for this test; a label that is not an expression of the symbols is an
/// error naming the field.
#[test]
fn new_problems_print_labels_as_mathematics() {
    let text = |label: &str| {
        format!(
            r#"
title = "Labels, written for this test"
source = "test"
[symbols]
constants = ["J", "k"]
time = ["phi", "theta"]
[[step]]
name = "T"
value = "J*(theta'^2 + phi'^2*sin(theta)^2)/2"
[[step]]
name = "p"
label = "partial(T, theta')"
value = "partial(T, theta')"
[[step]]
name = "coupled"
label = "{label}"
value = "phi''*sin(theta)"
[[step]]
name = "balance"
label = "0"
value = "[J*theta'' + k*theta, J*phi'', 0] in N"
[[step]]
name = "energy"
label = "0"
value = "2*T - J*theta'^2 - J*phi'^2*sin(theta)^2"
"#
        )
    };
    let d = hdot_sym::derivation::load_str("labels.toml", &text("phi''*sin(theta)")).unwrap();
    let unicode = hdot_sym::render::render(&d, hdot_sym::render::Format::Unicode);
    for line in [
        "   ∂T/∂θ\u{307} = J θ\u{307}\n",
        "   φ\u{308} sin θ = φ\u{308} sin θ\n",
        "   J θ\u{308} + k θ = 0\n",
        "   J φ\u{308} = 0\n",
        "   0 = 0\n",
        // Headings show the label as mathematics; a step labelled 0
        // states that its formula is zero.
        "\n2. ∂T/∂θ\u{307} = partial(T, theta')\n",
        "\n3. φ\u{308} sin θ = phi''*sin(theta)\n",
        "\n4. [J*theta'' + k*theta, J*phi'', 0] in N = 0\n",
        // A result that vanishes identically is said so, not `0 = 0`.
        "\n5. 2*T - J*theta'^2 - J*phi'^2*sin(theta)^2 = 0\n   the formula reduces to 0: the relation holds identically\n",
    ] {
        assert!(unicode.contains(line), "{line:?} not in\n{unicode}");
    }
    assert!(!unicode.contains("0_x"), "{unicode}");
    assert!(!unicode.contains("phi''*sin(theta) = "), "{unicode}");
    let latex = hdot_sym::render::render(&d, hdot_sym::render::Format::Latex);
    for part in [
        r"\frac{\partial T}{\partial \dot{\theta}} &= J \dot{\theta}",
        r"\ddot{\phi} \sin\theta &= ",
        r"J \ddot{\theta} + k \theta &= 0",
        r"\textbf{Step 2: $\frac{\partial T}{\partial \dot{\theta}}$.}",
        r"\textbf{Step 3: $\ddot{\phi} \sin\theta$.}",
        r"\textbf{Step 4.}",
        r"\emph{The formula reduces to 0: the relation holds identically.}",
    ] {
        assert!(latex.contains(part), "{part:?} not in\n{latex}");
    }
    let err = hdot_sym::derivation::load_str("labels.toml", &text("phi''*sin(thet)"))
        .expect_err("an unknown symbol in a label is refused")
        .to_string();
    assert!(
        err.contains("label") && err.contains("labels.toml"),
        "{err}"
    );
}

/// The order of constant factors is a file setting: `[symbols] order`
/// puts the names listed first, in that order, in every product (alone,
/// inside a bracket and in a solved form's ratio); without it the
/// conventional order holds (m g l). A name that is not a declared
/// constant is refused. A file written for this test.
#[test]
fn constant_order_is_a_file_setting() {
    let text = |order: &str| {
        format!(
            r#"
title = "A pendulum, written for this test"
source = "test"
[symbols]
constants = ["m", "g", "l", "k"]
time = ["theta"]
{order}
[[step]]
name = "M"
value = "l*g*m*sin(theta)"
[[step]]
name = "E"
value = "m*l^2*theta'^2/2 - m*g*l*cos(theta) + k*l*g*theta"
[[step]]
name = "acc"
value = "solve(m*l^2*theta'' + m*g*l*sin(theta) - k*g*theta', [theta''])"
"#
        )
    };
    let conventional = printed(&text(""));
    assert_eq!(conventional[0], "m g l sin θ", "{conventional:?}");
    let own = printed(&text(r#"order = ["l", "k", "g", "m"]"#));
    assert_eq!(own[0], "l g m sin θ", "{own:?}");
    assert_eq!(
        own[1..],
        [
            "(1/2) l² m θ\u{307}² + l g (k θ − m cos θ)",
            "g (k θ\u{307} − l m sin θ)/(l² m)"
        ],
        "{own:?}"
    );
    assert_ne!(own[1..], conventional[1..], "{conventional:?}");
    let err = hdot_sym::derivation::load_str("order.toml", &text(r#"order = ["l", "theta"]"#))
        .expect_err("a time-dependent name in order is refused")
        .to_string();
    assert!(err.contains("order") && err.contains("theta"), "{err}");
}

/// A failed expectation in every backend of the document model: the
/// terminal names the component, the expected form and derived − expected;
/// the LaTeX and Markdown sections show both as equations. A file written
/// for this test, with a wrong sign in its expectation.
#[test]
fn a_failed_expectation_shows_in_every_backend() {
    let text = r#"
title = "A spring, written for this test"
source = "test"
[symbols]
constants = ["m", "k"]
time = ["x"]
[[step]]
name = "F"
label = "Sigma F"
value = "[-k*x, 0, 0] in N"
expect = ["k*x", "0", "0"]
"#;
    let d = hdot_sym::derivation::load_str("spring.toml", text).unwrap();
    assert!(!d.all_hold());
    let unicode = hdot_sym::render::render(&d, hdot_sym::render::Format::Unicode);
    assert!(
        unicode.contains("   ✗ ΣF_x: expected k x; derived − expected = −2 k x\n"),
        "{unicode}"
    );
    assert!(!unicode.contains("ΣF_y: expected"), "{unicode}");
    assert!(!unicode.contains("✓"), "{unicode}");
    let latex = hdot_sym::render::render(&d, hdot_sym::render::Format::Latex);
    assert!(
        latex.contains(r"\Sigma F_{x}^{\text{expected}} &= k x"),
        "{latex}"
    );
    assert!(latex.contains(r"\text{difference} &= -2 k x"), "{latex}");
    let md = hdot_sym::render::render(&d, hdot_sym::render::Format::Markdown);
    assert!(
        md.contains("✗ **Does not equal the expected form**"),
        "{md}"
    );
}

/// sin² θ for 1 − cos² θ also where cos θ divides the group and for
/// higher powers (fewest terms: I cos⁴ γ − 2 I cos² γ + I is I sin⁴ γ);
/// with the sign pulled out the bracket leads with a positive term, and
/// the sign stays in when the highest derivative would lead negative.
/// Names and forms not in any bundled file, written for this test.
#[test]
fn new_problems_print_sin_squared_over_a_divisor_and_lead_positive() {
    let out = printed(
        r#"
title = "A tilted disk, written for this test"
source = "test"
[symbols]
constants = ["K", "L", "a", "b", "beta"]
time = ["u", "chi"]
[[step]]
name = "w"
value = "-K*sin(beta)^2*u'/cos(beta)"
[[step]]
name = "n"
value = "-(K*sin(beta)^2 + L*cos(beta)^2)*u'^2*sin(beta)/cos(beta)"
[[step]]
name = "E"
value = "(K*sin(beta)^2 + L*cos(beta)^2)*sin(beta)^2*u'^2/cos(beta)^2"
[[step]]
name = "acc"
value = "a*chi''*cos(chi) - b*u'^2 - a*u'^2*sin(chi) - a*chi'^2*sin(chi)"
"#,
    );
    assert_eq!(
        out,
        [
            "−K u\u{307} sin² β/cos β",
            "−(K sin² β + L cos² β) u\u{307}² sin β/cos β",
            "(K sin² β + L cos² β) u\u{307}² sin² β/cos² β",
            "a χ\u{308} cos χ − a χ\u{307}² sin χ − a u\u{307}² sin χ − b u\u{307}²",
        ]
    );
}

/// `fold` eliminates, of the abbreviation's atoms times constants, the one
/// that leaves the fewest terms (k := K (s + χ̇) folds as k s, not
/// k²/K − k χ̇), and never a fold that leaves more terms than it found: a
/// linearised result keeps no cos of its small angle. Presentation stays
/// exact. A file written for this test.
#[test]
fn new_problems_fold_by_the_atom_that_leaves_fewest_terms() {
    let text = r#"
title = "Folds, written for this test"
source = "test"
[symbols]
constants = ["B", "K", "c"]
time = ["s", "chi", "r", "y"]
small = ["eta"]
[[abbreviation]]
name = "k"
value = "K*(s + chi')"
[[abbreviation]]
name = "z"
value = "y' + c*cos(eta)"
[[step]]
name = "eq"
value = "B*r' + K*(s + chi')*s"
fold = ["k"]
[[step]]
name = "sol"
value = "solve(eq, r')"
fold = ["k"]
[[step]]
name = "lin"
value = "linearize(c*(y' + c*cos(eta))*sin(eta))"
fold = ["z"]
"#;
    let d = hdot_sym::derivation::load_str("folds.toml", text).unwrap();
    assert!(assert_exact(&d) >= 3);
    assert_eq!(
        printed(text),
        ["B r\u{307} + k s", "−k s/B", "c (y\u{307} + c) η"]
    );
}

/// What `collect` leaves over is not one bracket among the groups: its
/// terms are grouped by their rates, with differences of constants in
/// cyclic order of their subscripts (C_3 ẇ_3 + k̇ − (K_1 − K_2) w_1 w_2,
/// not C_3 ẇ_3 + (k̇ − K_1 w_1 w_2 + K_2 w_1 w_2), and
/// −(K_2 − C_3) w_2 w_3); and inside a bracket, terms that share their
/// rates are one term with a bracket of constants
/// (((K_2 − C_3) w_3 − k) w_2/K_1). A gyrostat with other names, and a
/// pendulum's forcing, written for this test.
#[test]
fn new_problems_group_what_collect_leaves_and_inside_brackets() {
    let out = printed(
        r#"
title = "A satellite with a wheel, written for this test"
source = "test"
[symbols]
constants = ["K_1", "K_2", "C_3", "B", "P", "Q", "c", "e"]
time = ["w_1", "w_2", "w_3", "s", "u", "chi"]
[[abbreviation]]
name = "k"
value = "B*(w_3 + s')"
[[frame]]
name = "S"
axes = ["1", "2", "3"]
angular_velocity = "[w_1, w_2, w_3]"
[[step]]
name = "M"
label = "Sigma M"
value = "dt(principal(K_1, K_2, C_3) * angvel(S) + [0, 0, k] in S)"
fold = ["k"]
collect = ["w_1'", "w_2'", "w_3'", "k"]
[[step]]
name = "rates"
value = "solve(list(M.1, M.2), [w_1', w_2'])"
fold = ["k"]
[[step]]
name = "f"
value = "(P*u'^2*cos(chi) - Q*u'^2*cos(chi) - e*c)*sin(chi)"
"#,
    );
    assert_eq!(
        out,
        [
            "K_1 w\u{307}_1 + k w_2 − (K_2 − C_3) w_2 w_3",
            "K_2 w\u{307}_2 − k w_1 − (C_3 − K_1) w_3 w_1",
            "C_3 w\u{307}_3 + k\u{307} − (K_1 − K_2) w_1 w_2",
            "((K_2 − C_3) w_3 − k) w_2/K_1",
            "((C_3 − K_1) w_3 + k) w_1/K_2",
            "((P − Q) u\u{307}² cos χ − c e) sin χ",
        ]
    );
}

/// Factors of one angle stay together: the cosine of an angle follows its
/// sine (sin θ cos θ cos² λ, sin ψ cos ψ sin θ); a cosine whose sine is
/// absent follows the sines (sin θ cos ψ). A file written for this test.
#[test]
fn new_problems_keep_the_factors_of_one_angle_together() {
    let out = printed(
        r#"
title = "Angles, written for this test"
source = "test"
[symbols]
constants = ["W", "lambda"]
time = ["psi", "theta", "u"]
[[step]]
name = "a"
value = "W^2*cos(theta)*cos(lambda)^2*sin(theta)"
[[step]]
name = "b"
value = "u'*cos(psi)*sin(theta)*sin(psi)"
[[step]]
name = "c"
value = "-u'*cos(psi)*sin(theta) + cos(lambda)*sin(lambda)*cos(theta)"
"#,
    );
    assert_eq!(
        out,
        [
            "W² sin θ cos θ cos² λ",
            "u\u{307} sin ψ cos ψ sin θ",
            "sin λ cos λ cos θ − u\u{307} sin θ cos ψ",
        ]
    );
}

/// A fraction is pulled out only over the terms that carry it (rule 12),
/// on files written for this test: a pendulum's energy keeps its potential
/// outside the ½, and a governor's swing equation keeps its integer terms
/// whole instead of doubling them under a ½.
#[test]
fn new_problems_pull_a_fraction_only_over_the_terms_that_carry_it() {
    let out = printed(
        r#"
title = "Fractions over part of a sum, written for this test"
source = "test"
[symbols]
constants = ["m", "g", "c", "K", "Q", "Omega"]
time = ["u", "v"]
[[step]]
name = "E"
value = "K*u'^2/2 + Q*u'^2*sin(v)^2/2 + K*v'^2/2 - m*g*c*cos(v)"
[[step]]
name = "swing"
value = "K*v'' - (K - Q)*Omega^2*sin(v)*cos(v) + m*g*c*sin(v)/2"
[[step]]
name = "steady"
value = "g - 2*c*Omega^2*cos(v)/3"
[[step]]
name = "half"
value = "K*u'^2/2 + Q*v'^2/2"
[[step]]
name = "lin"
value = "K*v'' + (m*g*c/2 - (K - Q)*Omega^2)*v"
collect = ["v''", "v"]
"#,
    );
    assert_eq!(
        out,
        [
            "(1/2) (K u\u{307}² + K v\u{307}² + Q u\u{307}² sin² v) − m g c cos v",
            "K v\u{308} + (Q − K) Ω² sin v cos v + (1/2) m g c sin v",
            "g − (2/3) c Ω² cos v",
            "(1/2) (K u\u{307}² + Q v\u{307}²)",
            "K v\u{308} + ((Q − K) Ω² + (1/2) m g c) v",
        ]
    );
}
