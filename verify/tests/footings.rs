//! Rigid footings on a weightless frictional soil under a surcharge: the
//! collapse load of the Mohr–Coulomb soil and the block contact against the
//! exact N_q, for a strip (`scenes/strip_footing.ron`) and a circle
//! (`scenes/circular_footing.ron`).

mod common;

use mpdem_verify::footing::{self, Footing};

/// (p + q) / (N_q q) over the plateau's window, for `footing`'s scene at
/// twice its cell.
fn ratio_at_twice_the_cell(footing: Footing) -> f64 {
    let base = common::load_scene(footing.scene_file());
    let sim = common::run_scene(&mpdem_verify::at_cell(&base, 2.0));
    let curve = footing::pressure_curve(&sim, footing).expect("curve");
    footing::plateau(&curve).expect("plateau") / footing.exact_nq()
}

#[test]
fn a_strip_footing_collapses_near_prandtls_load_at_a_coarse_cell() {
    // B/5, two and a half cells under the half footing. The collapse load
    // converges at first order from above: the full case measures +15% at
    // B/10 and +7% at B/20, which predict about +30% here. The band catches
    // a soil or contact that collapses below the exact load, or far above
    // it, not the precise excess.
    let ratio = ratio_at_twice_the_cell(Footing::Strip);
    println!("strip: (p + q) / (N_q q) at B/5: {ratio:.3}");
    assert!((1.05..1.6).contains(&ratio), "{ratio}");
}

#[test]
fn a_circular_footing_collapses_near_its_exact_load_at_a_coarse_cell() {
    // B/5, two and a half cells under the radius, where the rigid edge's
    // excess is large: the full case measures +27% at B/10 and +10% at
    // B/20, and this cell +71%. The band, ±20% about that, catches a circle
    // that collapses at the strip's load (0.59 of the circle's N_q, so
    // about 1.0 here), one whose hoop stress is lost, or a contact far off.
    let ratio = ratio_at_twice_the_cell(Footing::Circle);
    println!("circle: (p + q) / (N_q q) at B/5: {ratio:.3}");
    assert!((1.4..2.05).contains(&ratio), "{ratio}");
}

#[test]
#[ignore = "the full strip footing case at three cells: about 4 minutes on 2 cores"]
fn full_strip_footing_converges_to_prandtls_load() {
    common::verify_case("strip_footing");
}

#[test]
#[ignore = "the full circular footing case at three cells: about 8 minutes on 2 cores"]
fn full_circular_footing_converges_to_its_exact_load() {
    common::verify_case("circular_footing");
}
