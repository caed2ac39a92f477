//! The command-line definition (clap derive). Each subcommand's arguments
//! are turned into library options in `commands/`.

use clap::{Args, Parser, Subcommand, ValueEnum};
use immerse::Quality;
use immerse::certify::Player;
use immerse::curve::SvgShapes;
use immerse::drawing::MatchMode;
use immerse::morph::{Correspondence, Counts, Intermediate, ThirdVertexPath};
use immerse_mesh::coords::Weights;
use immerse_mesh::mesh_morph::Method;
use std::path::PathBuf;

const AFTER_HELP: &str = "\
Examples:
  immerse check curves/spiral-strip-540deg-n120.json
  immerse triangulate curves/ribbon-curl.svg -o ribbon.png
  immerse morph curves/spiral-strip-400deg-n30.json curves/curl-strip-n10.json -o out.gif

Exit codes: 0 success (or yes), 1 a negative answer (e.g. not self-overlapping),
2 bad input or usage; the cause is printed on one line to stderr.";

/// Tween closed curves that cross themselves, so that every in-between is
/// the boundary of an immersed disk.
#[derive(Debug, Parser)]
#[command(name = "immerse", version, about, long_about = None, after_help = AFTER_HELP)]
pub(crate) struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub(crate) command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub(crate) enum Command {
    /// Decide whether a curve is self-overlapping, and report its facts.
    ///
    /// Reads a curve (.json, .txt or .svg), cleans it (drops a repeated
    /// closing point and consecutive duplicates) and orients it (a
    /// clockwise curve is reversed). A curve is self-overlapping when it
    /// bounds an immersed disk; the answer is exact. Exit code 0 when it is,
    /// 1 when it is not (with the reason).
    #[command(
        after_help = "Examples:\n  immerse check curves/letter-S-n62.json\n  immerse check ribbon.svg --json\n  immerse check ribbon.svg --json=report.json"
    )]
    Check(CheckArgs),
    /// Triangulate the immersed disk that a curve bounds.
    ///
    /// Prints the triangulation (every triangle counter-clockwise, over the
    /// curve's own vertices) and its dual-tree facts; with -o, draws it.
    #[command(
        after_help = "Examples:\n  immerse triangulate curves/spiral-strip-400deg-n30.json --json\n  immerse triangulate curves/tail-loop.svg -o tail.png --quality maxmin"
    )]
    Triangulate(TriangulateArgs),
    /// Morph one self-overlapping curve into another.
    ///
    /// Every frame is the boundary of an immersed disk, checked exactly
    /// before it is written. Writes JSON (--json FILE), images (-o), or
    /// both; --metrics prints the quality measures.
    #[command(
        after_help = "Examples:\n  immerse morph a.json b.json --frames 40 --json morph.json\n  immerse morph a.svg b.svg -o frames/ --format png --size 800x800\n  immerse morph a.svg b.svg -o morph.gif --easing ease-in-out --ping-pong"
    )]
    Morph(MorphArgs),
    /// Morph two compatible planar tilings (triangulations or convex faces).
    ///
    /// Both tilings share their faces; methods other than linear keep every
    /// face convex and counter-clockwise (Floater & Gotsman; Surazhsky &
    /// Gotsman). Every frame carries a `valid` flag decided exactly, so a
    /// linear morph that folds is reported frame by frame, not hidden.
    #[command(
        after_help = "Examples:\n  immerse mesh-morph meshes/fg_4_3_a.json meshes/fg_4_3_b.json --method convex --json m.json\n  immerse mesh-morph a.obj b.obj --check-linear\n  immerse mesh-morph a.obj b.obj --method intrinsic -o frames/"
    )]
    MeshMorph(MeshMorphArgs),
    /// Morph two curves shipped inside immerse and write PNG frames and a GIF.
    ///
    /// A curled ribbon that overlaps itself becomes a tail that loops over
    /// itself; every frame is verified to be an immersed disk. Writes into
    /// immerse-demo/ by default; running it again replaces its own output
    /// but never files it did not write.
    #[command(after_help = "Examples:\n  immerse demo\n  immerse demo -o /tmp/show --frames 48")]
    Demo(DemoArgs),
    /// Animate a keyframe sequence K1 → K2 → K3 … of self-overlapping curves.
    ///
    /// Vertex counts are equalised once across all keys (original vertices
    /// stay exact), shape hints from a timeline file are honoured exactly,
    /// and frames are placed by vertex travel across the whole sequence so
    /// the motion carries through a key unless it holds or its easing
    /// stops there. Every frame is checked exactly to be an immersed disk.
    /// Prints the speed ratio at each key. The timeline file format is in
    /// docs/timeline.md.
    #[command(
        after_help = "Examples:\n  immerse animate a.svg b.svg c.svg -o seq.gif\n  immerse animate keys.svg --frames 90 --json seq.json\n  immerse animate --timeline curves/sequence/ribbon-loops.json -o seq.gif -o sheet.png"
    )]
    Animate(AnimateArgs),
    /// Serve the playground page on 127.0.0.1: draw curves, morph, scrub, download.
    ///
    /// An HTTP server bound to 127.0.0.1 only, serving one self-contained
    /// page (embedded in the binary; no network is used) and a JSON API
    /// (POST /api/morph, POST /api/check; see the README). Every resource a
    /// client can make it spend is bounded by one of the limits below.
    /// Ctrl-C finishes the requests in flight, then stops.
    #[command(
        after_help = "Examples:\n  immerse serve\n  immerse serve --port 0 --open\n  immerse serve --port 8080 --max-jobs 4"
    )]
    Serve(ServeArgs),
    /// Certify that an animation stays an immersed disk at every moment, not only at its keys.
    ///
    /// Players (Lottie, SVG, CSS, game engines) move every vertex on a
    /// straight line between stored shapes. certify decides exactly
    /// whether each such segment stays the boundary of an immersed disk
    /// for every s in [0, 1]: every triangle keeps a positive area and no
    /// vertex fan reaches a full turn (docs/design.md §13).
    ///
    /// Reads immerse's morph/animate JSON (its "keyframes", else its
    /// "frames"; their triangulations are tried first), a Lottie file (the
    /// keyframed paths of its shape layers) or an animated SVG (a path's
    /// <animate attributeName="d" values=...>). Where a file has no
    /// triangulation, or the one given fails, certify triangulates where a
    /// piece starts, certifies as far as that holds and triangulates again.
    ///
    /// Answers per segment: certified; invalid (the shape is not
    /// self-overlapping at an exact s, with where); or undecided (neither
    /// within --max-pieces triangulations, or a motion certify does not
    /// cover: curved outlines, easing that overshoots its keys). Exit code
    /// 0 when every segment is certified, 1 otherwise (the message and the
    /// JSON say invalid or undecided, where and why), 2 for bad input.
    #[command(
        after_help = "Examples:\n  immerse morph a.json b.json --frames 40 --json m.json && immerse certify m.json\n  immerse certify morph.lottie.json --player f32\n  immerse certify morph.svg --json=report.json\n\nPlayers: exact certifies the coordinates as written; f64 and f32 add the margin\nthat a player interpolating in that precision needs (per coordinate 8 u |x|,\nu its unit roundoff; f32 for native Lottie players)."
    )]
    Certify(CertifyArgs),
}

