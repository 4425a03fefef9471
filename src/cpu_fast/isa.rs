//! Which vector instructions the fast CPU path runs on, chosen at run time.

/// The instruction set of the fast path's per-vertex loops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Isa {
    /// x86-64 AVX2 with FMA: eight vertices per register, fused multiply-adds.
    Avx2Fma,
    /// One vertex at a time, the f32 twins' own arithmetic (`crate::cpu`); every target.
    Scalar,
}

impl Isa {
    /// The best instruction set this CPU has.
    pub fn detect() -> Isa {
        if Isa::Avx2Fma.is_available() { Isa::Avx2Fma } else { Isa::Scalar }
    }

    /// Whether this CPU can run `self` ([`Isa::Scalar`] always can).
    pub fn is_available(self) -> bool {
        match self {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2Fma => is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma"),
            #[cfg(not(target_arch = "x86_64"))]
            Isa::Avx2Fma => false,
            Isa::Scalar => true,
        }
    }

    /// `self` if this CPU has it, else [`Isa::Scalar`]: what a loop asked to run on `self` runs
    /// on.
    pub fn or_scalar(self) -> Isa {
        if self.is_available() { self } else { Isa::Scalar }
    }

    /// Vertices per register.
    pub fn lanes(self) -> usize {
        match self {
            Isa::Avx2Fma => 8,
            Isa::Scalar => 1,
        }
    }

    /// A short name for reports: `"avx2+fma"` or `"scalar"`.
    pub fn name(self) -> &'static str {
        match self {
            Isa::Avx2Fma => "avx2+fma",
            Isa::Scalar => "scalar",
        }
    }
}
