//! Figures the docs give that a test computes: the test asserts that the docs say exactly
//! what it measured (two significant digits, `brdfbake::numfmt::fig`), so the docs and the
//! measurement cannot drift apart.

#![allow(dead_code)]

/// Fails unless `doc` (a path relative to the repository) contains `phrase`.
pub fn assert_says(doc: &str, phrase: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(doc);
    let text = std::fs::read_to_string(&path).unwrap();
    // (the docs wrap lines: compare with whitespace runs as single spaces)
    let squash = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        squash(&text).contains(&squash(phrase)),
        "{doc} should say \"{phrase}\" (what this test measures)"
    );
}