/// Arguments of `immerse certify`.
#[derive(Debug, Args)]
pub(crate) struct CertifyArgs {
    /// The animation: immerse's JSON, a Lottie file, or an animated SVG.
    pub(crate) file: PathBuf,
    /// Certify against this player's arithmetic.
    #[arg(long, value_enum, default_value = "exact")]
    pub(crate) player: Player,
    /// Most triangulations per segment before it is undecided.
    #[arg(long, default_value_t = 24, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(crate) max_pieces: u32,
    /// Write one JSON object instead of text: bare --json prints it on
    /// stdout, --json=FILE writes FILE ("-" or /dev/stdout: stdout).
    ///
    /// Fields: file, format, player, answer (certified, invalid,
    /// undecided), segments, certified, certified_as_given, invalid,
    /// undecided, paths (each with its segments: index, t0, t1, play,
    /// answer, as_given, pieces, failure, invalid_at, certified_up_to,
    /// reason), skipped.
    #[arg(long, value_name = "FILE", num_args = 0..=1, require_equals = true, default_missing_value = "-")]
    pub(crate) json: Option<PathBuf>,
    /// Replace an existing --json file.
    #[arg(long)]
    pub(crate) force: bool,
}

/// Arguments of `immerse animate`.
#[derive(Debug, Args)]
#[command(mut_arg("onion", |a| a.help("Draw the first and last key faintly behind every frame")))]
pub(crate) struct AnimateArgs {
    /// The keys in order: two or more curve or drawing files, or one SVG
    /// whose shapes (or groups, or layers) are the keys; a group of
    /// several shapes is a drawing key.
    #[arg(value_name = "KEY", required_unless_present = "timeline")]
    pub(crate) keys: Vec<PathBuf>,
    /// A timeline file (JSON): keys with times or durations, holds,
    /// easings, loop and shape hints (see docs/timeline.md).
    #[arg(long, value_name = "FILE", conflicts_with = "keys")]
    pub(crate) timeline: Option<PathBuf>,
    /// Which shapes of an SVG drawing are the keys (default auto).
    #[arg(long, value_enum)]
    pub(crate) svg_keys: Option<SvgShapes>,
    /// For keys that are drawings (files of several shapes, or an SVG
    /// whose groups hold several): which shape of a key becomes which of
    /// the next (docs/design.md §2b).
    #[arg(long = "match", value_enum, default_value_t = MatchMode::Auto)]
    pub(crate) match_mode: MatchMode,
    /// Frames over the whole sequence, holds included (default: the
    /// timeline's, else 2 seconds per segment at --fps).
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=100_000))]
    pub(crate) frames: Option<u32>,
    /// Frames per second of the timing and of a GIF or animated SVG, from
    /// 0.1 to 1000 (default: the timeline's, else 30).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) fps: Option<f64>,
    /// Easing of every segment without its own: linear keeps the speed
    /// through the keys, ease-in-out stops at each; also ease-in, ease-out,
    /// cubic-bezier(x1,y1,x2,y2).
    #[arg(long)]
    pub(crate) easing: Option<String>,
    /// Seconds every key between the first and the last holds still
    /// (keys without their own hold).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub(crate) hold: Option<f64>,
    /// The path of the motion and the tolerance of its keys.
    #[command(flatten)]
    pub(crate) motion: MotionArgs,
    /// Triangulation quality of each key.
    #[arg(long, value_enum, default_value_t = Quality::Delaunay)]
    pub(crate) quality: Quality,
    /// Where incompatible keys change triangulation on the way.
    #[arg(long, value_enum, default_value_t = Intermediate::Target)]
    pub(crate) intermediate: Intermediate,
    /// How vertices of consecutive keys without shape hints are matched.
    #[arg(long, value_enum, default_value_t = Correspondence::Best)]
    pub(crate) correspondence: Correspondence,
    /// Write every frame as JSON (the format of morph --json, with the
    /// keys' frame numbers and the speeds at them) to FILE; bare --json,
    /// "-" or /dev/stdout print it on stdout.
    #[arg(long, value_name = "FILE", num_args = 0..=1, default_missing_value = "-")]
    pub(crate) json: Option<PathBuf>,
    /// Write images (may be given more than once): a folder for PNG or
    /// SVG frame sequences, or a .gif, .svg (animated) or .png (contact
    /// sheet, one row per segment) file.
    #[arg(short, long, value_name = "PATH")]
    pub(crate) output: Vec<PathBuf>,
    /// Image format of every -o; by default from each one's extension.
    #[arg(long, value_enum)]
    pub(crate) format: Option<FormatArg>,
    /// Image size in pixels, WIDTHxHEIGHT (a contact sheet's cell size).
    #[arg(long, value_name = "WxH", default_value = "600x600", value_parser = parse_size)]
    pub(crate) size: (u32, u32),
    /// In-betweens per segment on a contact sheet, besides the two keys.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(0..=50))]
    pub(crate) sheet_inbetweens: u32,
    /// How the animation plays and what images draw.
    #[command(flatten)]
    pub(crate) play: PlayArgs,
    /// Replace existing output files (and write into a non-empty folder).
    #[arg(long)]
    pub(crate) force: bool,
    /// No progress bars or notices on stderr.
    #[arg(short, long)]
    pub(crate) quiet: bool,
}

