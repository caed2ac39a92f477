//! Bytes → `Curve::from_bytes(.., Format::Text, ..)`: never panics; an
//! accepted curve keeps the documented invariants.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    immerse_fuzz::curve_text(data);
});
