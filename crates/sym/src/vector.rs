//! 3-vectors and 3×3 matrices of canonical expressions.
//!
//! Components are [`Poly`] values, so every operation returns canonical
//! components. The inertia-tensor builder follows the textbook sign
//! convention: products of inertia enter with a **minus** sign.
//!
//! # Example
//! ```
//! use hdot_sym::{Mat3, Poly, Symbols, Vec3};
//! let s = Symbols::parse_decl(&["I_x", "I_y", "I_z", "I_xy", "I_yz", "I_zx"], &["w_x", "w_y", "w_z"]);
//! let p = |t: &str| s.poly(t).unwrap();
//! let inertia = Mat3::inertia([p("I_x"), p("I_y"), p("I_z")], [p("I_xy"), p("I_yz"), p("I_zx")]);
//! let h = inertia.mul_vec(&Vec3::new([p("w_x"), p("w_y"), p("w_z")]));
//! assert_eq!(h.0[0], p("I_x*w_x - I_xy*w_y - I_zx*w_z"));
//! ```

use crate::atom::Atom;
use crate::poly::Poly;

/// A column vector of three expressions.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Vec3(pub [Poly; 3]);

/// A 3×3 matrix of expressions, row-major.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Mat3(pub [[Poly; 3]; 3]);

/// # Construction
impl Vec3 {
    /// From three components.
    pub fn new(c: [Poly; 3]) -> Vec3 {
        Vec3(c)
    }

    /// The zero vector.
    pub fn zero() -> Vec3 {
        Vec3::default()
    }

    /// The unit vector along axis `k` (0, 1, 2).
    pub fn unit(k: usize) -> Vec3 {
        let mut v = Vec3::zero();
        v.0[k] = Poly::one();
        v
    }
}

/// # Operations
impl Vec3 {
    /// Component-wise map.
    pub fn map(&self, f: impl Fn(&Poly) -> Poly) -> Vec3 {
        Vec3([f(&self.0[0]), f(&self.0[1]), f(&self.0[2])])
    }

    /// `self + other`.
    pub fn add(&self, o: &Vec3) -> Vec3 {
        Vec3([
            &self.0[0] + &o.0[0],
            &self.0[1] + &o.0[1],
            &self.0[2] + &o.0[2],
        ])
    }

    /// `self − other`.
    pub fn sub(&self, o: &Vec3) -> Vec3 {
        Vec3([
            &self.0[0] - &o.0[0],
            &self.0[1] - &o.0[1],
            &self.0[2] - &o.0[2],
        ])
    }

    /// `−self`.
    pub fn neg(&self) -> Vec3 {
        self.map(|c| -c)
    }

    /// `s · self`.
    pub fn scale(&self, s: &Poly) -> Vec3 {
        self.map(|c| s * c)
    }

    /// The dot product.
    pub fn dot(&self, o: &Vec3) -> Poly {
        &(&(&self.0[0] * &o.0[0]) + &(&self.0[1] * &o.0[1])) + &(&self.0[2] * &o.0[2])
    }

    /// The cross product `self × other`.
    pub fn cross(&self, o: &Vec3) -> Vec3 {
        let (a, b) = (&self.0, &o.0);
        Vec3([
            &(&a[1] * &b[2]) - &(&a[2] * &b[1]),
            &(&a[2] * &b[0]) - &(&a[0] * &b[2]),
            &(&a[0] * &b[1]) - &(&a[1] * &b[0]),
        ])
    }

    /// Component-wise time derivative (the derivative *relative to* the
    /// frame the components are expressed in).
    pub fn dt(&self) -> Vec3 {
        self.map(Poly::dt)
    }

    /// True when every component is zero.
    pub fn is_zero(&self) -> bool {
        self.0.iter().all(Poly::is_zero)
    }
}

/// # Construction
impl Mat3 {
    /// From rows.
    pub fn new(rows: [[Poly; 3]; 3]) -> Mat3 {
        Mat3(rows)
    }

    /// The identity matrix.
    pub fn identity() -> Mat3 {
        Mat3::diag([Poly::one(), Poly::one(), Poly::one()])
    }

    /// A diagonal matrix.
    pub fn diag(d: [Poly; 3]) -> Mat3 {
        let [a, b, c] = d;
        let z = Poly::zero;
        Mat3([[a, z(), z()], [z(), b, z()], [z(), z(), c]])
    }

    /// The inertia tensor from moments `(I_x, I_y, I_z)` and products
    /// `(I_xy, I_yz, I_zx)`, which enter with a minus sign:
    ///
    /// ```text
    ///  |  I_x  −I_xy −I_zx |
    ///  | −I_xy  I_y  −I_yz |
    ///  | −I_zx −I_yz  I_z  |
    /// ```
    pub fn inertia(moments: [Poly; 3], products: [Poly; 3]) -> Mat3 {
        let [ix, iy, iz] = moments;
        let [pxy, pyz, pzx] = products.map(|p| -p);
        Mat3([
            [ix, pxy.clone(), pzx.clone()],
            [pxy, iy, pyz.clone()],
            [pzx, pyz, iz],
        ])
    }

    /// The inertia tensor in principal axes: `diag(I_1, I_2, I_3)`.
    pub fn principal(moments: [Poly; 3]) -> Mat3 {
        Mat3::diag(moments)
    }

    /// The rotation matrix that takes components in a frame turned by the
    /// angle `q` about axis `k` (0 = x, 1 = y, 2 = z) of its parent into
    /// components in the parent: `v_parent = R · v_child`.
    pub fn rotation(k: usize, q: Atom) -> Mat3 {
        let c = Poly::atom(Atom::cos(q).expect("an angle symbol"));
        let s = Poly::atom(Atom::sin(q).expect("an angle symbol"));
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let mut m = Mat3::identity();
        m.0[i][i] = c.clone();
        m.0[j][j] = c;
        m.0[i][j] = -&s;
        m.0[j][i] = s;
        m
    }
}

/// # Operations
impl Mat3 {
    /// `self · v`.
    pub fn mul_vec(&self, v: &Vec3) -> Vec3 {
        Vec3(std::array::from_fn(|i| Vec3(self.0[i].clone()).dot(v)))
    }

    /// `self · other`.
    pub fn mul(&self, o: &Mat3) -> Mat3 {
        let t = o.transpose();
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| Vec3(self.0[i].clone()).dot(&Vec3(t.0[j].clone())))
        }))
    }

    /// The transpose.
    pub fn transpose(&self) -> Mat3 {
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| self.0[j][i].clone())
        }))
    }

    /// Element-wise map.
    pub fn map(&self, f: impl Fn(&Poly) -> Poly) -> Mat3 {
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| f(&self.0[i][j]))
        }))
    }

    /// `self + other`.
    pub fn add(&self, o: &Mat3) -> Mat3 {
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| &self.0[i][j] + &o.0[i][j])
        }))
    }

    /// True when symmetric.
    pub fn is_symmetric(&self) -> bool {
        (0..3).all(|i| (0..3).all(|j| self.0[i][j] == self.0[j][i]))
    }
}