/// Arguments of `immerse serve`.
#[derive(Debug, Args)]
pub(crate) struct ServeArgs {
    /// Port on 127.0.0.1; 0 picks a free one. The URL is printed on stdout.
    #[arg(long, default_value_t = 7878)]
    pub(crate) port: u16,
    /// Open the page in the default browser.
    #[arg(long)]
    pub(crate) open: bool,
    /// Every morph's key tolerance: how far the straight segment between two keyframes may stray from
    /// the planned motion, as a fraction of the shape's diagonal (above 0,
    /// at most 0.1); smaller gives more keys.
    #[arg(long, value_name = "FRACTION", default_value_t = immerse::morph::KEY_TOLERANCE, value_parser = key_tolerance, allow_negative_numbers = true)]
    pub(crate) key_tolerance: f64,
    /// What the server bounds (README, "Playground": each limit and its answer).
    #[command(flatten)]
    pub(crate) limits: ServeLimits,
}

/// The limits of `immerse serve`: every resource a client can make the
/// server spend is bounded by one of these.
#[derive(Debug, Clone, Args)]
#[command(next_help_heading = "Limits")]
pub(crate) struct ServeLimits {
    /// Most jobs at once: checks, morphs and every download (a frame, GIF,
    /// SVG, Lottie or JSON file); a request waits for a free slot.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub(crate) max_jobs: u32,
    /// Seconds a job may take, the wait for its slot included; then HTTP
    /// 503, and the job stops (a morph's planning runs to its end first).
    #[arg(long, value_name = "SECONDS", default_value_t = 60, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub(crate) job_timeout: u64,
    /// MiB of finished morphs kept for their frames and downloads; the
    /// oldest are dropped first, and a larger morph gets HTTP 413.
    #[arg(long, value_name = "MIB", default_value_t = 128, value_parser = clap::value_parser!(u64).range(1..=65536))]
    pub(crate) job_memory: u64,
    /// Most open connections; past it the oldest connection without a
    /// request, or whose request still waits for a job slot or its body,
    /// is closed; when none is, the new one gets HTTP 503.
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(2..=10000))]
    pub(crate) max_connections: u32,
    /// Seconds a client has to send a request's headers; also how long an
    /// idle connection is kept open.
    #[arg(long, value_name = "SECONDS", default_value_t = 10, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub(crate) header_timeout: u64,
    /// Largest request head (request line and headers), in bytes; larger
    /// get HTTP 431.
    #[arg(long, value_name = "BYTES", default_value_t = 16384, value_parser = clap::value_parser!(u32).range(1024..=1_048_576))]
    pub(crate) max_header_bytes: u32,
    /// Most header lines in one request; more get HTTP 431.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(8..=1000))]
    pub(crate) max_headers: u32,
    /// Seconds a client has to send a request body once its job has a
    /// slot; then HTTP 408.
    #[arg(long, value_name = "SECONDS", default_value_t = 10, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub(crate) body_timeout: u64,
    /// Largest request body, in bytes; larger get HTTP 413 (before the
    /// body is read when its length is announced, else while reading).
    #[arg(long, value_name = "BYTES", default_value_t = 2 << 20, value_parser = clap::value_parser!(u32).range(1024..=268_435_456))]
    pub(crate) max_body_bytes: u32,
    /// Seconds a response may wait for a client that stopped reading it;
    /// then the connection is closed.
    #[arg(long, value_name = "SECONDS", default_value_t = 20, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub(crate) write_timeout: u64,
    /// Most points in one curve (as sent, or read from a file's text);
    /// more get HTTP 413.
    #[arg(long, default_value_t = 5000, value_parser = clap::value_parser!(u32).range(3..=200_000))]
    pub(crate) max_points: u32,
    /// Most frames of one morph; more get HTTP 400.
    #[arg(long, default_value_t = 240, value_parser = clap::value_parser!(u32).range(2..=100_000))]
    pub(crate) max_frames: u32,
    /// Most curves (keys) in one morph; more get HTTP 400.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(2..=64))]
    pub(crate) max_curves: u32,
    /// Largest image side, in pixels; larger get HTTP 400.
    #[arg(long, value_name = "PIXELS", default_value_t = 2048, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub(crate) max_side: u32,
    /// Seconds Ctrl-C waits for the requests in flight before the server
    /// stops.
    #[arg(long, value_name = "SECONDS", default_value_t = 5, value_parser = clap::value_parser!(u64).range(0..=600))]
    pub(crate) drain_timeout: u64,
}

