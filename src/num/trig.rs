//! `const` trigonometry: the mesh generators and the fixed camera's tables
//! are built at compile time, where `libm` cannot run.

/// `(sin x, cos x)` in `f64` for `const fn` generators: reduced to
/// `|r| ≤ π/4` around a multiple of π/2, then Taylor series to the 18th
/// order (error below 10⁻¹⁵ for `|x| ≤ 100`).
pub(crate) const fn sin_cos(x: f64) -> (f64, f64) {
    let half_pi = core::f64::consts::FRAC_PI_2;
    let q = x / half_pi;
    let k = if q >= 0.0 {
        (q + 0.5) as i64
    } else {
        (q - 0.5) as i64
    };
    let r = x - k as f64 * half_pi;
    let r2 = r * r;
    // sin r = r − r³/3! + …, cos r = 1 − r²/2! + …
    let mut s = r;
    let mut c = 1.0;
    let mut ts = r;
    let mut tc = 1.0;
    let mut n = 1;
    while n <= 9 {
        ts = -ts * r2 / ((2 * n) as f64 * (2 * n + 1) as f64);
        tc = -tc * r2 / ((2 * n - 1) as f64 * (2 * n) as f64);
        s += ts;
        c += tc;
        n += 1;
    }
    match k.rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn const_sin_cos_matches_libm() {
        let mut x = -20.0f64;
        while x < 20.0 {
            let (s, c) = sin_cos(x);
            assert!((s - libm::sin(x)).abs() < 1e-14, "{x}");
            assert!((c - libm::cos(x)).abs() < 1e-14, "{x}");
            x += 0.0137;
        }
    }
}
