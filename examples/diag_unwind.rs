//! scratch
use immerse::Curve;
use immerse::morph::{CurveMorphOptions, Tween};
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
    let a = Curve::from_path(dir.join(&args[0])).unwrap();
    let b = Curve::from_path(dir.join(&args[1])).unwrap();
    let tw = Tween::new(&a.points, &b.points, &CurveMorphOptions::DEFAULT).unwrap();
    println!("{:?}", tw.report());
    for i in 0..=40 {
        let t = i as f64 / 40.0;
        let (f, fb) = tw.frame_with_fallback(t).unwrap();
        println!(
            "t {t:.3} turning {:.3} area {:.4} fb {}",
            immerse::frames::total_absolute_turning(&f.points),
            f.total_area(),
            fb.is_some()
        );
    }
}