/// Arguments of `immerse mesh-morph`.
#[derive(Debug, Args)]
pub(crate) struct MeshMorphArgs {
    /// The source tiling (.obj or .json with "points" and "faces").
    pub(crate) source: PathBuf,
    /// The target tiling, with the same faces.
    pub(crate) target: PathBuf,
    /// The morph method.
    #[arg(long, value_enum, default_value_t = Method::Convex)]
    pub(crate) method: Method,
    /// Barycentric weights for convex, power and local.
    #[arg(long, value_enum, default_value_t = Weights::MeanValue)]
    pub(crate) weights: Weights,
    /// Improve triangle areas in the local method (Surazhsky & Gotsman, Controllable Morphing §4.3).
    #[arg(long)]
    pub(crate) area_improvement: bool,
    /// Morph through this intermediate tiling (convex and intrinsic).
    #[arg(long, value_name = "FILE")]
    pub(crate) intermediate: Option<PathBuf>,
    /// Number of frames, including both ends.
    #[arg(long, default_value_t = 41, value_parser = clap::value_parser!(u32).range(2..=100_000))]
    pub(crate) frames: u32,
    /// Only report whether the linear morph is valid (exact test on every star).
    #[arg(long)]
    pub(crate) check_linear: bool,
    /// The frames as JSON and as images.
    #[command(flatten)]
    pub(crate) out: OutputArgs,
    /// Replacing outputs and quiet.
    #[command(flatten)]
    pub(crate) run: RunArgs,
}

