//! A deliberate panic for the tests: they check that a panic in a render thread is
//! reported (exit code 1, or a message in the viewer), not swallowed.

/// Panics when `PRISM_INJECT_PANIC` is set.
pub fn injected_panic() {
    if std::env::var_os("PRISM_INJECT_PANIC").is_some() {
        panic!("PRISM_INJECT_PANIC is set: a deliberate panic, to test how one is reported");
    }
}
