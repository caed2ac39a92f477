//! [`immerse_render::remove_partial_outputs`] marks the whole process as
//! interrupted, so this test has a test binary of its own.

/// An interrupt handler removes the temporary file of an unfinished
/// output, and later writers fail instead of starting new ones.
#[test]
fn partial_outputs_are_removed_on_request() {
    use std::io::Write;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.json");
    let mut out = immerse_render::OutputFile::create(&path, false).unwrap();
    out.write_all(&vec![b' '; 1 << 20]).unwrap();
    out.flush().unwrap();
    let temps = || {
        std::fs::read_dir(dir.path())
            .unwrap()
            .filter(|e| {
                let e = e.as_ref().unwrap();
                e.file_name().to_string_lossy().starts_with(".immerse-")
            })
            .count()
    };
    assert_eq!(temps(), 1);
    assert!(immerse_render::remove_partial_outputs() >= 1);
    assert_eq!(temps(), 0);
    drop(out);
    assert!(!path.exists());
    // Later writers are refused (this is why the test has its own binary).
    assert!(immerse_render::OutputFile::create(&dir.path().join("later"), false).is_err());
}