/// Arguments of `immerse demo`.
#[derive(Debug, Args)]
pub(crate) struct DemoArgs {
    /// The output folder.
    #[arg(short, long, value_name = "DIR", default_value = "immerse-demo")]
    pub(crate) output: PathBuf,
    /// Number of frames.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(2..=2000))]
    pub(crate) frames: u32,
    /// Image size in pixels, WIDTHxHEIGHT (each at most 8192).
    #[arg(long, value_name = "WxH", default_value = "480x480", value_parser = parse_size)]
    pub(crate) size: (u32, u32),
    /// Write into the folder even if it holds other files (same-named files
    /// are replaced, frame_N.png files of a longer run removed).
    #[arg(long)]
    pub(crate) force: bool,
    /// No progress bars on stderr.
    #[arg(short, long)]
    pub(crate) quiet: bool,
}

/// Arguments of `immerse check`.
#[derive(Debug, Args)]
pub(crate) struct CheckArgs {
    /// The curve file (.json, .txt, .csv, .xy or .svg); a drawing of
    /// several shapes is answered shape by shape (yes when every shape is
    /// self-overlapping).
    pub(crate) curve: PathBuf,
    /// Write one JSON object instead of text: bare --json prints it on
    /// stdout, --json=FILE writes FILE ("-" or /dev/stdout: stdout).
    ///
    /// Fields: points (count after cleaning), turning_number (of the curve
    /// as given), simple, reversed, self_overlapping, reason (null when
    /// self-overlapping). For a drawing: self_overlapping (every shape),
    /// notices, and shapes, each with id, label and those fields.
    #[arg(long, value_name = "FILE", num_args = 0..=1, require_equals = true, default_missing_value = "-")]
    pub(crate) json: Option<PathBuf>,
    /// Replace an existing --json file.
    #[arg(long)]
    pub(crate) force: bool,
}

/// Arguments of `immerse triangulate`.
#[derive(Debug, Args)]
pub(crate) struct TriangulateArgs {
    /// The curve file (.json, .txt, .csv, .xy or .svg).
    pub(crate) curve: PathBuf,
    /// Write the triangulation as JSON: bare --json prints it on stdout,
    /// --json=FILE writes FILE ("-" or /dev/stdout: stdout).
    ///
    /// Fields: points (oriented order, y up), triangles (counter-clockwise
    /// index triples), reversed, spine (triangle indices), pivot_vertex,
    /// root_triangle.
    #[arg(long, value_name = "FILE", num_args = 0..=1, require_equals = true, default_missing_value = "-")]
    pub(crate) json: Option<PathBuf>,
    /// Which triangulation to compute.
    #[arg(long, value_enum, default_value_t = Quality::Delaunay)]
    pub(crate) quality: Quality,
    /// Draw the triangulation to a .png or .svg file ("-" is refused: name
    /// a file).
    #[arg(short, long, value_name = "FILE")]
    pub(crate) output: Option<PathBuf>,
    /// Image size in pixels, WIDTHxHEIGHT (each at most 8192).
    #[arg(long, value_name = "WxH", default_value = "800x800", value_parser = parse_size)]
    pub(crate) size: (u32, u32),
    /// Replace existing output files (-o, --json=FILE).
    #[arg(long)]
    pub(crate) force: bool,
}

/// Image or animation format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum FormatArg {
    /// A folder of frame_0000.png, frame_0001.png, ...
    Png,
    /// One animated GIF file.
    Gif,
    /// A folder of frame_0000.svg, ...
    Svg,
    /// One animated SVG file (SMIL).
    AnimatedSvg,
    /// One PNG with every frame side by side (a contact sheet).
    Sheet,
    /// One Lottie JSON animation (one shape layer, path keyframes); also for -o NAME.lottie.json.
    Lottie,
}

