//! The pair lists of `curves/` (`reference-pairs.list`,
//! `motion-pairs.list`), shared by the morph tests and the examples.

/// The pairs of `curves/reference-pairs.list` ("source target" per line,
/// `#` comments).
pub fn reference_pairs() -> Vec<(String, String)> {
    pair_list("reference-pairs.list")
}

/// The pairs of `curves/motion-pairs.list`: self-overlapping pairs for
/// measuring motion (detour, unwind).
pub fn motion_pairs() -> Vec<(String, String)> {
    pair_list("motion-pairs.list")
}

fn pair_list(name: &str) -> Vec<(String, String)> {
    let path = crate::workspace_root().join("curves").join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{} is not readable: {e}", path.display()));
    text.lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty())
        .filter_map(|l| l.split_once(' '))
        .map(|(a, b)| (a.trim().to_string(), b.trim().to_string()))
        .collect()
}

/// A pair of curves read from `curves/`: its name (`a → b`), and the
/// source's and target's points, cleaned and oriented.
#[cfg(feature = "immerse")]
pub type CurvePair = (String, Vec<immerse::Point>, Vec<immerse::Point>);

/// The pairs of the set `motion` or `reference`, read; `None` for another
/// name.
///
/// # Panics
///
/// Where a curve of the list is not readable.
#[cfg(feature = "immerse")]
pub fn read_set(set: &str) -> Option<Vec<CurvePair>> {
    let list = match set {
        "motion" => motion_pairs(),
        "reference" => reference_pairs(),
        _ => return None,
    };
    let dir = crate::workspace_root().join("curves");
    let read = |name: &str| {
        immerse::Curve::from_path(dir.join(name))
            .unwrap_or_else(|e| panic!("curves/{name} is not readable: {e}"))
            .points
    };
    Some(
        list.into_iter()
            .map(|(a, b)| (format!("{a} → {b}"), read(&a), read(&b)))
            .collect(),
    )
}
