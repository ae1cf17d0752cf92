//! Particle sums: deterministic parallel reductions over any
//! [`ParticleSource`], and the kinematic quantities of a rigid motion.
//!
//! # Determinism
//!
//! A sum over particles `lo..hi` is split at the midpoint into two halves,
//! recursively, down to leaves of at most [`LEAF`] particles; leaves are
//! summed in order, halves combined as `left + right`. The tree depends on
//! the particle count only, never on the number of threads: rayon decides
//! *who* computes a subtree, not *how* it is cut. The result is the same to
//! the bit with 1 thread or 64 (pairwise summation: error grows like
//! `(LEAF + log₂ N) ε`). Memory: one leaf buffer per active task, i.e.
//! bounded by the thread count × the recursion depth.

use nalgebra::Vector3;

use crate::error::BodyError;
use crate::inertia::Inertia;
use crate::mass::MassProperties;

/// Particles per leaf of the summation tree.
pub const LEAF: usize = 512;
/// Subtrees smaller than this are summed on the current thread.
const PAR_MIN: usize = 1 << 15;

/// A contiguous block of particles in structure-of-arrays layout (all four
/// slices have the same length).
#[derive(Debug, Clone, Copy)]
pub struct Block<'a> {
    /// x coordinates.
    pub x: &'a [f64],
    /// y coordinates.
    pub y: &'a [f64],
    /// z coordinates.
    pub z: &'a [f64],
    /// masses.
    pub m: &'a [f64],
}

