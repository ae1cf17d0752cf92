//! Linearization about an operating point: `linearize(x, q = q0, …)` of
//! the nonlinear heavy top gives the sleeping top's M, C and K; Kane's
//! equations to first order (`kane(…, q = q0, …)`) equal the nonlinear
//! ones linearized, for the rolling disk; a configuration constraint's
//! dependent coordinate is eliminated by implicit differentiation (two
//! pendulums geared 2 : 1); and what cannot be linearized is a located
//! error.

use hdot_sym::derivation::{Derivation, Value, load_str};
use hdot_tests::repo_root;

fn step<'d>(d: &'d Derivation, name: &str) -> &'d Value {
    &d.steps
        .iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("no step {name}"))
        .value
}

/// The heavy top in the sleeping top's tilts a (about N's x) and b (about
/// the tilted y), spinning by c about its axis: Lagrange's equations,
/// nonlinear, then linearized about the vertical at spin rate ω.
const HEAVY_TOP: &str = r#"
title = "the heavy top, tilted by a and b"
source = "written for the test"
[symbols]
constants = ["I", "Ip", "m", "g", "l", "omega"]
time = ["a", "b", "c"]
[[frame]]
name = "A"
parent = "N"
rotation = "x(a)"
[[frame]]
name = "B"
parent = "A"
rotation = "y(b)"
[[frame]]
name = "S"
parent = "B"
rotation = "z(c)"
[[step]]
name = "T"
value = "dot(angvel(S), principal(Ip, Ip, I)*angvel(S))/2"
[[step]]
name = "V"
value = "m*g*express([0, 0, l] in B, N).z"
[[step]]
name = "L"
value = "lagrange(T, V, [a, b, c])"
[[step]]
name = "eqs"
value = "linearize(list(L.1, L.2), a = 0, b = 0, c' = omega)"
[[step]]
name = "M"
value = "jacobian(eqs, [a'', b''])"
[[step]]
name = "C"
value = "jacobian(eqs, [a', b'])"
[[step]]
name = "K"
value = "jacobian(eqs, [a, b])"
"#;

#[test]
fn the_heavy_top_linearized_is_the_sleeping_top() {
    let top = load_str("heavy-top.toml", HEAVY_TOP).unwrap_or_else(|e| panic!("{e}"));
    let path = repo_root().join("docs/examples/derivations/sleeping-top.toml");
    let sleeping = hdot_sym::derivation::load(&path).unwrap_or_else(|e| panic!("{e}"));
    for m in ["M", "C", "K"] {
        assert_eq!(step(&top, m), step(&sleeping, m), "{m}");
    }
    // Linear: the linearized equations are their own linearization, and
    // they hold no second power of a small symbol.
    let Value::List { items, .. } = step(&top, "eqs") else {
        panic!("a list")
    };
    for p in items {
        for (mono, _) in p.terms() {
            let small: i32 = mono
                .factors()
                .iter()
                .filter(|(a, _)| ["a", "b"].contains(&a.name()) && a.is_time_dependent())
                .map(|f| f.1)
                .sum();
            assert!(small <= 1, "{p}");
        }
    }
}

/// The bundled rolling disk with a spin rate Ω: Kane's equations to first
/// order about upright rolling equal its nonlinear Kane's equations
/// linearized there.
#[test]
fn linearized_kane_is_kane_linearized_for_the_rolling_disk() {
    let text = std::fs::read_to_string(repo_root().join("derivations/disk-rolling-on-plane.toml"))
        .unwrap();
    let text = text.replace(
        "constants = [\"m\", \"g\", \"r\", \"I\", \"J\"]",
        "constants = [\"m\", \"g\", \"r\", \"I\", \"J\", \"Omega\"]",
    ) + r#"
[[step]]
name = "KN"
value = "linearize(K, theta = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
[[step]]
name = "KL"
value = "kane([u_1, u_2, u_3], no_slip, [u_4, u_5], theta = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
expect = ["KN.1", "KN.2", "KN.3"]
"#;
    assert!(text.contains("\"Omega\"]"));
    let d = load_str("disk.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
    // Not vacuous: the lean equation keeps its gyroscopic and gravity terms.
    let Value::List { items, .. } = step(&d, "KL") else {
        panic!("a list")
    };
    let names: Vec<&str> = items[0].atoms().iter().map(|a| a.name()).collect();
    for n in ["Omega", "theta", "g"] {
        assert!(names.contains(&n), "{n} in {}", items[0]);
    }
}

/// Two pendulums on one pivot, a about N's x and b about it too, tied by
/// sin b = 2 sin a: to first order b = 2a, so the system is one pendulum
/// with inertia I₁ + 4 I₂ and stiffness m₁ g l₁ + 4 m₂ g l₂.
const GEARED: &str = r#"
title = "two pendulums geared 2 : 1"
source = "written for the test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m_1", "m_2", "l_1", "l_2", "I_1", "I_2", "J", "g"]
time = ["a", "b"]
speeds = ["u_a", "u_b"]
[kinematics]
a = "u_a"
b = "u_b"
[[frame]]
name = "A"
parent = "N"
rotation = "x(a)"
[[frame]]
name = "B"
parent = "N"
rotation = "x(b)"
[[point]]
name = "O"
fixed = true
[[body]]
name = "one"
frame = "A"
point = "O"
mass = "m_1"
mass_centre = "[0, 0, -l_1] in A"
inertia = "principal(I_1, J, J)"
[[body]]
name = "two"
frame = "B"
point = "O"
mass = "m_2"
mass_centre = "[0, 0, -l_2] in B"
inertia = "principal(I_2, J, J)"
[[step]]
name = "K"
value = "CALL"
"#;

