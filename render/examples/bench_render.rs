//! Times the writers on a synthetic 500-vertex morph and prints a markdown
//! table (median of 3 runs).
//!
//! ```text
//! cargo run --release -p immerse-render --example bench_render [-- OUT_DIR]
//! ```
//!
//! With `OUT_DIR` the last run's PNG frames and GIF are kept there.

use testkit::synth;

use std::hint::black_box;
use std::time::{Duration, Instant};

use immerse_render::{
    Loop, Output, Style, View, encode_png, render, write_gif, write_png_sequence,
};

fn median(mut runs: Vec<Duration>) -> Duration {
    runs.sort();
    runs[runs.len() / 2]
}

fn time(mut f: impl FnMut()) -> Duration {
    median(
        (0..3)
            .map(|_| {
                let start = Instant::now();
                f();
                start.elapsed()
            })
            .collect(),
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let keep = std::env::args_os().nth(1).map(std::path::PathBuf::from);
    let frames = synth::morph(500, 120);
    let threads = rayon::current_num_threads();
    println!(
        "500 vertices, {} triangles, 120 frames, {threads} threads, median of 3\n",
        frames[0].triangles.len()
    );
    println!("| task | size | total | per frame |");
    println!("|---|---|---|---|");
    let row = |task: &str, size: u32, d: Duration| {
        println!(
            "| {task} | {size}² | {:.2} s | {:.1} ms |",
            d.as_secs_f64(),
            d.as_secs_f64() * 1000.0 / 120.0
        );
    };
    let tmp = tempfile::tempdir()?;
    let opts = Output::DEFAULT.with_force(true);
    for size in [1024, 512] {
        let style = Style::DEFAULT.with_size(size, size);
        let view = View::fit(&frames, &style);
        let ghosts = [&frames[0], &frames[119]];
        let d = time(|| {
            for f in &frames {
                black_box(render(f, &view, &style, &ghosts).expect("render"));
            }
        });
        row("render only (1 thread)", size, d);
        let pixmap = render(&frames[60], &view, &style, &ghosts).expect("render");
        let d = time(|| {
            for _ in 0..frames.len() {
                black_box(encode_png(&pixmap).expect("encode"));
            }
        });
        row("png encode only (1 thread)", size, d);
        let dir = keep.clone().unwrap_or_else(|| tmp.path().to_path_buf());
        let d = time(|| {
            write_png_sequence(
                &frames,
                &dir.join(format!("png{size}")),
                &style,
                &opts,
                &|_| {},
            )
            .expect("png sequence");
        });
        row("write_png_sequence", size, d);
        let d = time(|| {
            let path = dir.join(format!("morph{size}.gif"));
            write_gif(&frames, &path, &style, 30.0, Loop::Loop, &opts, &|_| {}).expect("gif");
        });
        row("write_gif", size, d);
    }
    if let Some(dir) = keep {
        println!("\nframes and gifs kept in {}", dir.display());
    }
    Ok(())
}
