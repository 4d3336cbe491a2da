//! `mpdem verify --report DIR` writes a Markdown page of the cases' checks
//! and a PNG per figure: here for made-up reports, without a simulation.

mod common;

use mpdem_verify::report::write_report;
use mpdem_verify::{CaseReport, Check, Curve, Figure, Measured, VerifyError};

/// A wave case with a met, a missed and a reported check and two figures,
/// and a toppling case that could not be measured.
fn reports() -> Vec<CaseReport> {
    let computed: Vec<(f64, f64)> = (0..=20)
        .map(|k| (0.05 * k as f64, 0.01 * k as f64))
        .collect();
    let reference = computed.iter().map(|&(t, v)| (t, 1.05 * v)).collect();
    let figure = Figure::new("Made-up wave", "time t (s)", "velocity v (m/s)")
        .with(Curve::computed("mpdem", computed.clone()))
        .with(Curve::reference("exact", reference));
    let band = Figure::new("Made-up error", "time t (s)", "error (%)")
        .with(Curve::computed("mpdem", computed))
        .with(Curve::reference(
            "target: within ±2%",
            vec![
                (0.0, 2.0),
                (1.0, 2.0),
                (f64::NAN, f64::NAN),
                (0.0, -2.0),
                (1.0, -2.0),
            ],
        ));
    let checks = vec![
        Check::judged("max |v − v_exact|", "1.85%", "≤ 2%", true)
            .because("the floor of the finite-strain response"),
        Check::judged("F = π E* a²", "12%", "< 10%", false),
        Check::reported("run-out", "0.51", "0.60 (published)"),
    ];
    vec![
        CaseReport {
            case: "wave_1d",
            outcome: Ok(Measured {
                checks,
                figures: vec![figure, band],
            }),
            seconds: 12.3,
        },
        CaseReport {
            case: "toppling",
            outcome: Err(VerifyError::Measurement("no probe sample at 0.3 s".into())),
            seconds: 0.4,
        },
    ]
}

/// (width, height) of a PNG file, from its IHDR chunk.
fn png_size(path: &std::path::Path) -> (u32, u32) {
    let bytes = std::fs::read(path).expect("the figure");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", path.display());
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

#[test]
fn report_has_the_summary_the_checks_the_failure_and_the_figures() {
    let dir = common::TempFolder::new("verify-report");
    let reports = reports();
    let page = write_report(&dir, "mpdem verify --report docs/", &reports).expect("the report");
    assert_eq!(page, dir.join("verification.md"));
    let md = std::fs::read_to_string(&page).unwrap();
    for expected in [
        "# Verification",
        "`mpdem verify --report docs/`",
        "| [wave_1d](#wave_1d) | paper 4.1 | 1 | 1 | 1 |",
        "| [toppling](#toppling) | paper 4.2.1 | could not be measured | | |",
        "2 cases: 1 check met, 1 missed, 1 reported; 1 case could not be measured.",
        "| max \\|v − v_exact\\| | 1.85% | ≤ 2% | the floor of the finite-strain response | met |",
        "| F = π E\\* a² | 12% | < 10% | | missed |",
        "| run-out | 0.51 | 0.60 (published) | | reported |",
        "Could not be measured: no probe sample at 0.3 s.",
        "![Made-up wave](verification/wave_1d.png)",
        "![Made-up error](verification/wave_1d_2.png)",
        "doi:10.1016/j.cma.2022.115814",
    ] {
        assert!(md.contains(expected), "no {expected:?} in\n{md}");
    }
    // No wall-clock time: the page depends on the checks only.
    assert!(!md.contains("12.3"), "{md}");
    for figure in ["wave_1d.png", "wave_1d_2.png"] {
        assert_eq!(png_size(&dir.join("verification").join(figure)), (800, 500));
    }
    assert!(!dir.join("verification/toppling.png").exists());

    // The same reports give the same page.
    write_report(&dir, "mpdem verify --report docs/", &reports).unwrap();
    assert_eq!(std::fs::read_to_string(&page).unwrap(), md);
}