/// Anything that can present its particles, by index range, as blocks:
/// stored clouds (zero copy) and lazily generated discretisations.
pub trait ParticleSource: Sync {
    /// Number of particles.
    fn len(&self) -> usize;
    /// True when there is no particle.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Calls `f` on consecutive blocks covering particles `lo..hi` in
    /// order (`hi - lo ≤ LEAF`).
    fn visit(&self, lo: usize, hi: usize, f: &mut dyn FnMut(Block<'_>));
}

/// A reduction over particles: an accumulator filled block by block and
/// combined pairwise.
pub trait Kernel: Sync {
    /// The partial sum.
    type Acc: Default + Send;
    /// Adds a block's particles to `acc`.
    fn accumulate(&self, acc: &mut Self::Acc, block: Block<'_>);
    /// `left + right` (left covers the lower indices).
    fn combine(&self, left: Self::Acc, right: Self::Acc) -> Self::Acc;
}

/// Runs `kernel` over all particles of `src`: bitwise the same result
/// whatever the number of rayon threads.
pub fn reduce<S: ParticleSource + ?Sized, K: Kernel>(src: &S, kernel: &K) -> K::Acc {
    reduce_range(src, kernel, 0, src.len())
}

fn reduce_range<S: ParticleSource + ?Sized, K: Kernel>(
    src: &S,
    kernel: &K,
    lo: usize,
    hi: usize,
) -> K::Acc {
    if hi - lo <= LEAF {
        let mut acc = K::Acc::default();
        if hi > lo {
            src.visit(lo, hi, &mut |b| kernel.accumulate(&mut acc, b));
        }
        return acc;
    }
    let mid = lo + (hi - lo) / 2;
    let (l, r) = if hi - lo >= PAR_MIN {
        rayon::join(
            || reduce_range(src, kernel, lo, mid),
            || reduce_range(src, kernel, mid, hi),
        )
    } else {
        (
            reduce_range(src, kernel, lo, mid),
            reduce_range(src, kernel, mid, hi),
        )
    };
    kernel.combine(l, r)
}

// ---------------------------------------------------------------- moments

/// Zeroth, first and second moments of mass about an origin `o`:
/// `Σ m`, `Σ m r`, and `Σ m r_i r_j` (with `r = p − o`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Moments {
    /// Σ m.
    pub mass: f64,
    /// Σ m r.
    pub first: Vector3<f64>,
    /// Σ m [xx, yy, zz, xy, yz, zx].
    pub second: [f64; 6],
}

impl Moments {
    /// The inertia tensor about the origin of the sums (unchecked: it comes
    /// from positive masses).
    pub fn inertia(&self) -> Inertia {
        let [xx, yy, zz, xy, yz, zx] = self.second;
        Inertia::new_unchecked(nalgebra::Matrix3::new(
            yy + zz,
            -xy,
            -zx,
            -xy,
            zz + xx,
            -yz,
            -zx,
            -yz,
            xx + yy,
        ))
    }
}

/// Kernel of [`Moments`] about `origin`.
#[derive(Debug, Clone, Copy)]
pub struct MomentKernel {
    /// The origin of the position vectors.
    pub origin: Vector3<f64>,
}

const LANES: usize = 4;

/// Moment sums of one block: `[Σm, Σmx, Σmy, Σmz, Σmxx, Σmyy, Σmzz, Σmxy,
/// Σmyz, Σmzx]` about `o`.
///
/// Independent lanes (one small array per quantity, so that they live in
/// registers and the compiler can vectorise across lanes), no bounds checks
/// inside (exact chunks), lanes reduced in a fixed order at the end. No
/// fused multiply-add: each lane does the same IEEE operations whether the
/// code runs as SSE2 or AVX2, so the result has the same bits on every
/// x86-64 and with any number of threads.
#[inline(always)]
fn moments_block(o: [f64; 3], b: Block<'_>) -> [f64; 10] {
    let [ox, oy, oz] = o;
    let n = b.m.len();
    let (xs, ys, zs, ms) = (&b.x[..n], &b.y[..n], &b.z[..n], &b.m[..n]);
    let z = [0.0f64; LANES];
    let (mut sm, mut sx, mut sy, mut sz) = (z, z, z, z);
    let (mut sxx, mut syy, mut szz, mut sxy, mut syz, mut szx) = (z, z, z, z, z, z);
    let chunks = xs
        .chunks_exact(LANES)
        .zip(ys.chunks_exact(LANES))
        .zip(zs.chunks_exact(LANES))
        .zip(ms.chunks_exact(LANES));
    for (((x, y), zc), m) in chunks {
        for l in 0..LANES {
            let (x, y, z, m) = (x[l] - ox, y[l] - oy, zc[l] - oz, m[l]);
            let (mx, my, mz) = (m * x, m * y, m * z);
            sm[l] += m;
            sx[l] += mx;
            sy[l] += my;
            sz[l] += mz;
            sxx[l] += mx * x;
            syy[l] += my * y;
            szz[l] += mz * z;
            sxy[l] += mx * y;
            syz[l] += my * z;
            szx[l] += mz * x;
        }
    }
    for j in n - n % LANES..n {
        let (x, y, z, m) = (xs[j] - ox, ys[j] - oy, zs[j] - oz, ms[j]);
        let (mx, my, mz) = (m * x, m * y, m * z);
        sm[0] += m;
        sx[0] += mx;
        sy[0] += my;
        sz[0] += mz;
        sxx[0] += mx * x;
        syy[0] += my * y;
        szz[0] += mz * z;
        sxy[0] += mx * y;
        syz[0] += my * z;
        szx[0] += mz * x;
    }
    let r = |a: [f64; LANES]| (a[0] + a[1]) + (a[2] + a[3]);
    [
        r(sm),
        r(sx),
        r(sy),
        r(sz),
        r(sxx),
        r(syy),
        r(szz),
        r(sxy),
        r(syz),
        r(szx),
    ]
}

/// [`moments_block`] written with AVX2 intrinsics: one 4-wide register
/// per quantity, lane `l` doing exactly the IEEE operations of lane `l` of
/// [`moments_block`] (subtract, multiply, add; no FMA), the tail added to
/// lane 0 and the lanes reduced in the same order — the same bits.
/// (Left to the auto-vectoriser, the lane loop was packed across
/// quantities, with shuffles and spills, at half the speed.) With
/// `SHIFT = false` the origin is +0 and the subtractions are skipped
/// (`x − (+0) = x` for every x).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn moments_block_avx2<const SHIFT: bool>(o: [f64; 3], b: Block<'_>) -> [f64; 10] {
    use std::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd,
        _mm256_storeu_pd, _mm256_sub_pd,
    };
    let n = b.m.len();
    let (xs, ys, zs, ms) = (&b.x[..n], &b.y[..n], &b.z[..n], &b.m[..n]);
    let (ox, oy, oz) = (
        _mm256_set1_pd(o[0]),
        _mm256_set1_pd(o[1]),
        _mm256_set1_pd(o[2]),
    );
    let mut acc: [__m256d; 10] = [_mm256_setzero_pd(); 10];
    let full = n - n % LANES;
    let mut i = 0;
    while i < full {
        // SAFETY: i + 4 ≤ full ≤ n, the length of all four slices.
        let (mut x, mut y, mut z, m) = unsafe {
            (
                _mm256_loadu_pd(xs.as_ptr().add(i)),
                _mm256_loadu_pd(ys.as_ptr().add(i)),
                _mm256_loadu_pd(zs.as_ptr().add(i)),
                _mm256_loadu_pd(ms.as_ptr().add(i)),
            )
        };
        if SHIFT {
            x = _mm256_sub_pd(x, ox);
            y = _mm256_sub_pd(y, oy);
            z = _mm256_sub_pd(z, oz);
        }
        let (mx, my, mz) = (
            _mm256_mul_pd(m, x),
            _mm256_mul_pd(m, y),
            _mm256_mul_pd(m, z),
        );
        acc[0] = _mm256_add_pd(acc[0], m);
        acc[1] = _mm256_add_pd(acc[1], mx);
        acc[2] = _mm256_add_pd(acc[2], my);
        acc[3] = _mm256_add_pd(acc[3], mz);
        acc[4] = _mm256_add_pd(acc[4], _mm256_mul_pd(mx, x));
        acc[5] = _mm256_add_pd(acc[5], _mm256_mul_pd(my, y));
        acc[6] = _mm256_add_pd(acc[6], _mm256_mul_pd(mz, z));
        acc[7] = _mm256_add_pd(acc[7], _mm256_mul_pd(mx, y));
        acc[8] = _mm256_add_pd(acc[8], _mm256_mul_pd(my, z));
        acc[9] = _mm256_add_pd(acc[9], _mm256_mul_pd(mz, x));
        i += LANES;
    }
    let mut lanes = [[0.0f64; LANES]; 10];
    for (dst, src) in lanes.iter_mut().zip(acc) {
        // SAFETY: `dst` holds 4 f64.
        unsafe { _mm256_storeu_pd(dst.as_mut_ptr(), src) };
    }
    let shift = |v: f64, o: f64| if SHIFT { v - o } else { v };
    for j in full..n {
        let (x, y, z, m) = (
            shift(xs[j], o[0]),
            shift(ys[j], o[1]),
            shift(zs[j], o[2]),
            ms[j],
        );
        let (mx, my, mz) = (m * x, m * y, m * z);
        let add = [
            m,
            mx,
            my,
            mz,
            mx * x,
            my * y,
            mz * z,
            mx * y,
            my * z,
            mz * x,
        ];
        for (q, v) in lanes.iter_mut().zip(add) {
            q[0] += v;
        }
    }
    lanes.map(|a| (a[0] + a[1]) + (a[2] + a[3]))
}