/// Arguments of `immerse morph`.
#[derive(Debug, Args)]
pub(crate) struct MorphArgs {
    /// The source curve file.
    pub(crate) source: PathBuf,
    /// The target curve file.
    pub(crate) target: PathBuf,
    /// Number of frames, including the two ends.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(2..=100_000))]
    pub(crate) frames: u32,
    /// For drawings (files of several shapes): which shape of the source
    /// becomes which of the target (docs/design.md §2b).
    #[arg(long = "match", value_enum, default_value_t = MatchMode::Auto)]
    pub(crate) match_mode: MatchMode,
    /// The path of the motion and the tolerance of its keys.
    #[command(flatten)]
    pub(crate) motion: MotionArgs,
    /// Triangulation quality of each curve.
    #[arg(long, value_enum, default_value_t = Quality::Delaunay)]
    pub(crate) quality: Quality,
    /// How vertex counts are matched.
    #[arg(long, value_enum, default_value_t = Counts::Insert)]
    pub(crate) counts: Counts,
    /// Where incompatible curves change triangulation on the way.
    ///
    /// When the two curves' triangulations differ, edges are flipped while
    /// the shape moves toward an intermediate: `target` (a valid shape
    /// resembling the other curve) or `disk` (a convex disk).
    #[arg(long, value_enum, default_value_t = Intermediate::Target)]
    pub(crate) intermediate: Intermediate,
    /// How vertices of the two curves are matched.
    #[arg(long, value_enum, default_value_t = Correspondence::Best)]
    pub(crate) correspondence: Correspondence,
    /// Timing of the frames: linear, ease-in, ease-out, ease-in-out or
    /// cubic-bezier(x1,y1,x2,y2).
    #[arg(long, default_value = "linear")]
    pub(crate) easing: String,
    /// Print the quality metrics (area-matrix rank, variance, minimum
    /// angle, ballooning, area share, valid frames, and the motion's
    /// detour and unwind, also in the JSON) to stdout.
    #[arg(long)]
    pub(crate) metrics: bool,
    /// The frames as JSON and as images.
    #[command(flatten)]
    pub(crate) out: OutputArgs,
    /// How the animation plays and what images draw.
    #[command(flatten)]
    pub(crate) play: PlayArgs,
    /// Replacing outputs and quiet.
    #[command(flatten)]
    pub(crate) run: RunArgs,
    /// Print how long each stage took (read, morph, json, images) to stderr.
    #[arg(long)]
    pub(crate) timings: bool,
}

/// The motion flags that `morph` and `animate` share: the third vertex's
/// path and the keys' tolerance.
#[derive(Debug, Args)]
pub(crate) struct MotionArgs {
    /// How each triangle's third vertex travels.
    #[arg(long, value_enum, default_value_t = ThirdVertexPath::Rigid)]
    pub(crate) path: ThirdVertexPath,
    /// How far the straight segment between two keyframes may stray from
    /// the planned motion, as a fraction of the shape's diagonal (above 0,
    /// at most 0.1); smaller gives more keys.
    #[arg(long, value_name = "FRACTION", default_value_t = immerse::morph::KEY_TOLERANCE, value_parser = key_tolerance, allow_negative_numbers = true)]
    pub(crate) key_tolerance: f64,
}

/// The outputs that `morph` and `mesh-morph` share: the frames as JSON,
/// and as images in a format, grid, size and speed.
#[derive(Debug, Args)]
pub(crate) struct OutputArgs {
    /// Write the frames as JSON to FILE; bare --json, "-" or /dev/stdout
    /// print it on stdout.
    #[arg(long, value_name = "FILE", num_args = 0..=1, default_missing_value = "-")]
    pub(crate) json: Option<PathBuf>,
    /// Write images: a folder (a path without an extension, or ending in
    /// /) of PNG or SVG frames, or a .gif, .svg (animated) or .png
    /// (contact sheet) file; any other extension is refused. "-" writes a
    /// single-file format to stdout (give --format).
    #[arg(short, long, value_name = "PATH")]
    pub(crate) output: Option<PathBuf>,
    /// Image format; by default taken from the -o extension (.gif, .svg
    /// for animated SVG, .png for a contact sheet) and png frames for a
    /// folder.
    #[arg(long, value_enum)]
    pub(crate) format: Option<FormatArg>,
    /// The images' grid, size and speed.
    #[command(flatten)]
    pub(crate) image: ImageArgs,
}

