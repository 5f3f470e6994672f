//! Deterministic worst-case search for the stated error bounds (issue 21,
//! item 6): hill climbs from seeded, *targeted* starts (near the mirror
//! direction where `x^n` is steepest, grazing lights, the highest exponents,
//! colours near saturation, attenuation extremes), the approach of the
//! `accuracy` harness for the general lighting path, shared by the tests
//! of every kernel with a bound (`lighting_accuracy`, `incremental_phong`,
//! `quadratic_accuracy`, `normal_mapping`, `texture_mapping`).
//!
//! A climb moves the current point by a random amount (log-uniform between
//! 10⁻⁴ and 10⁻¹ of the parameter's scale) and keeps the move when the
//! *unquantised* error does not decrease (the quantised error is flat almost
//! everywhere; equal values let the climb cross plateaus). Every evaluated
//! point's quantised error counts towards the worst. Same seed, same result.

#![allow(dead_code)]

/// A small deterministic generator (xorshift64*).
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    /// Uniform in [0, 1).
    pub fn f(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f()
    }
    /// Uniform in `a..=b`.
    pub fn int(&mut self, a: i64, b: i64) -> i64 {
        a + ((b - a + 1) as f64 * self.f()) as i64
    }
    /// `±1`.
    pub fn sign(&mut self) -> f64 {
        if self.f() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
    /// A step size: log-uniform between 10⁻⁴ and 10⁻¹.
    pub fn step(&mut self) -> f64 {
        10f64.powf(-1.0 - 3.0 * self.f())
    }
}

/// What a search found: the largest quantised error, where, and the effort.
#[derive(Clone, Debug)]
pub struct Worst<P> {
    pub error: u32,
    pub at: Option<P>,
    pub evaluations: usize,
}

/// Hill climbs of `steps` moves from each start. `perturb(p, amount, rng)`
/// moves a point by about `amount` (a step size, [`Rng::step`]); `score(p)`
/// is `None` outside the bound's domain (excluded points), else the
/// unquantised error the climb follows and the quantised error the bound
/// limits.
pub fn climb<P: Clone>(
    starts: &[P],
    steps: u32,
    seed: u64,
    mut perturb: impl FnMut(&P, f64, &mut Rng) -> P,
    mut score: impl FnMut(&P) -> Option<(f64, u32)>,
) -> Worst<P> {
    let mut rng = Rng::new(seed);
    let mut worst = Worst {
        error: 0,
        at: None,
        evaluations: 0,
    };
    let note = |p: &P, q: u32, worst: &mut Worst<P>| {
        worst.evaluations += 1;
        if worst.at.is_none() || q > worst.error {
            worst.error = q;
            worst.at = Some(p.clone());
        }
    };
    for s in starts {
        let Some((mut e, q)) = score(s) else {
            continue;
        };
        note(s, q, &mut worst);
        let mut p = s.clone();
        for _ in 0..steps {
            let amount = rng.step();
            let t = perturb(&p, amount, &mut rng);
            let Some((et, qt)) = score(&t) else {
                continue;
            };
            note(&t, qt, &mut worst);
            if et >= e {
                (e, p) = (et, t);
            }
        }
    }
    worst
}

// ---- vectors (f64) ----------------------------------------------------------------

pub type V3 = [f64; 3];

pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn norm(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    a.map(|c| c / l)
}

pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A unit vector at angle `theta` from unit `axis`, azimuth `phi`.
pub fn around(axis: V3, theta: f64, phi: f64) -> V3 {
    let a = norm(axis);
    let helper = if a[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let u = norm(cross(a, helper));
    let w = cross(a, u);
    core::array::from_fn(|i| {
        a[i] * theta.cos() + (u[i] * phi.cos() + w[i] * phi.sin()) * theta.sin()
    })
}

/// `v` turned by a random angle up to `amount` radians (its length kept).
pub fn nudge(v: V3, amount: f64, rng: &mut Rng) -> V3 {
    let l = dot(v, v).sqrt();
    around(v, amount * rng.f(), rng.range(0.0, std::f64::consts::TAU)).map(|c| c * l)
}

/// The direction towards the light whose mirror direction about `n` is `v`
/// (`R = V`, and `H = N` for Blinn-Phong): `2(N·V)N − V`.
pub fn mirror(n: V3, v: V3) -> V3 {
    let n = norm(n);
    let k = 2.0 * dot(n, v);
    norm(core::array::from_fn(|i| k * n[i] - v[i]))
}

pub fn f32s(v: V3) -> [f32; 3] {
    v.map(|c| c as f32)
}

pub fn f64s(v: [f32; 3]) -> V3 {
    v.map(f64::from)
}
