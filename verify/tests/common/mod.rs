//! Helpers shared by the verification suite's tests: the engine's test
//! helpers, and a verify case run as a test.
#![allow(dead_code)] // each test binary uses a different subset

#[path = "../../../tests/common/mod.rs"]
mod engine;

pub use engine::*;

/// Runs the `mpdem verify` case `name` on the scenes of `scenes/` (plots go
/// to `out/verify/`), prints its report and asserts that it was measured
/// and that no check missed its target.
pub fn verify_case(name: &str) -> mpdem_verify::CaseReport {
    let case = mpdem_verify::case(name).expect("a verify case");
    let root = repository_root();
    let quiet = |_: mpdem_verify::RunEvent| {};
    let ctx = mpdem_verify::Context::new(&root.join("scenes"), &root.join("out/verify"), &quiet);
    let report = mpdem_verify::CaseReport::run(case, &ctx);
    print!("{report}");
    assert!(report.all_met(), "{name}: a target is missed, see above");
    report
}
