//! Bytes → `Curve::from_bytes(.., Format::Svg, ..)`: never panics; an
//! accepted curve keeps the documented invariants.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    immerse_fuzz::curve_svg(data);
});
