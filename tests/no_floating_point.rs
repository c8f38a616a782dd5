//! SPEC §16: no `f32`/`f64` in planning or on the per-cycle path, so a plan computed on a host
//! is the plan a microcontroller computes, bit for bit. Floats live at the edges only: the
//! register conversions (`src/format/`) and the `reference` yardstick. This test reads the
//! sources of every generator and fails on a floating-point type outside comments (a doc example
//! may convert a result to `f64` for display: doc comments are comments).

/// The generators' sources, by path.
const SOURCES: &[(&str, &str)] = &[
    ("src/scurve/mod.rs", include_str!("../src/scurve/mod.rs")),
    (
        "src/scurve/search.rs",
        include_str!("../src/scurve/search.rs"),
    ),
    (
        "src/scurve/shape.rs",
        include_str!("../src/scurve/shape.rs"),
    ),
    (
        "src/scurve/remainder.rs",
        include_str!("../src/scurve/remainder.rs"),
    ),
    (
        "src/scurve/schedule.rs",
        include_str!("../src/scurve/schedule.rs"),
    ),
    ("src/scurve/stop.rs", include_str!("../src/scurve/stop.rs")),
    (
        "src/trapezoidal/mod.rs",
        include_str!("../src/trapezoidal/mod.rs"),
    ),
    (
        "src/trapezoidal/landing.rs",
        include_str!("../src/trapezoidal/landing.rs"),
    ),
    ("src/velocity.rs", include_str!("../src/velocity.rs")),
    ("src/predict.rs", include_str!("../src/predict.rs")),
    ("src/gearing.rs", include_str!("../src/gearing.rs")),
    ("src/steps.rs", include_str!("../src/steps.rs")),
    (
        "src/scurve/predict.rs",
        include_str!("../src/scurve/predict.rs"),
    ),
    (
        "src/trapezoidal/predict.rs",
        include_str!("../src/trapezoidal/predict.rs"),
    ),
    ("src/state.rs", include_str!("../src/state.rs")),
    ("src/waveform.rs", include_str!("../src/waveform.rs")),
    ("src/mcx514/mod.rs", include_str!("../src/mcx514/mod.rs")),
    (
        "src/mcx514/trapezoidal/mod.rs",
        include_str!("../src/mcx514/trapezoidal/mod.rs"),
    ),
    (
        "src/mcx514/trapezoidal/rule.rs",
        include_str!("../src/mcx514/trapezoidal/rule.rs"),
    ),
    (
        "src/mcx514/trapezoidal/plan.rs",
        include_str!("../src/mcx514/trapezoidal/plan.rs"),
    ),
    ("src/replay.rs", include_str!("../src/replay.rs")),
    ("src/division.rs", include_str!("../src/division.rs")),
    (
        "src/mcx514/scurve/mod.rs",
        include_str!("../src/mcx514/scurve/mod.rs"),
    ),
    (
        "src/mcx514/scurve/ramp.rs",
        include_str!("../src/mcx514/scurve/ramp.rs"),
    ),
    (
        "src/mcx514/scurve/rule.rs",
        include_str!("../src/mcx514/scurve/rule.rs"),
    ),
    (
        "src/mcx514/scurve/plan.rs",
        include_str!("../src/mcx514/scurve/plan.rs"),
    ),
    (
        "src/interpolation/mod.rs",
        include_str!("../src/interpolation/mod.rs"),
    ),
    (
        "src/interpolation/drive.rs",
        include_str!("../src/interpolation/drive.rs"),
    ),
    (
        "src/interpolation/linear.rs",
        include_str!("../src/interpolation/linear.rs"),
    ),
];

/// Whether `code` names `word` as a whole token (not inside a longer identifier).
fn names(code: &str, word: &str) -> bool {
    let is_ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    code.match_indices(word).any(|(at, _)| {
        let before = code[..at].chars().next_back();
        let after = code[at + word.len()..].chars().next();
        !before.is_some_and(is_ident) && !after.is_some_and(is_ident)
    })
}

#[test]
fn no_floating_point_in_planning_or_stepping() {
    let mut found = Vec::new();
    for (path, source) in SOURCES {
        for (number, line) in source.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for word in ["f32", "f64", "Float"] {
                if names(code, word) {
                    found.push(format!("{path}:{}: {}", number + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "floating point in a generator:\n{}",
        found.join("\n")
    );
}

/// Every source file of the S-curve (`src/scurve/`, its folders included, read from disk so
/// that a file added there is checked without being listed): none names a floating-point type
/// outside comments and its unit tests (`#[cfg(test)]` on, where a test may compute a float
/// reference). Issue #11: the S-curve module's planning is integer-only.
#[test]
fn no_floating_point_anywhere_in_the_s_curve() {
    fn sources(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                sources(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/scurve");
    let mut paths = Vec::new();
    sources(&root, &mut paths);
    // The planners and the table at least (a walk that found nothing would pass).
    for file in [
        "mod.rs",
        "pure_jerk.rs",
        "volumes.rs",
        "tiny/mod.rs",
        "tiny/table.rs",
    ] {
        assert!(paths.contains(&root.join(file)), "{file} not found");
    }
    let mut found = Vec::new();
    for path in &paths {
        let source = std::fs::read_to_string(path).unwrap();
        let lines: Vec<&str> = source.lines().collect();
        for (number, line) in lines.iter().enumerate() {
            // The file's unit tests: a top-level `#[cfg(test)]` module (not a test-only item
            // within the code, which is indented).
            let next = lines.get(number + 1).copied().unwrap_or("");
            if *line == "#[cfg(test)]" && next.starts_with("mod ") {
                break;
            }
            let code = line.split("//").next().unwrap_or("");
            for word in ["f32", "f64", "Float"] {
                if names(code, word) {
                    found.push(format!(
                        "{}:{}: {}",
                        path.display(),
                        number + 1,
                        line.trim()
                    ));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "floating point in the S-curve:\n{}",
        found.join("\n")
    );
}

/// The check itself finds what it must (and not what it must not).
#[test]
fn the_check_finds_floats() {
    assert!(names("let x: f64 = 1.0;", "f64"));
    assert!(names("(x as f32)", "f32"));
    assert!(!names("let f64_bits = 3;", "f64"));
    assert!(!names("let my_f64 = 3;", "f64"));
}
