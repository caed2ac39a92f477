//! Small arbitrary point lists → `triangulate`; every answer passes the
//! independent `check`, and so do the Delaunay-improved and max–min ones.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    immerse_fuzz::check_points(data);
});
