//! The TOML tables that the tests' own derivation files share: a frame
//! turned from its parent, a fixed point, a point placed from another, and
//! the two chains of frames written most often (the heavy top's and the
//! rolling disk's). Each macro expands to a string literal, so a file
//! written for a test stays a `const` built with `concat!`:
//!
//! ```
//! const FILE: &str = concat!(
//!     "title = \"a hinge\"\n",
//!     hdot_tests::frame!("A", "N", "z(q)"),
//!     hdot_tests::fixed_point!("O"),
//! );
//! assert!(FILE.contains("[[frame]]\nname = \"A\"\nparent = \"N\"\nrotation = \"z(q)\"\n"));
//! ```

/// A `[[frame]]` table: `name`, turned from `parent` by `rotation`.
#[macro_export]
macro_rules! frame {
    ($name:literal, $parent:literal, $rotation:literal) => {
        concat!(
            "[[frame]]\nname = \"",
            $name,
            "\"\nparent = \"",
            $parent,
            "\"\nrotation = \"",
            $rotation,
            "\"\n"
        )
    };
}

/// A `[[point]]` table of a fixed point `name` (at the origin).
#[macro_export]
macro_rules! fixed_point {
    ($name:literal) => {
        concat!("[[point]]\nname = \"", $name, "\"\nfixed = true\n")
    };
}

/// A `[[point]]` table: `name` placed at `at` from the point `from`.
#[macro_export]
macro_rules! point {
    ($name:literal, $from:literal, $at:literal) => {
        concat!(
            "[[point]]\nname = \"",
            $name,
            "\"\nfrom = \"",
            $from,
            "\"\nat = \"",
            $at,
            "\"\n"
        )
    };
}

/// The heavy top's (and the rolling cone's) chain: precession `P = z(φ)`
/// from `N`, nutation `F = y(nutation)` from `P`, spin `R = z(ψ)` from `F`.
#[macro_export]
macro_rules! top_frames {
    ($nutation:literal) => {
        concat!(
            $crate::frame!("P", "N", "z(phi)"),
            "[[frame]]\nname = \"F\"\nparent = \"P\"\nrotation = \"y(",
            $nutation,
            ")\"\n",
            $crate::frame!("R", "F", "z(psi)")
        )
    };
}

/// The rolling disk's chain: yaw `A = z(ψ)` from `N`, lean `L = x(θ)` from
/// `A`, spin `D = y(φ)` from `L`.
#[macro_export]
macro_rules! disk_frames {
    () => {
        concat!(
            $crate::frame!("A", "N", "z(psi)"),
            $crate::frame!("L", "A", "x(theta)"),
            $crate::frame!("D", "L", "y(phi)")
        )
    };
}

/// A double pendulum's two rods as `[[body]]` tables: rod 1 (frame `A`,
/// mass `m1`, length `l1`) hangs from `O`, rod 2 (frame `B`, `m2`, `l2`)
/// from rod 1's end `P`; each rod's centre (`G1`, `G2`) halfway down it,
/// its moment of inertia (`I1`, `I2`) about the axes across it.
#[macro_export]
macro_rules! double_pendulum_rods {
    () => {
        concat!(
            "[[body]]\nname = \"rod1\"\nframe = \"A\"\npoint = \"O\"\ncentre = \"G1\"\n",
            "mass = \"m1\"\nmass_centre = \"[0, -l1/2, 0] in A\"\n",
            "inertia = \"principal(I1, 0, I1)\"\ninertia_about = \"G1\"\n",
            "[[body]]\nname = \"rod2\"\nframe = \"B\"\npoint = \"P\"\ncentre = \"G2\"\n",
            "mass = \"m2\"\nmass_centre = \"[0, -l2/2, 0] in B\"\n",
            "inertia = \"principal(I2, 0, I2)\"\ninertia_about = \"G2\"\n"
        )
    };
}