fn moments_block_dispatch(o: [f64; 3], b: Block<'_>) -> [f64; 10] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // +0 only: x − (+0) = x for every x, −0 included.
        let shift = o.iter().any(|v| v.to_bits() != 0);
        // SAFETY: the CPU supports AVX2 (checked just above).
        return unsafe {
            if shift {
                moments_block_avx2::<true>(o, b)
            } else {
                moments_block_avx2::<false>(o, b)
            }
        };
    }
    moments_block(o, b)
}

impl Kernel for MomentKernel {
    type Acc = Moments;

    fn accumulate(&self, acc: &mut Moments, b: Block<'_>) {
        let o = [self.origin.x, self.origin.y, self.origin.z];
        let r = moments_block_dispatch(o, b);
        acc.mass += r[0];
        acc.first += Vector3::new(r[1], r[2], r[3]);
        for (a, v) in acc.second.iter_mut().zip(&r[4..]) {
            *a += v;
        }
    }

    fn combine(&self, a: Moments, b: Moments) -> Moments {
        Moments {
            mass: a.mass + b.mass,
            first: a.first + b.first,
            second: std::array::from_fn(|k| a.second[k] + b.second[k]),
        }
    }
}

/// Moments of `src` about `origin`.
pub fn moments<S: ParticleSource + ?Sized>(src: &S, origin: Vector3<f64>) -> Moments {
    reduce(src, &MomentKernel { origin })
}

/// Mass properties of `src` by particle sums, in two passes (the centre,
/// then the second moments about the centre, so that no large parallel-
/// axis term cancels).
pub fn mass_properties<S: ParticleSource + ?Sized>(src: &S) -> Result<MassProperties, BodyError> {
    if src.is_empty() {
        return Err(BodyError::Empty {
            what: "particle set".into(),
        });
    }
    let first = moments(src, Vector3::zeros());
    crate::mass::check_mass("particle set", first.mass)?;
    let center = first.first / first.mass;
    let second = moments(src, center);
    // Correct the (round-off) residual first moment about the centre.
    let center = center + second.first / second.mass;
    Ok(MassProperties {
        mass: second.mass,
        center,
        inertia_g: second.inertia(),
    })
}

