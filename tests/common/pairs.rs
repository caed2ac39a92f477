//! The reference pairs of `curves/reference-pairs.list`, shared by the
//! morph tests and the examples (`#[path]`-included).

/// The pairs of `curves/reference-pairs.list` ("source target" per line,
/// `#` comments).
pub(crate) fn reference_pairs() -> Vec<(String, String)> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("curves/reference-pairs.list");
    let text = std::fs::read_to_string(&path).expect("curves/reference-pairs.list is readable");
    text.lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty())
        .filter_map(|l| l.split_once(' '))
        .map(|(a, b)| (a.trim().to_string(), b.trim().to_string()))
        .collect()
}