/// The image flags that `morph` and `mesh-morph` share: a contact
/// sheet's columns, the image size and the frame rate.
#[derive(Debug, Args)]
pub(crate) struct ImageArgs {
    /// Columns of a contact sheet; by default a nearly square grid.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(crate) columns: Option<u32>,
    /// Image size in pixels, WIDTHxHEIGHT (each at most 8192).
    #[arg(long, value_name = "WxH", default_value = "600x600", value_parser = parse_size)]
    pub(crate) size: (u32, u32),
    /// Frames per second of a GIF (at most 50: GIF delays are whole
    /// hundredths of a second), animated SVG or Lottie, from 0.1 to 1000.
    #[arg(long, default_value_t = 30.0)]
    pub(crate) fps: f64,
}

/// How an animation plays (`morph`, `animate`) and what its images draw.
/// `--onion` says what it draws per command (`mut_arg` on the command).
#[derive(Debug, Args)]
pub(crate) struct PlayArgs {
    /// Play the animation forwards then backwards, repeating.
    #[arg(long, conflicts_with = "once")]
    pub(crate) ping_pong: bool,
    /// Play the animation once instead of looping.
    #[arg(long)]
    pub(crate) once: bool,
    /// Draw the triangulation's edges in images.
    #[arg(long)]
    pub(crate) wireframe: bool,
    /// Draw the source and target faintly behind every frame.
    #[arg(long)]
    pub(crate) onion: bool,
}

/// Replacing outputs and quiet, as `morph` and `mesh-morph` take them.
#[derive(Debug, Args)]
pub(crate) struct RunArgs {
    /// Replace existing output files; write into a non-empty folder,
    /// replacing frames and removing frame_N files of an earlier, longer
    /// run.
    #[arg(long)]
    pub(crate) force: bool,
    /// No progress bars or notices on stderr.
    #[arg(short, long)]
    pub(crate) quiet: bool,
}

/// Parses `WxH`.
pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT, e.g. 800x600"))?;
    let num = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|&n| (1..=immerse_render::Style::MAX_SIDE).contains(&n))
            .ok_or_else(|| {
                format!(
                    "'{v}' in '{s}' is not a size from 1 to {}",
                    immerse_render::Style::MAX_SIDE
                )
            })
    };
    Ok((num(w)?, num(h)?))
}

