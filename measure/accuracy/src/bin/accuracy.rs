//! Prints each tier's error against the f64 reference, per lighting term, in 8-bit
//! LSBs: the largest channel error and the mean of the per-sample largest channel
//! error over random samples, then the largest error a worst-case search finds (hill
//! climbs from the worst samples, near the highlight, with interpolated normals, and
//! from targeted starts: the mirror direction at the band's highest exponent, grazing
//! lights, colours near saturation, attenuation extremes).
//! The README's accuracy table and the bounds of `tests/lighting/lighting_accuracy.rs` come
//! from this program:
//!
//! ```sh
//! cargo run --release -p fixshade-accuracy --bin accuracy
//! ```

use fixshade_testkit::scenes;

use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade_testkit::scenes::{measure, search, Band, Term, BANDS, TERMS};

const CASES: u32 = 20_000;
/// The search: random samples, then hill climbs of so many steps from the worst.
const SEARCH: (u32, usize, u32) = (20_000, 32, 600);

fn cell<S: Scalar>(term: Term, band: Band, seed: u64) -> String {
    let (max, mean, _) = measure::<S>(term, band, CASES, seed);
    let (cases, climbs, steps) = SEARCH;
    let (worst, _) = search::<S>(term, band, cases, climbs, steps, seed + 7);
    // and from the targeted starts (mirror direction, grazing, saturation,
    // attenuation extremes) of tests/lighting/lighting_accuracy.rs, with more effort
    let worst = worst.max(scenes::targeted_search::<S>(term, band, 64, 600, seed + 11).0);
    format!(" {max} / {mean:.3} / **{worst}** |")
}

fn main() {
    println!("Error against the f64 reference in 8-bit LSBs: max / mean over {CASES} random");
    println!(
        "samples per cell / **largest error of a worst-case search** ({} samples, then",
        SEARCH.0
    );
    println!(
        "{} hill climbs of {} steps from the worst of them).",
        SEARCH.1, SEARCH.2
    );
    println!(
        "(normals within 75° of the viewer, half of them interpolated (length 0.6..1), half of"
    );
    println!("the lights near the highlight; for distances, attenuation and fog half of the samples span");
    println!(
        "the whole legal range; samples within 1e-3 of N·L = 0 or a spot cone's edge excluded;"
    );
    println!("generator: testkit/src/scenes.rs)\n");
    println!(
        "| term | {} | {} | {} | {} | {} | {} |",
        Q14::<1>::NAME,
        Q14::<2>::NAME,
        Q30::<3>::NAME,
        f32::NAME,
        F32Fast::<1>::NAME,
        F32Fast::<2>::NAME
    );
    println!("|---|---|---|---|---|---|---|");
    for (i, term) in TERMS.iter().enumerate() {
        let specular = matches!(
            term,
            Term::Phong | Term::BlinnPhong | Term::Fresnel | Term::Everything
        );
        let bands: &[Band] = if specular { &BANDS } else { &[Band::Low] };
        for &band in bands {
            let seed = 1000 + 10 * i as u64 + band as u64;
            let label = if specular {
                let (lo, hi) = band.range();
                format!("{}, n = {lo}..{hi}", term.name())
            } else {
                term.name().to_string()
            };
            let mut line = format!("| {label} |");
            line += &cell::<Q14<1>>(*term, band, seed);
            line += &cell::<Q14<2>>(*term, band, seed);
            line += &cell::<Q30<3>>(*term, band, seed);
            line += &cell::<f32>(*term, band, seed);
            line += &cell::<F32Fast<1>>(*term, band, seed);
            line += &cell::<F32Fast<2>>(*term, band, seed);
            println!("{line}");
        }
    }
}