fn geared(call: &str) -> Result<Derivation, hdot_sym::derivation::Diagnostic> {
    load_str("geared.toml", &GEARED.replace("CALL", call))
}

#[test]
fn a_dependent_coordinate_is_eliminated_by_implicit_differentiation() {
    let d = geared("kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 0, b = 0, u_a = 0)")
        .unwrap_or_else(|e| panic!("{e}"));
    let want = load_str(
        "want.toml",
        &GEARED.replace(
            "CALL",
            "list((I_1 + 4*I_2)*u_a' + (m_1*g*l_1 + 4*m_2*g*l_2)*a)",
        ),
    )
    .unwrap();
    assert_eq!(step(&d, "K"), step(&want, "K"));
    // Exactly (no operating point), the constraint's rate joins the
    // velocity constraints: the same as writing the rate by hand.
    let exact = geared("kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b])").unwrap();
    let by_hand = geared("kane([u_a], list(cos(b)*u_b - 2*cos(a)*u_a), [u_b])").unwrap();
    assert_eq!(step(&exact, "K"), step(&by_hand, "K"));
}

#[test]
fn what_cannot_be_linearized_is_a_located_error() {
    let cases = [
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], a = 0, b = 0, u_a = 0)",
            "1 configuration constraint (free of the speeds) for 0 dependent coordinates",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a) - 1), [u_b], [b], a = 0, b = 0, u_a = 0)",
            "is -1 at the operating point, not 0",
        ),
        (
            "kane([u_a], list(cos(b) - cos(a)), [u_b], [b], a = 0, b = 0, u_a = 0)",
            "cannot be eliminated at the operating point",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 0, u_a = 0)",
            "the dependent coordinate `b` needs an operating value",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [u_a], a = 0, b = 0)",
            "`u_a` is not a coordinate",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = u_a, b = 0)",
            "an operating value is written in constants",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 0, b = 0, g = 1)",
            "`g` is a constant",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 1/2, b = 0, u_a = 0)",
            "cannot be expanded about its operating value",
        ),
        (
            "kane([u_a], list(u_a*u_b), [u_b])",
            "not linear in the speeds",
        ),
    ];
    for (call, want) in cases {
        let e = geared(call)
            .err()
            .unwrap_or_else(|| panic!("{call} derives"));
        assert!(e.message.contains(want), "{call}: {e}");
        assert!(e.source_line.contains("kane("), "{call}: {e}");
        assert_eq!(e.path, "geared.toml");
    }
}

/// A damped pendulum driven by a torque, in Lagrange's form (the speed is
/// θ̇): E ẋ = A x + B r with M = m l² divided out (E = I).
const PENDULUM: &str = r#"
title = "a damped pendulum driven by a torque, linearized"
source = "written for the test"
[symbols]
constants = ["m", "l", "g", "c", "M_a"]
time = ["theta"]
[[step]]
name = "eqs"
value = "list(m*l^2*theta'' + c*theta' + m*g*l*theta - M_a)"
[[step]]
name = "A_lin"
label = "A"
value = "state_matrix(eqs, [theta], [theta'], [M_a])"
expect = [["0", "1"], ["-g/l", "-c/(m*l^2)"]]
[[step]]
name = "B_lin"
label = "B"
value = "input_matrix(eqs, [theta], [theta'], [M_a])"
expect = [["0"], ["1/(m*l^2)"]]
[[step]]
name = "E_lin"
label = "E"
value = "state_mass(eqs, [theta], [theta'], [M_a])"
expect = [["1", "0"], ["0", "1"]]
"#;

#[test]
fn a_state_space_form_divides_out_a_mass_matrix_it_can_divide_by() {
    let d = load_str("pendulum.toml", PENDULUM).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
}

/// Two coupled masses whose mass matrix's determinant a c − b² has no
/// known sign: E holds M, and A and B are not divided by it.
#[test]
fn a_state_space_form_keeps_a_mass_matrix_it_cannot_divide_by_in_e() {
    let text = r#"
title = "coupled, descriptor form"
source = "written for the test"
[symbols]
constants = ["a", "b", "c", "k", "F"]
time = ["x", "y"]
speeds = ["u", "w"]
[kinematics]
x = "u"
y = "w"
[[step]]
name = "eqs"
value = "list(a*u' + b*w' + k*x - F, b*u' + c*w' + k*(y - x))"
[[step]]
name = "A_lin"
value = "state_matrix(eqs, [x, y], [u, w], [F])"
expect = [["0", "0", "1", "0"], ["0", "0", "0", "1"], ["-k", "0", "0", "0"], ["k", "-k", "0", "0"]]
[[step]]
name = "B_lin"
value = "input_matrix(eqs, [x, y], [u, w], [F])"
expect = [["0"], ["0"], ["1"], ["0"]]
[[step]]
name = "E_lin"
value = "state_mass(eqs, [x, y], [u, w], [F])"
expect = [["1", "0", "0", "0"], ["0", "1", "0", "0"], ["0", "0", "a", "b"], ["0", "0", "b", "c"]]
"#;
    let d = load_str("coupled.toml", text).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
}