/// Parses `--key-tolerance`: a fraction of the diagonal above 0 and at
/// most [`immerse::morph::MAX_KEY_TOLERANCE`].
fn key_tolerance(text: &str) -> Result<f64, String> {
    let v: f64 = text.trim().parse().map_err(|_| {
        format!("'{text}' is not a number; give a fraction of the diagonal such as 0.0025")
    })?;
    immerse::morph::CurveMorphOptions::DEFAULT
        .with_key_tolerance(v)
        .validate()
        .map_err(|e| e.to_string())?;
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn check_parses_json_flag() {
        let json = |argv: &[&str]| {
            let cli = Cli::try_parse_from(argv).unwrap();
            let Command::Check(args) = cli.command else {
                panic!("not check")
            };
            assert_eq!(args.curve, PathBuf::from("a.json"));
            args.json
        };
        assert_eq!(
            json(&["immerse", "check", "a.json", "--json"]),
            Some("-".into())
        );
        // The old form: a bare flag before the curve.
        assert_eq!(
            json(&["immerse", "check", "--json", "a.json"]),
            Some("-".into())
        );
        assert_eq!(
            json(&["immerse", "check", "a.json", "--json=r.json"]),
            Some("r.json".into())
        );
        assert_eq!(json(&["immerse", "check", "a.json"]), None);
        // morph and mesh-morph also take the value after a space (the old form).
        let cli = Cli::try_parse_from(["immerse", "morph", "a", "b", "--json", "m.json"]).unwrap();
        let Command::Morph(m) = cli.command else {
            panic!("not morph")
        };
        assert_eq!(m.out.json, Some("m.json".into()));
        let cli = Cli::try_parse_from(["immerse", "morph", "a", "b", "--json", "-q"]).unwrap();
        let Command::Morph(m) = cli.command else {
            panic!("not morph")
        };
        assert_eq!(m.out.json, Some("-".into()));
        assert!(m.run.quiet);
    }

    #[test]
    fn serve_limits_have_their_defaults_and_ranges() {
        let cli = Cli::try_parse_from(["immerse", "serve"]).unwrap();
        let Command::Serve(a) = cli.command else {
            panic!("not serve")
        };
        let l = &a.limits;
        assert_eq!(
            (a.port, l.max_jobs, l.job_timeout, l.job_memory),
            (7878, 2, 60, 128)
        );
        assert_eq!(
            (l.max_connections, l.header_timeout, l.max_header_bytes),
            (128, 10, 16384)
        );
        assert_eq!(
            (l.max_body_bytes, l.body_timeout, l.write_timeout),
            (2 << 20, 10, 20)
        );
        assert_eq!(
            (l.max_points, l.max_frames, l.max_curves, l.max_side),
            (5000, 240, 8, 2048)
        );
        for bad in [
            ["--max-jobs", "0"],
            ["--max-connections", "1"],
            ["--max-header-bytes", "100"],
            ["--job-memory", "0"],
        ] {
            assert!(
                Cli::try_parse_from(["immerse", "serve", bad[0], bad[1]]).is_err(),
                "{bad:?}"
            );
        }
        // The test hook of the first server is gone.
        assert!(Cli::try_parse_from(["immerse", "serve", "--job-delay-ms", "10"]).is_err());
    }

    #[test]
    fn shared_flags_keep_their_rules_and_help_per_command() {
        for cmd in ["morph", "animate"] {
            assert!(
                Cli::try_parse_from(["immerse", cmd, "a", "b", "--ping-pong", "--once"]).is_err(),
                "{cmd}"
            );
        }
        let help = |cmd: &str, flag: &str| {
            let mut cli = Cli::command();
            let sub = cli.find_subcommand_mut(cmd).unwrap();
            let arg = sub.get_arguments().find(|a| a.get_id() == flag).unwrap();
            arg.get_help().unwrap().to_string()
        };
        assert_eq!(
            help("morph", "onion"),
            "Draw the source and target faintly behind every frame"
        );
        assert_eq!(
            help("animate", "onion"),
            "Draw the first and last key faintly behind every frame"
        );
        let cli = Cli::try_parse_from([
            "immerse",
            "mesh-morph",
            "a",
            "b",
            "--size",
            "30x20",
            "--fps",
            "12",
            "-q",
        ])
        .unwrap();
        let Command::MeshMorph(m) = cli.command else {
            panic!("not mesh-morph")
        };
        assert_eq!(
            (m.out.image.size, m.out.image.fps, m.run.quiet),
            ((30, 20), 12.0, true)
        );
    }

    /// The values clap offers are the library's own names, in the order
    /// of its `ALL`, and exactly the experimental ones are hidden unless
    /// built with the feature.
    #[test]
    fn option_values_are_the_library_names() {
        fn names<T: ValueEnum>() -> Vec<String> {
            T::value_variants()
                .iter()
                .map(|v| v.to_possible_value().unwrap().get_name().to_string())
                .collect()
        }
        fn same<T: ValueEnum + Copy>(all: &[T], name: fn(T) -> &'static str) {
            let ours: Vec<&str> = all.iter().map(|&v| name(v)).collect();
            assert_eq!(names::<T>(), ours);
        }
        same(&ThirdVertexPath::ALL, ThirdVertexPath::as_str);
        same(&Correspondence::ALL, Correspondence::as_str);
        same(&Quality::ALL, Quality::as_str);
        same(
            &[Intermediate::Target, Intermediate::Disk],
            Intermediate::as_str,
        );
        same(&Player::ALL, Player::name);
        same(&Method::ALL, Method::as_str);
        same(&Weights::ALL, Weights::as_str);
        assert_eq!(names::<Counts>(), ["insert", "resample"]);
        assert_eq!(names::<MatchMode>(), ["id", "order", "auto"]);
        assert_eq!(names::<SvgShapes>(), ["auto", "shapes", "groups"]);
        let hidden = |p: Option<clap::builder::PossibleValue>| p.unwrap().is_hide_set();
        let experimental = |e: bool| e && !cfg!(feature = "experimental");
        for p in ThirdVertexPath::ALL {
            assert_eq!(
                hidden(p.to_possible_value()),
                experimental(p.is_experimental())
            );
        }
        for c in Correspondence::ALL {
            assert_eq!(
                hidden(c.to_possible_value()),
                experimental(c.is_experimental())
            );
        }
    }

    #[test]
    fn morph_defaults_and_size() {
        let cli = Cli::try_parse_from(["immerse", "morph", "a.json", "b.json"]).unwrap();
        let Command::Morph(m) = cli.command else {
            panic!("not morph")
        };
        assert_eq!(m.frames, 60);
        assert_eq!(m.motion.path, ThirdVertexPath::Rigid);
        assert_eq!(m.out.image.size, (600, 600));
        assert!(Cli::try_parse_from(["immerse", "morph", "a", "b", "--frames", "1"]).is_err());
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert!(parse_size("0x480").is_err());
        assert!(parse_size("640").is_err());
    }
}