// ---------------------------------------------------------------- kinetics

/// Instantaneous rigid motion: angular velocity and acceleration of the
/// body, velocity and acceleration of its mass centre G (world axes,
/// absolute rates).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Motion {
    /// ω.
    pub omega: Vector3<f64>,
    /// α = dω/dt.
    pub alpha: Vector3<f64>,
    /// v̄, velocity of G.
    pub v_g: Vector3<f64>,
    /// ā, acceleration of G.
    pub a_g: Vector3<f64>,
}

impl Motion {
    /// Rotation about a fixed point `o`: v̄ = ω × r̄,
    /// ā = α × r̄ + ω × (ω × r̄) with r̄ = G − O.
    pub fn about_fixed_point(
        o: Vector3<f64>,
        g: Vector3<f64>,
        omega: Vector3<f64>,
        alpha: Vector3<f64>,
    ) -> Self {
        let r = g - o;
        Self {
            omega,
            alpha,
            v_g: omega.cross(&r),
            a_g: alpha.cross(&r) + omega.cross(&omega.cross(&r)),
        }
    }

    /// Velocity of the body point at `p` (G at `g`).
    pub fn velocity_at(&self, g: &Vector3<f64>, p: &Vector3<f64>) -> Vector3<f64> {
        self.v_g + self.omega.cross(&(p - g))
    }

    /// Acceleration of the body point at `p` (G at `g`).
    pub fn acceleration_at(&self, g: &Vector3<f64>, p: &Vector3<f64>) -> Vector3<f64> {
        let r = p - g;
        self.a_g + self.alpha.cross(&r) + self.omega.cross(&self.omega.cross(&r))
    }
}

/// Kinetic quantities of a body in a motion, about its centre G and a
/// reference point O (world axes).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Kinetics {
    /// Σ m.
    pub mass: f64,
    /// Linear momentum Σ m v = m v̄.
    pub momentum: Vector3<f64>,
    /// H_G = Σ m r′ × v′ (r′, v′ relative to G).
    pub h_g: Vector3<f64>,
    /// H_O = Σ m r × v (r from O).
    pub h_o: Vector3<f64>,
    /// T = Σ ½ m v².
    pub kinetic_energy: f64,
    /// Resultant force Σ m a = m ā.
    pub force: Vector3<f64>,
    /// Ḣ_G = Σ m r′ × a (the couple of the effective forces at G).
    pub hdot_g: Vector3<f64>,
    /// Σ m r × a: moment about O of the effective forces, which equals
    /// the moment about O of the external forces (= Ḣ_O when O is fixed
    /// or is G).
    pub moment_o: Vector3<f64>,
}

impl Kinetics {
    fn add(self, o: Self) -> Self {
        Self {
            mass: self.mass + o.mass,
            momentum: self.momentum + o.momentum,
            h_g: self.h_g + o.h_g,
            h_o: self.h_o + o.h_o,
            kinetic_energy: self.kinetic_energy + o.kinetic_energy,
            force: self.force + o.force,
            hdot_g: self.hdot_g + o.hdot_g,
            moment_o: self.moment_o + o.moment_o,
        }
    }
}

/// Kernel of the direct particle sums of [`Kinetics`].
#[derive(Debug, Clone, Copy)]
pub struct KineticKernel {
    /// The motion.
    pub motion: Motion,
    /// Mass centre G.
    pub center: Vector3<f64>,
    /// Reference point O.
    pub reference: Vector3<f64>,
}

impl Kernel for KineticKernel {
    type Acc = Kinetics;

    fn accumulate(&self, acc: &mut Kinetics, b: Block<'_>) {
        let Motion {
            omega,
            alpha,
            v_g,
            a_g,
        } = self.motion;
        let mut k = Kinetics::default();
        for i in 0..b.m.len() {
            let m = b.m[i];
            let p = Vector3::new(b.x[i], b.y[i], b.z[i]);
            let rp = p - self.center;
            let r = p - self.reference;
            let vp = omega.cross(&rp);
            let v = v_g + vp;
            let ap = alpha.cross(&rp) + omega.cross(&vp);
            let a = a_g + ap;
            k.mass += m;
            k.momentum += v * m;
            k.h_g += rp.cross(&vp) * m;
            k.h_o += r.cross(&v) * m;
            k.kinetic_energy += 0.5 * m * v.norm_squared();
            k.force += a * m;
            k.hdot_g += rp.cross(&a) * m;
            k.moment_o += r.cross(&a) * m;
        }
        *acc = acc.add(k);
    }