#[test]
fn what_is_no_linear_state_space_system_is_a_located_error() {
    for (from, to, says) in [
        (
            "c*theta' + m*g*l*theta",
            "c*theta'^2 + m*g*l*theta",
            "occurs to the power 2",
        ),
        (
            "m*g*l*theta - M_a",
            "m*g*l*sin(theta) - M_a",
            "neither in the state nor an input",
        ),
        ("- M_a)", "- M_a + g)", "the equations must vanish"),
        (
            "state_matrix(eqs, [theta], [theta'], [M_a])",
            "state_matrix(eqs, [theta], [m], [M_a])",
            "is a constant",
        ),
        (
            "state_mass(eqs, [theta], [theta'], [M_a])",
            "state_mass(eqs, [theta, theta'], [theta'], [M_a])",
            "2 coordinates for 1 equation",
        ),
    ] {
        let file = PENDULUM.replace(from, to);
        assert_ne!(file, PENDULUM, "{from}");
        let e = load_str("pendulum.toml", &file).expect_err(to);
        assert!(e.message.contains(says), "{to}: {}", e.message);
        assert!(e.line > 0 && e.column > 0, "{to}: {e}");
    }
}

/// The bundled bicycle's state matrix (E ẋ = A x, E = diag(I, M): its
/// det M holds sin λ and cos λ) has at 5 m/s the eigenvalues of the
/// benchmark's form M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = 0 built from the
/// steps M, C_1, K_0 and K_2, with the benchmark's parameters.
#[test]
fn the_bicycle_s_state_matrix_has_the_eigenvalues_of_its_lean_and_steer_form() {
    use hdot_sym::atom::AtomKind;
    use nalgebra::DMatrix;
    let d = hdot_sym::derivation::load(&repo_root().join("derivations/bicycle.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let text =
        std::fs::read_to_string(repo_root().join("docs/examples/stability-bicycle.toml")).unwrap();
    let table: toml::Table = toml::from_str(&text).unwrap();
    let mut constants: std::collections::BTreeMap<String, f64> = table["constants"]
        .as_table()
        .expect("[constants]")
        .iter()
        .map(|(k, v)| (k.clone(), v.as_float().expect("a number")))
        .collect();
    let v = 5.0;
    constants.insert("v".into(), v);
    let of = |q: hdot_sym::atom::Atom| constants[q.name()];
    let number = |p: &hdot_sym::Poly| -> f64 {
        p.eval(&mut |a| match a.kind() {
            AtomKind::Sin(q) => of(q).sin(),
            AtomKind::Cos(q) => of(q).cos(),
            _ => of(a),
        })
    };
    let matrix = |name: &str| -> DMatrix<f64> {
        let Value::Array(rows) = step(&d, name) else {
            panic!("{name} is no array");
        };
        let (n, m) = (rows.len(), rows[0].len());
        DMatrix::from_fn(n, m, |i, j| number(&d.unfold(&rows[i][j])))
    };
    let (a, e) = (matrix("A_lin"), matrix("E_lin"));
    assert_eq!(a.shape(), (4, 4));
    let state = e.lu().solve(&a).expect("E is regular");
    // The benchmark's form, A = [[0, I], [−M⁻¹ K, −M⁻¹ C]].
    let (m, c1, k0, k2) = (matrix("M"), matrix("C_1"), matrix("K_0"), matrix("K_2"));
    let g = constants["g"];
    let k = &k0 * g + &k2 * (v * v);
    let c = &c1 * v;
    let lu = m.lu();
    let (mk, mc) = (lu.solve(&k).unwrap(), lu.solve(&c).unwrap());
    let mut reference = DMatrix::zeros(4, 4);
    for i in 0..2 {
        reference[(i, 2 + i)] = 1.0;
        for j in 0..2 {
            reference[(2 + i, j)] = -mk[(i, j)];
            reference[(2 + i, 2 + j)] = -mc[(i, j)];
        }
    }
    let got = state.complex_eigenvalues();
    let want = reference.complex_eigenvalues();
    let scale = want.iter().fold(0.0f64, |s, z| s.max(z.norm()));
    for z in want.iter() {
        let nearest = got.iter().map(|e| (e - z).norm()).fold(f64::MAX, f64::min);
        assert!(
            nearest <= 1e-12 * scale,
            "v = {v}: {z} not among {got:?} (nearest {nearest:e})"
        );
    }
    // The weave pair: a complex pair with negative real part at 5 m/s.
    assert!(
        want.iter().any(|z| z.im.abs() > 1.0 && z.re < 0.0),
        "{want:?}"
    );
}
