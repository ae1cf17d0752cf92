//! Two f64 lanes, for evaluating two outputs of a tape at once: a packed
//! SSE2 register on x86-64 (part of its baseline: no feature to detect),
//! a pair of scalars elsewhere. Each operation is the IEEE operation on
//! each lane, as the scalar one is, so an output evaluated in a lane has
//! the bits it has evaluated alone. LLVM does not pair the two outputs by
//! itself: their operands are gathered from scattered slots, which its
//! cost model rejects, and two three-term sums took ~82 instructions
//! where the pair takes ~70.

use std::ops::{Add, Mul, Sub};

#[cfg(target_arch = "x86_64")]
mod imp {
    use std::arch::x86_64::{
        __m128d, _mm_add_pd, _mm_cvtsd_f64, _mm_mul_pd, _mm_set_pd, _mm_sub_pd, _mm_unpackhi_pd,
    };

    #[derive(Clone, Copy)]
    pub(super) struct Raw(__m128d);

    // SAFETY (each block below): the intrinsics are `unsafe` only as they
    // need SSE2, which every x86-64 processor has (the target's baseline);
    // they read and write no memory.
    impl Raw {
        #[inline(always)]
        pub(super) fn new(lo: f64, hi: f64) -> Raw {
            Raw(unsafe { _mm_set_pd(hi, lo) })
        }
        #[inline(always)]
        pub(super) fn add(self, o: Raw) -> Raw {
            Raw(unsafe { _mm_add_pd(self.0, o.0) })
        }
        #[inline(always)]
        pub(super) fn sub(self, o: Raw) -> Raw {
            Raw(unsafe { _mm_sub_pd(self.0, o.0) })
        }
        #[inline(always)]
        pub(super) fn mul(self, o: Raw) -> Raw {
            Raw(unsafe { _mm_mul_pd(self.0, o.0) })
        }
        #[inline(always)]
        pub(super) fn lo(self) -> f64 {
            unsafe { _mm_cvtsd_f64(self.0) }
        }
        #[inline(always)]
        pub(super) fn hi(self) -> f64 {
            unsafe { _mm_cvtsd_f64(_mm_unpackhi_pd(self.0, self.0)) }
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
mod imp {
    #[derive(Clone, Copy)]
    pub(super) struct Raw([f64; 2]);

    impl Raw {
        #[inline(always)]
        pub(super) fn new(lo: f64, hi: f64) -> Raw {
            Raw([lo, hi])
        }
        #[inline(always)]
        pub(super) fn add(self, o: Raw) -> Raw {
            Raw([self.0[0] + o.0[0], self.0[1] + o.0[1]])
        }
        #[inline(always)]
        pub(super) fn sub(self, o: Raw) -> Raw {
            Raw([self.0[0] - o.0[0], self.0[1] - o.0[1]])
        }
        #[inline(always)]
        pub(super) fn mul(self, o: Raw) -> Raw {
            Raw([self.0[0] * o.0[0], self.0[1] * o.0[1]])
        }
        #[inline(always)]
        pub(super) fn lo(self) -> f64 {
            self.0[0]
        }
        #[inline(always)]
        pub(super) fn hi(self) -> f64 {
            self.0[1]
        }
    }
}

/// Two f64 lanes, `(lo, hi)`.
#[derive(Clone, Copy)]
pub(super) struct Lanes(imp::Raw);

impl Lanes {
    #[inline(always)]
    pub(super) fn new(lo: f64, hi: f64) -> Lanes {
        Lanes(imp::Raw::new(lo, hi))
    }

    /// The same value in both lanes.
    #[inline(always)]
    pub(super) fn splat(v: f64) -> Lanes {
        Lanes::new(v, v)
    }

    #[inline(always)]
    pub(super) fn lo(self) -> f64 {
        self.0.lo()
    }

    #[inline(always)]
    pub(super) fn hi(self) -> f64 {
        self.0.hi()
    }
}

impl Add for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn add(self, o: Lanes) -> Lanes {
        Lanes(self.0.add(o.0))
    }
}

impl Sub for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn sub(self, o: Lanes) -> Lanes {
        Lanes(self.0.sub(o.0))
    }
}

impl Mul for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn mul(self, o: Lanes) -> Lanes {
        Lanes(self.0.mul(o.0))
    }
}

#[cfg(test)]
mod tests {
    use super::Lanes;

    /// Each lane gets the bits of the scalar operation, rounding included.
    #[test]
    fn each_lane_is_the_scalar_operation() {
        let (a, b) = (0.1_f64, 1e16_f64);
        let (c, d) = (0.7_f64, -3.3_f64);
        let (x, y) = (Lanes::new(a, b), Lanes::new(c, d));
        for (v, lo, hi) in [
            (x + y, a + c, b + d),
            (x - y, a - c, b - d),
            (x * y, a * c, b * d),
        ] {
            assert_eq!(v.lo().to_bits(), lo.to_bits());
            assert_eq!(v.hi().to_bits(), hi.to_bits());
        }
        let z = Lanes::splat(-0.0) + Lanes::new(0.0, -0.0);
        assert_eq!(
            (z.lo().to_bits(), z.hi().to_bits()),
            (0.0_f64.to_bits(), (-0.0_f64).to_bits())
        );
    }
}