    fn combine(&self, a: Kinetics, b: Kinetics) -> Kinetics {
        a.add(b)
    }
}

/// Direct particle sums of the kinetic quantities of `src` in `motion`,
/// about its centre `center` and the reference point `reference`.
pub fn kinetics<S: ParticleSource + ?Sized>(
    src: &S,
    motion: &Motion,
    center: Vector3<f64>,
    reference: Vector3<f64>,
) -> Kinetics {
    reduce(
        src,
        &KineticKernel {
            motion: *motion,
            center,
            reference,
        },
    )
}

/// The same quantities from the rigid-body formulas: H_G = I_G ω,
/// H_O = r̄ × m v̄ + H_G, T = ½ m v̄² + ½ ω·I_G ω, Ḣ_G = I_G α + ω × (I_G ω),
/// ΣM_O = r̄ × m ā + Ḣ_G, ΣF = m ā (r̄ = G − O).
pub fn rigid_kinetics(
    props: &MassProperties,
    motion: &Motion,
    reference: Vector3<f64>,
) -> Kinetics {
    let m = props.mass;
    let i = props.inertia_g;
    let rbar = props.center - reference;
    let h_g = i.apply(&motion.omega);
    let hdot_g = i.apply(&motion.alpha) + motion.omega.cross(&h_g);
    Kinetics {
        mass: m,
        momentum: motion.v_g * m,
        h_g,
        h_o: rbar.cross(&(motion.v_g * m)) + h_g,
        kinetic_energy: 0.5 * m * motion.v_g.norm_squared() + 0.5 * motion.omega.dot(&h_g),
        force: motion.a_g * m,
        hdot_g,
        moment_o: rbar.cross(&(motion.a_g * m)) + hdot_g,
    }
}

#[cfg(test)]
mod kernel {
    use super::*;

    /// The AVX2 kernel gives the same bits as the portable one, for every
    /// tail length, with and without an origin shift.
    #[test]
    fn avx2_moments_have_the_bits_of_the_portable_kernel() {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            let mut s = 0x2545_F491_4F6C_DD1Du64;
            let mut next = || {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            };
            for n in [0, 1, 3, 4, 5, 7, 64, 511, 512] {
                let v: Vec<Vec<f64>> = (0..4).map(|_| (0..n).map(|_| next()).collect()).collect();
                let m: Vec<f64> = v[3].iter().map(|x| x + 1.0).collect();
                let b = Block {
                    x: &v[0],
                    y: &v[1],
                    z: &v[2],
                    m: &m,
                };
                for o in [[0.0; 3], [0.3, -1.2, 2.5], [-0.0, 0.0, 0.0]] {
                    let a = moments_block(o, b).map(f64::to_bits);
                    // SAFETY: AVX2 is available (checked above).
                    let w = unsafe {
                        if o.iter().any(|v| v.to_bits() != 0) {
                            moments_block_avx2::<true>(o, b)
                        } else {
                            moments_block_avx2::<false>(o, b)
                        }
                    }
                    .map(f64::to_bits);
                    assert_eq!(a, w, "n = {n}, o = {o:?}");
                }
            }
        }
    }
}

#[cfg(all(test, feature = "slow-tests"))]
mod slow {
    use super::*;
    use crate::{Body, Discretization, DiscretizedBody, Pose, Primitive};

    /// 10⁸ lazily generated particles: the box's closed-form midpoint sum.
    #[test]
    fn hundred_million_particles_without_storing_them() {
        let (a, m) = (1.5, 2.0);
        let body = Body::try_new(Primitive::Prism { a, b: a, c: a }, m, Pose::identity()).unwrap();
        let n = 465; // 465³ ≈ 1.005 × 10⁸
        let src = DiscretizedBody::new(&body, &Discretization::midpoint(n));
        assert!(src.len() >= 100_000_000);
        let mo = moments(&src, Vector3::zeros());
        let nf = n as f64;
        let expected = m * a * a / 12.0 * (1.0 - 1.0 / (nf * nf));
        assert!((mo.mass - m).abs() <= 1e-12 * m);
        assert!((mo.second[0] - expected).abs() <= 1e-12 * expected);
    }
}
