//! `immerse._immerse`: the Python binding of the immerse library
//! (docs/python.md).
//!
//! A thin layer: it reads points (numpy arrays, lists of pairs or curve
//! files), calls the library, and turns its answers into numpy arrays,
//! small result objects and exceptions with the command line's messages.
//! Bad input raises `ValueError`; the negative answer (a curve that is not
//! self-overlapping) raises `immerse.NotSelfOverlapping`, except in
//! `check`, which returns it; a broken invariant of the library (a bug)
//! raises `RuntimeError`. Every computation that plans, morphs,
//! triangulates or certifies runs with the GIL released.

use immerse::certify::{AnimatedPath, Animation, Format, MAX_ANIMATION_BYTES, Play, ReadKey};
use immerse::certify::{CertifyError, MotionOptions, Player, certify_animation, read_animation};
use immerse::geom::Point;
use immerse::geom::polygon::{self, Turning};
use immerse::morph::{
    Correspondence, Counts, CurveMorphError, CurveMorphOptions, Intermediate, MorphError,
    MorphOptions, ThirdVertexPath,
};
use immerse::sequence::{
    Ease, Hint, HintAt, Key, KeyTiming, SequenceError, SequenceOptions, Timing,
};
use immerse::{Curve, Quality};
use immerse_render::Easing;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyException, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyString};
use std::io::Read;

pyo3::create_exception!(
    immerse,
    NotSelfOverlapping,
    PyException,
    "The negative answer: a curve does not bound an immersed disk.\n\n\
     Raised by `triangulate`, `Tween` and `Sequence` (never by `check`, which\n\
     returns the answer). The message is the command line's; `reason` holds\n\
     the reason alone."
);

/// Most vertex positions (frames × points) one call returns, as
/// `immerse morph` allows.
const MAX_FRAME_POINTS: usize = 50_000_000;

// ---------------------------------------------------------------- input

/// A curve argument: points in memory, or a curve file.
enum CurveInput {
    Points(Vec<Point>),
    File(String),
}

/// Reads a curve argument: a `str` or path-like names a curve file (JSON,
/// text or SVG, as the command line reads them); anything else is taken
/// as an (n, 2) array of x, y pairs.
fn curve_input(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<CurveInput> {
    if obj.is_instance_of::<PyString>() || obj.hasattr("__fspath__")? {
        let os = obj.py().import("os")?;
        let path: String = os.call_method1("fspath", (obj,))?.extract()?;
        return Ok(CurveInput::File(path));
    }
    points_of(obj, name).map(CurveInput::Points)
}

/// An (n, 2) array of finite-or-not floats from a numpy array or any
/// sequence of pairs `numpy.asarray` reads.
fn points_of(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<Point>> {
    let py = obj.py();
    let array = match obj.extract::<PyReadonlyArrayDyn<'_, f64>>() {
        Ok(a) => a,
        Err(_) => {
            let np = py.import("numpy")?;
            let kwargs = PyDict::new(py);
            kwargs.set_item("dtype", "float64")?;
            let converted = np
                .call_method("asarray", (obj,), Some(&kwargs))
                .map_err(|e| {
                    PyValueError::new_err(format!(
                        "{name}: expected an (n, 2) array of x, y pairs ({})",
                        e.value(py)
                    ))
                })?;
            converted.extract::<PyReadonlyArrayDyn<'_, f64>>()?
        }
    };
    let shape = array.shape().to_vec();
    if shape.len() != 2 || shape[1] != 2 {
        return Err(PyValueError::new_err(format!(
            "{name}: expected an (n, 2) array of x, y pairs, got shape {}",
            shape_text(&shape)
        )));
    }
    let view = array.as_array();
    Ok(view
        .outer_iter()
        .map(|row| Point::new(row[0], row[1]))
        .collect())
}

fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A cleaned, oriented curve and the label messages call it by (the file,
/// or `name` for points in memory).
fn read_curve(py: Python<'_>, input: CurveInput, name: &str) -> PyResult<(Curve, String)> {
    let name = name.to_string();
    py.detach(move || match input {
        CurveInput::Points(points) => Curve::from_points(&name, points)
            .map(|c| (c, name))
            .map_err(|e| e.to_string()),
        CurveInput::File(path) => Curve::from_path(&path)
            .map(|c| (c, path))
            .map_err(|e| error_chain(&e)),
    })
    .map_err(PyValueError::new_err)
}

/// An error with its sources, as the command line prints it (`{:#}`).
fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// The negative answer, with `reason` set.
fn negative(py: Python<'_>, message: String, reason: &str) -> PyErr {
    let err = NotSelfOverlapping::new_err(message);
    // Setting an attribute on a fresh exception cannot fail in practice;
    // if it did, the message still says everything.
    let _ = err.value(py).setattr("reason", reason);
    err
}

fn parse_choice<T: Copy>(what: &str, value: &str, all: &[(T, &'static str)]) -> PyResult<T> {
    all.iter()
        .find(|(_, n)| *n == value)
        .map(|(v, _)| *v)
        .ok_or_else(|| {
            let names: Vec<&str> = all.iter().map(|(_, n)| *n).collect();
            PyValueError::new_err(format!(
                "unknown {what} '{value}'; use {}",
                names.join(", ")
            ))
        })
}

fn quality_of(q: Option<&str>) -> PyResult<Quality> {
    match q {
        None => Ok(Quality::default()),
        Some(q) => q
            .parse::<Quality>()
            .map_err(|e| PyValueError::new_err(e.to_string())),
    }
}

fn easing_of(e: Option<&str>) -> PyResult<Easing> {
    match e {
        None => Ok(Easing::Linear),
        Some(e) => e
            .parse::<Easing>()
            .map_err(|err| PyValueError::new_err(format!("easing '{e}': {err}"))),
    }
}

/// The options of a morph from keyword arguments (`None`: the library's
/// default).
#[allow(clippy::too_many_arguments)]
fn morph_options(
    quality: Option<&str>,
    path: Option<&str>,
    correspondence: Option<&str>,
    counts: Option<&str>,
    intermediate: Option<&str>,
    fan_margin: Option<f64>,
) -> PyResult<CurveMorphOptions> {
    let mut morph = MorphOptions::DEFAULT;
    if let Some(p) = path {
        morph = morph.with_path(
            p.parse::<ThirdVertexPath>()
                .map_err(PyValueError::new_err)?,
        );
    }
    if let Some(eps) = fan_margin {
        if !(eps.is_finite() && eps > 0.0 && eps < std::f64::consts::PI) {
            return Err(PyValueError::new_err(format!(
                "fan_margin {eps} is not a number of radians in (0, π)"
            )));
        }
        morph = morph.with_fan_margin(eps);
    }
    let mut options = CurveMorphOptions::DEFAULT
        .with_quality(quality_of(quality)?)
        .with_morph(morph);
    if let Some(c) = correspondence {
        options = options.with_correspondence(
            c.parse::<Correspondence>()
                .map_err(PyValueError::new_err)?,
        );
    }
    if let Some(c) = counts {
        options = options.with_counts(parse_choice(
            "counts",
            c,
            &[(Counts::Insert, "insert"), (Counts::Resample, "resample")],
        )?);
    }
    if let Some(i) = intermediate {
        options = options.with_intermediate(parse_choice(
            "intermediate",
            i,
            &[
                (Intermediate::Target, Intermediate::Target.as_str()),
                (Intermediate::Disk, Intermediate::Disk.as_str()),
            ],
        )?);
    }
    Ok(options)
}

// --------------------------------------------------------------- output

fn points_array<'py>(py: Python<'py>, points: &[Point]) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y]).collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([points.len(), 2])?
        .into_any())
}

fn triangles_array<'py>(py: Python<'py>, triangles: &[[u32; 3]]) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([triangles.len(), 3])?
        .into_any())
}

/// Frames as one (count, n, 2) array.
fn frames_array<'py>(
    py: Python<'py>,
    frames: &[immerse::frames::Frame],
    n: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = frames
        .iter()
        .flat_map(|f| f.points.iter().flat_map(|p| [p.x, p.y]))
        .collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([frames.len(), n, 2])?
        .into_any())
}

fn morph_error(e: MorphError) -> PyErr {
    match e {
        MorphError::Fraction(_) => PyValueError::new_err(e.to_string()),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

fn check_frame_budget(frames: usize, n: usize) -> PyResult<()> {
    if frames.saturating_mul(n) > MAX_FRAME_POINTS {
        return Err(PyValueError::new_err(format!(
            "{frames} frames of {n} points is more than {MAX_FRAME_POINTS} points in all; ask for fewer frames"
        )));
    }
    Ok(())
}

// ---------------------------------------------------------------- check

/// The answer of :func:`check`: is the curve self-overlapping, and its
/// facts (the fields of ``immerse check --json``).
#[pyclass(module = "immerse", frozen, get_all)]
struct CheckResult {
    /// True when the curve bounds an immersed disk.
    self_overlapping: bool,
    /// Why it does not; ``None`` when it does.
    reason: Option<String>,
    /// Points after cleaning.
    points: usize,
    /// Repeated points cleaning dropped (a closing point, duplicates).
    dropped: usize,
    /// Turning number as given (before any reversal); ``None`` at a cusp.
    turning_number: Option<i64>,
    /// True when no two edges touch except neighbours at their vertex.
    simple: bool,
    /// True when the curve was clockwise and has been reversed.
    reversed: bool,
}

#[pymethods]
impl CheckResult {
    fn __bool__(&self) -> bool {
        self.self_overlapping
    }

    fn __repr__(&self) -> String {
        match &self.reason {
            None => format!("CheckResult(self_overlapping=True, points={})", self.points),
            Some(r) => format!(
                "CheckResult(self_overlapping=False, reason={r:?}, points={})",
                self.points
            ),
        }
    }

    /// The fields as a dict (the JSON of ``immerse check --json``, plus
    /// ``dropped``).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("points", self.points)?;
        d.set_item("dropped", self.dropped)?;
        d.set_item("turning_number", self.turning_number)?;
        d.set_item("simple", self.simple)?;
        d.set_item("reversed", self.reversed)?;
        d.set_item("self_overlapping", self.self_overlapping)?;
        d.set_item("reason", self.reason.clone())?;
        Ok(d)
    }
}

/// Is a closed curve self-overlapping (the boundary of an immersed disk)?
///
/// Decided exactly. Returns the answer; never raises for "no".
#[pyfunction]
fn check(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<CheckResult> {
    let input = curve_input(points, "points")?;
    let (curve, label) = read_curve(py, input, "points")?;
    let (crossing, verdict) = py.detach(|| {
        (
            polygon::first_self_intersection(&curve.points),
            immerse::triangulate(&curve.points),
        )
    });
    if let Err(e) = &verdict
        && !e.is_answer()
    {
        return Err(PyValueError::new_err(format!("{label}: {e}")));
    }
    Ok(CheckResult {
        self_overlapping: verdict.is_ok(),
        reason: verdict.err().map(|e| e.to_string()),
        points: curve.len(),
        dropped: curve.dropped,
        turning_number: curve.turning_number_as_given(),
        simple: crossing.is_none(),
        reversed: curve.reversed,
    })
}

// ----------------------------------------------------------- triangulate

/// The immersion triangulation of a self-overlapping curve (the fields of
/// ``immerse triangulate --json``).
#[pyclass(module = "immerse", frozen)]
struct Triangulation {
    points: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    /// True when the curve was clockwise and has been reversed.
    #[pyo3(get)]
    reversed: bool,
    /// The spine: triangle indices from the pivot triangle to the other end.
    #[pyo3(get)]
    spine: Vec<usize>,
    /// The pivot vertex (index into ``points``).
    #[pyo3(get)]
    pivot_vertex: u32,
    /// The root triangle of morph propagation (index into ``triangles``).
    #[pyo3(get)]
    root_triangle: usize,
    /// The smallest triangle angle, in radians.
    #[pyo3(get)]
    min_angle: f64,
    /// The quality asked for.
    #[pyo3(get)]
    quality: &'static str,
}

#[pymethods]
impl Triangulation {
    /// Vertices in oriented order (turning number +1), an (n, 2) array.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_array(py, &self.points)
    }

    /// Counter-clockwise triangles as index triples, an (n − 2, 3) array.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        triangles_array(py, &self.triangles)
    }

    fn __repr__(&self) -> String {
        format!(
            "Triangulation({} points, {} triangles, quality={:?}, min_angle={:.3}°)",
            self.points.len(),
            self.triangles.len(),
            self.quality,
            self.min_angle.to_degrees()
        )
    }
}

/// Triangulates a self-overlapping curve: ``quality`` is ``"any"``,
/// ``"delaunay"`` (the default) or ``"maxmin"``.
#[pyfunction]
#[pyo3(signature = (points, *, quality = None))]
fn triangulate(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    quality: Option<&str>,
) -> PyResult<Triangulation> {
    let quality = quality_of(quality)?;
    let input = curve_input(points, "points")?;
    let (curve, label) = read_curve(py, input, "points")?;
    let result = py.detach(|| {
        immerse::triangulate_with(&curve.points, quality).map(|imm| {
            let parts = imm
                .spine()
                .and_then(|spine| Ok((spine, imm.root_triangle(immerse::RootChoice::Disk)?)));
            (imm, parts)
        })
    });
    let (imm, parts) = match result {
        Ok(done) => done,
        Err(reason) if !reason.is_answer() => {
            return Err(PyValueError::new_err(format!("{label}: {reason}")));
        }
        Err(reason) => {
            let why = reason.to_string();
            return Err(negative(
                py,
                format!("{label}: not self-overlapping: {why}"),
                &why,
            ));
        }
    };
    let (spine, root) = parts.map_err(|_| {
        PyRuntimeError::new_err(
            "the triangulation's dual graph is not a tree; this is a bug in immerse",
        )
    })?;
    Ok(Triangulation {
        min_angle: imm.min_angle(),
        points: imm.points,
        triangles: imm.triangles,
        reversed: curve.reversed,
        spine: spine.triangles,
        pivot_vertex: spine.pivot_vertex,
        root_triangle: root,
        quality: quality.as_str(),
    })
}

// ----------------------------------------------------------------- Frame

/// One in-between: its points and the triangulation that shows it is an
/// immersion.
#[pyclass(module = "immerse", frozen)]
struct Frame {
    inner: immerse::frames::Frame,
}

#[pymethods]
impl Frame {
    /// The morph parameter of the frame, in [0, 1].
    #[getter]
    fn t(&self) -> f64 {
        self.inner.t
    }

    /// Vertex positions (y up), an (n, 2) array.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_array(py, &self.inner.points)
    }

    /// Counter-clockwise triangles, an (n − 2, 3) array of vertex indices.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        triangles_array(py, &self.inner.triangles)
    }

    /// Checks again, exactly, that the triangles show an immersion.
    fn is_immersion(&self, py: Python<'_>) -> bool {
        py.detach(|| self.inner.is_immersion())
    }

    fn __repr__(&self) -> String {
        format!(
            "Frame(t={}, {} points, {} triangles)",
            self.inner.t,
            self.inner.points.len(),
            self.inner.triangles.len()
        )
    }
}

// --------------------------------------------------------------- reports

/// What planning a morph did (``Tween.report``).
#[pyclass(module = "immerse", frozen, get_all)]
struct MorphReport {
    /// Vertices of each curve after equalising counts.
    n: usize,
    /// The cyclic shift of the correspondence: target vertex ``i + shift``
    /// matches source vertex ``i``.
    shift: usize,
    /// Flips on the side used.
    flips: usize,
    /// The side whose path was used: ``"source"`` or ``"target"``.
    used: String,
    /// The third-vertex paths used, in order of first use.
    paths: Vec<String>,
    /// What was done instead of what was asked, and why: (what, why) pairs.
    fallbacks: Vec<(String, String)>,
    /// Local unblocks on the side used.
    unblocks: usize,
    /// True when the side used needed the disk intermediate.
    used_disk: bool,
    /// Rounding repairs of the layout over every checked sample.
    repairs: usize,
}

#[pymethods]
impl MorphReport {
    fn __repr__(&self) -> String {
        format!(
            "MorphReport(n={}, shift={}, flips={}, used={:?}, paths={:?}, fallbacks={})",
            self.n,
            self.shift,
            self.flips,
            self.used,
            self.paths,
            self.fallbacks.len()
        )
    }
}

fn report_of(r: &immerse::morph::MorphReport) -> MorphReport {
    MorphReport {
        n: r.n,
        shift: r.shift,
        flips: r.flips,
        used: r.used.to_string(),
        paths: r.paths.iter().map(|p| p.as_str().to_string()).collect(),
        fallbacks: r
            .fallbacks
            .iter()
            .map(|f| (f.what.clone(), f.why.clone()))
            .collect(),
        unblocks: r.unblocks,
        used_disk: r.used_disk,
        repairs: r.repairs,
    }
}

// ----------------------------------------------------------------- Tween

/// A morph planned once from curve ``a`` to curve ``b``: a verified frame
/// at any ``t``.
#[pyclass(module = "immerse", frozen)]
struct Tween {
    inner: immerse::morph::Tween,
    reversed: (bool, bool),
}

#[pymethods]
impl Tween {
    #[new]
    #[pyo3(signature = (a, b, *, quality = None, path = None, correspondence = None, counts = None, intermediate = None, fan_margin = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        b: &Bound<'_, PyAny>,
        quality: Option<&str>,
        path: Option<&str>,
        correspondence: Option<&str>,
        counts: Option<&str>,
        intermediate: Option<&str>,
        fan_margin: Option<f64>,
    ) -> PyResult<Tween> {
        let options = morph_options(
            quality,
            path,
            correspondence,
            counts,
            intermediate,
            fan_margin,
        )?;
        let (ia, ib) = (curve_input(a, "a")?, curve_input(b, "b")?);
        let (ca, la) = read_curve(py, ia, "a")?;
        let (cb, lb) = read_curve(py, ib, "b")?;
        let planned = py.detach(|| immerse::morph::Tween::new(&ca.points, &cb.points, &options));
        match planned {
            Ok(inner) => Ok(Tween {
                inner,
                reversed: (ca.reversed, cb.reversed),
            }),
            Err(CurveMorphError::NotSelfOverlapping { side, reason }) => {
                let label = match side {
                    immerse::morph::Side::Source => &la,
                    immerse::morph::Side::Target => &lb,
                };
                let err = CurveMorphError::NotSelfOverlapping {
                    side,
                    reason: reason.clone(),
                };
                let message = format!("{label}: {err}");
                if reason.is_answer() {
                    Err(negative(py, message, &reason.to_string()))
                } else {
                    Err(PyValueError::new_err(message))
                }
            }
            Err(e @ CurveMorphError::Insertion { .. }) => Err(PyValueError::new_err(e.to_string())),
            Err(e) => Err(PyRuntimeError::new_err(e.to_string())),
        }
    }

    /// The points of the frame at fraction ``t`` ∈ [0, 1] of the vertex
    /// travel (0 = ``a`` exactly, 1 = ``b`` exactly), an (n, 2) array.
    fn at<'py>(&self, py: Python<'py>, t: f64) -> PyResult<Bound<'py, PyAny>> {
        let frame = py.detach(|| self.inner.frame(t)).map_err(morph_error)?;
        points_array(py, &frame.points)
    }

    /// The frame at ``t`` with its triangulation.
    fn frame(&self, py: Python<'_>, t: f64) -> PyResult<Frame> {
        let inner = py.detach(|| self.inner.frame(t)).map_err(morph_error)?;
        Ok(Frame { inner })
    }

    /// ``count`` frames from ``a`` to ``b`` (the first is ``a``, the last
    /// ``b``), eased in time as the command line's ``--easing``; a
    /// (count, n, 2) array.
    #[pyo3(signature = (count, easing = None))]
    fn frames<'py>(
        &self,
        py: Python<'py>,
        count: usize,
        easing: Option<&str>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let easing = easing_of(easing)?;
        let n = self.inner.vertex_count();
        check_frame_budget(count, n)?;
        let times = immerse_render::frame_times(count, &easing);
        let morph = py
            .detach(|| self.inner.morph(&times))
            .map_err(morph_error)?;
        frames_array(py, &morph.frames, n)
    }

    /// The keyframes: the animation is their piecewise-linear
    /// interpolation, every segment between consecutive keys certified an
    /// immersion for every s in exact arithmetic (docs/design.md §13). A
    /// list of ``Frame``: ``t`` strictly increasing from 0 to 1, and the
    /// triangulation of the segment that follows each key (a flip key is
    /// written once, with the triangulation after the flip).
    #[getter]
    fn keyframes(&self, py: Python<'_>) -> Vec<Frame> {
        py.detach(|| self.inner.keyframes())
            .into_iter()
            .map(|k| Frame {
                inner: immerse::frames::Frame {
                    t: k.t,
                    points: k.points,
                    triangles: k.triangles,
                },
            })
            .collect()
    }

    /// What planning did: shift, flips, side, paths, fallbacks.
    #[getter]
    fn report(&self) -> MorphReport {
        report_of(self.inner.report())
    }

    /// Vertices of every frame.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.vertex_count()
    }

    /// Total vertex travel (the unit of the frame timing).
    #[getter]
    fn path_length(&self) -> f64 {
        self.inner.path_length()
    }

    /// Whether ``a`` and ``b`` were given clockwise and reversed.
    #[getter]
    fn reversed(&self) -> (bool, bool) {
        self.reversed
    }

    fn __repr__(&self) -> String {
        let r = self.inner.report();
        format!(
            "Tween({} vertices, shift {}, {} flips, path {})",
            r.n,
            r.shift,
            r.flips,
            r.paths
                .iter()
                .map(|p| p.as_str())
                .collect::<Vec<_>>()
                .join("+")
        )
    }
}

// -------------------------------------------------------------- Sequence

/// A hint's place on its key: a vertex index (int), a point ((x, y)) or a
/// fraction of the arc length (float).
fn hint_at(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<HintAt> {
    if let Ok(v) = obj.extract::<usize>() {
        if obj.is_instance_of::<pyo3::types::PyInt>() {
            return Ok(HintAt::Vertex(v));
        }
    }
    if obj.is_instance_of::<pyo3::types::PyFloat>() {
        return Ok(HintAt::Fraction(obj.extract::<f64>()?));
    }
    if let Ok((x, y)) = obj.extract::<(f64, f64)>() {
        return Ok(HintAt::Point(Point::new(x, y)));
    }
    Err(PyTypeError::new_err(format!(
        "{what}: a hint's place is a vertex index (int), a fraction of the arc length (float) or a point (x, y)"
    )))
}

fn hints_of(hints: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<Hint>> {
    let Some(hints) = hints else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for (i, h) in hints.try_iter()?.enumerate() {
        let h = h?;
        let what = format!("hints[{i}]");
        let items: Vec<Bound<'_, PyAny>> = h
            .try_iter()
            .map_err(|_| {
                PyTypeError::new_err(format!(
                    "{what}: expected (segment, from, to) or (segment, from, to, name)"
                ))
            })?
            .collect::<PyResult<_>>()?;
        let (segment, from, to, name) = match items.as_slice() {
            [s, f, t] => (s, f, t, format!("hint {}", i + 1)),
            [s, f, t, n] => (s, f, t, n.extract::<String>()?),
            _ => {
                return Err(PyTypeError::new_err(format!(
                    "{what}: expected (segment, from, to) or (segment, from, to, name)"
                )));
            }
        };
        out.push(Hint {
            name,
            segment: segment.extract::<usize>()?,
            from: hint_at(from, &what)?,
            to: hint_at(to, &what)?,
        });
    }
    Ok(out)
}

fn sequence_error(py: Python<'_>, e: SequenceError) -> PyErr {
    match &e {
        SequenceError::NotSelfOverlapping { reason, .. } if reason.is_answer() => {
            negative(py, e.to_string(), &reason.to_string())
        }
        SequenceError::Morph { .. } => PyRuntimeError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// A planned keyframe sequence K1 → K2 → …: equal vertex counts across
/// all keys, hints honoured, one verified tween per segment, each vertex
/// keeping its identity through the chain.
#[pyclass(module = "immerse", frozen)]
struct Sequence {
    inner: immerse::sequence::Sequence,
}

#[pymethods]
impl Sequence {
    #[new]
    #[pyo3(signature = (keys, *, hints = None, quality = None, path = None, correspondence = None, intermediate = None, fan_margin = None, hint_tolerance = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        keys: &Bound<'_, PyAny>,
        hints: Option<&Bound<'_, PyAny>>,
        quality: Option<&str>,
        path: Option<&str>,
        correspondence: Option<&str>,
        intermediate: Option<&str>,
        fan_margin: Option<f64>,
        hint_tolerance: Option<f64>,
    ) -> PyResult<Sequence> {
        let morph = morph_options(
            quality,
            path,
            correspondence,
            None,
            intermediate,
            fan_margin,
        )?;
        let mut options = SequenceOptions::DEFAULT.with_morph(morph);
        if let Some(tol) = hint_tolerance {
            if !(tol.is_finite() && tol >= 0.0) {
                return Err(PyValueError::new_err(format!(
                    "hint_tolerance {tol} is not a number of at least 0"
                )));
            }
            options = options.with_hint_tolerance(tol);
        }
        let hints = hints_of(hints)?;
        let mut lib_keys = Vec::new();
        for (j, k) in keys.try_iter()?.enumerate() {
            let name = format!("keys[{j}]");
            let input = curve_input(&k?, &name)?;
            let (curve, label) = read_curve(py, input, &name)?;
            lib_keys.push(Key::new(label, curve.points));
        }
        let planned = py.detach(|| immerse::sequence::Sequence::new(&lib_keys, &hints, &options));
        planned
            .map(|inner| Sequence { inner })
            .map_err(|e| sequence_error(py, e))
    }

    /// Every frame of the sequence, a (frames, n, 2) array.
    ///
    /// ``count`` frames in all (holds included), or, when ``None``, as
    /// many as ``fps`` and the times, durations and holds give (2 s per
    /// segment by default). ``easing`` eases every segment; ``times``
    /// (one per key, ``None`` where free), ``durations`` (one per
    /// segment) and ``holds`` (one per key) are seconds.
    #[pyo3(signature = (count = None, *, fps = 30.0, easing = None, times = None, durations = None, holds = None))]
    #[allow(clippy::too_many_arguments)]
    fn frames<'py>(
        &self,
        py: Python<'py>,
        count: Option<usize>,
        fps: f64,
        easing: Option<&str>,
        times: Option<Vec<Option<f64>>>,
        durations: Option<Vec<Option<f64>>>,
        holds: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if !(fps.is_finite() && fps > 0.0 && fps <= 1000.0) {
            return Err(PyValueError::new_err(format!(
                "fps {fps} is not a number above 0 and at most 1000"
            )));
        }
        let m = self.inner.key_count();
        let easing = easing_of(easing)?;
        let ease = if easing == Easing::Linear {
            Ease::LINEAR
        } else {
            Ease::new(move |x| easing.apply(x))
        };
        let per_key = |what: &str, len: usize, want: usize| -> PyResult<()> {
            if len != want {
                return Err(PyValueError::new_err(format!(
                    "{what}: {len} given, the sequence has {want}"
                )));
            }
            Ok(())
        };
        if let Some(t) = &times {
            per_key("times (one per key)", t.len(), m)?;
        }
        if let Some(d) = &durations {
            per_key("durations (one per segment)", d.len(), m - 1)?;
        }
        if let Some(h) = &holds {
            per_key("holds (one per key)", h.len(), m)?;
        }
        let timing = Timing {
            fps,
            frames: count,
            keys: (0..m)
                .map(|j| KeyTiming {
                    time: times.as_ref().and_then(|t| t[j]),
                    hold: holds.as_ref().map_or(0.0, |h| h[j]),
                    duration: durations.as_ref().and_then(|d| d.get(j).copied().flatten()),
                    easing: ease.clone(),
                })
                .collect(),
        };
        let n = self.inner.vertex_count();
        let schedule = self
            .inner
            .schedule(&timing)
            .map_err(|e| sequence_error(py, e))?;
        check_frame_budget(schedule.samples.len(), n)?;
        let morph = py
            .detach(|| self.inner.frames(&schedule))
            .map_err(|e| sequence_error(py, e))?;
        frames_array(py, &morph.frames, n)
    }

    /// The frame at fraction ``t`` of segment ``segment``'s travel (key
    /// ``segment`` at 0, key ``segment + 1`` at 1), in the sequence's
    /// vertex numbering.
    fn frame(&self, py: Python<'_>, segment: usize, t: f64) -> PyResult<Frame> {
        if segment + 1 >= self.inner.key_count() {
            return Err(PyValueError::new_err(format!(
                "segment {segment} does not exist; the sequence has {} (0 to {})",
                self.inner.key_count() - 1,
                self.inner.key_count() - 2
            )));
        }
        let inner = py
            .detach(|| self.inner.frame(segment, t))
            .map_err(morph_error)?;
        Ok(Frame { inner })
    }

    /// The keys with the sequence's vertex numbering (original vertices
    /// exactly, inserted ones on their edges): a list of (n, 2) arrays.
    #[getter]
    fn keys<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        (0..self.inner.key_count())
            .map(|j| points_array(py, self.inner.key_points(j)))
            .collect()
    }

    /// The tween of segment ``segment`` (key ``segment`` to the next), in
    /// its own vertex numbering.
    fn tween(&self, segment: usize) -> PyResult<Tween> {
        if segment + 1 >= self.inner.key_count() {
            return Err(PyValueError::new_err(format!(
                "segment {segment} does not exist; the sequence has {}",
                self.inner.key_count() - 1
            )));
        }
        Ok(Tween {
            inner: self.inner.tween(segment).clone(),
            reversed: (false, false),
        })
    }

    /// Vertices of every frame and key.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.vertex_count()
    }

    /// Number of keys.
    #[getter]
    fn key_count(&self) -> usize {
        self.inner.key_count()
    }

    /// The keys' names (file names, or ``keys[j]``).
    #[getter]
    fn key_names(&self) -> Vec<String> {
        self.inner.key_names().to_vec()
    }

    fn __repr__(&self) -> String {
        format!(
            "Sequence({} keys, {} vertices)",
            self.inner.key_count(),
            self.inner.vertex_count()
        )
    }
}

// --------------------------------------------------------------- certify

/// The certificate of an animation (``immerse certify``): is it an
/// immersed disk at every moment, for a player's arithmetic?
#[pyclass(module = "immerse", frozen)]
struct CertifyReport {
    inner: immerse::certify::AnimationReport,
    /// The input's name.
    #[pyo3(get)]
    file: String,
}

fn answer_name(a: immerse::certify::Answer) -> &'static str {
    match a {
        immerse::certify::Answer::Certified => "certified",
        immerse::certify::Answer::Invalid => "invalid",
        immerse::certify::Answer::Undecided => "undecided",
    }
}

#[pymethods]
impl CertifyReport {
    /// ``"certified"``, ``"invalid"`` or ``"undecided"``.
    #[getter]
    fn answer(&self) -> &'static str {
        answer_name(self.inner.answer)
    }

    /// True when every segment of every outline is certified.
    #[getter]
    fn certified(&self) -> bool {
        self.inner.answer == immerse::certify::Answer::Certified
    }

    /// The player's arithmetic: ``"exact"``, ``"f64"`` or ``"f32"``.
    #[getter]
    fn player(&self) -> &'static str {
        self.inner.player.name()
    }

    /// Segments in all.
    #[getter]
    fn segments(&self) -> usize {
        self.inner.segments
    }

    /// Segments certified.
    #[getter]
    fn certified_segments(&self) -> usize {
        self.inner.certified
    }

    /// Segments certified by their first key's own triangulation alone.
    #[getter]
    fn certified_as_given(&self) -> usize {
        self.inner.certified_as_given
    }

    /// Segments with a shape that is not self-overlapping.
    #[getter]
    fn invalid(&self) -> usize {
        self.inner.invalid
    }

    /// Segments neither certified nor shown invalid.
    #[getter]
    fn undecided(&self) -> usize {
        self.inner.undecided
    }

    fn __bool__(&self) -> bool {
        self.certified()
    }

    /// The whole report as a dict: the JSON of ``immerse certify --json``.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        #[derive(serde::Serialize)]
        struct Report<'a> {
            file: &'a str,
            #[serde(flatten)]
            report: &'a immerse::certify::AnimationReport,
        }
        let text = serde_json::to_string(&Report {
            file: &self.file,
            report: &self.inner,
        })
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        py.import("json")?.call_method1("loads", (text,))
    }

    fn __repr__(&self) -> String {
        format!(
            "CertifyReport(answer={:?}, player={:?}, segments={}, certified={}, invalid={}, undecided={})",
            self.answer(),
            self.player(),
            self.inner.segments,
            self.inner.certified,
            self.inner.invalid,
            self.inner.undecided
        )
    }
}

/// Reads a file for `certify` through the size cap.
fn read_bounded(path: &str) -> Result<Vec<u8>, String> {
    let fail = |e: std::io::Error| format!("cannot read {path}: {e}");
    let meta = std::fs::metadata(path).map_err(fail)?;
    if meta.is_dir() {
        return Err(format!(
            "cannot read {path}: it is a folder; give an animation file"
        ));
    }
    let limit = MAX_ANIMATION_BYTES as u64;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(fail)?
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(fail)?;
    if bytes.len() as u64 > limit {
        return Err(format!(
            "cannot read {path}: too large (over {limit} bytes)"
        ));
    }
    Ok(bytes)
}

/// Keys given as shapes: their times and optional triangulations.
fn animation_of_shapes(
    shapes: &Bound<'_, PyAny>,
    times: Option<Vec<f64>>,
    triangles: Option<&Bound<'_, PyAny>>,
) -> PyResult<Animation> {
    let mut keys: Vec<ReadKey> = Vec::new();
    for (j, s) in shapes.try_iter()?.enumerate() {
        let points = points_of(&s?, &format!("keys[{j}]"))?;
        keys.push(ReadKey {
            t: j as f64,
            points,
            triangles: None,
        });
    }
    let key_error = |key: usize, e: CertifyError| {
        PyValueError::new_err(
            CertifyError::InKey {
                key,
                source: Box::new(e),
            }
            .to_string(),
        )
    };
    let Some(first) = keys.first() else {
        return Err(PyValueError::new_err(CertifyError::NoKeys.to_string()));
    };
    let n = first.points.len();
    for (j, k) in keys.iter().enumerate() {
        if k.points.len() < 3 {
            return Err(key_error(j, CertifyError::TooFewPoints(k.points.len())));
        }
        if k.points.len() != n {
            return Err(key_error(
                j,
                CertifyError::CountMismatch {
                    start: n,
                    end: k.points.len(),
                },
            ));
        }
        if let Some(point) = k.points.iter().position(|p| !p.is_finite()) {
            return Err(key_error(
                j,
                CertifyError::NotFinite {
                    point,
                    at_end: false,
                },
            ));
        }
    }
    if let Some(times) = times {
        if times.len() != keys.len() {
            return Err(PyValueError::new_err(format!(
                "times: {} given for {} keys",
                times.len(),
                keys.len()
            )));
        }
        for (k, t) in keys.iter_mut().zip(times) {
            k.t = t;
        }
        for j in 0..keys.len() {
            let t = keys[j].t;
            if !t.is_finite()
                || (j > 0 && t.partial_cmp(&keys[j - 1].t) != Some(std::cmp::Ordering::Greater))
            {
                return Err(PyValueError::new_err(
                    CertifyError::KeyTime { key: j, t }.to_string(),
                ));
            }
        }
    }
    if let Some(triangles) = triangles {
        let count = keys.len();
        for (j, t) in triangles.try_iter()?.enumerate() {
            let t = t?;
            let Some(key) = keys.get_mut(j) else {
                return Err(PyValueError::new_err(format!(
                    "triangles: more triangulations than the {count} keys"
                )));
            };
            if !t.is_none() {
                let tris: Vec<[u32; 3]> = t
                    .extract::<Vec<[u32; 3]>>()
                    .or_else(|_| {
                        let np = t.py().import("numpy")?;
                        let list = np.call_method1("asarray", (&t,))?.call_method0("tolist")?;
                        list.extract::<Vec<[u32; 3]>>()
                    })
                    .map_err(|_| {
                        PyValueError::new_err(format!(
                            "triangles[{j}]: expected an (m, 3) array of vertex indices"
                        ))
                    })?;
                if let Some(bad) = tris.iter().flatten().find(|&&v| v as usize >= n) {
                    return Err(PyValueError::new_err(format!(
                        "triangles[{j}]: vertex {bad} does not exist; the keys have {n} points"
                    )));
                }
                key.triangles = Some(tris);
            }
        }
    }
    // As the file reader does: a clockwise first key reverses every key
    // (not when triangulations are given: they name vertices as given).
    let mut reversed = false;
    if keys.iter().all(|k| k.triangles.is_none())
        && polygon::turning_number(&keys[0].points) == Turning::Number(-1)
    {
        reversed = true;
        for k in &mut keys {
            k.points.reverse();
        }
    }
    let segments = keys.len().saturating_sub(1);
    Ok(Animation {
        format: Format::ImmerseKeyframes,
        paths: vec![AnimatedPath {
            name: "keys".into(),
            keys,
            play: vec![Play::Linear; segments],
            reversed,
        }],
        skipped: Vec::new(),
    })
}

/// Certify that an animation is an immersed disk at every moment, for a
/// player that moves every vertex on a straight line between keys.
#[pyfunction]
#[pyo3(signature = (animation, *, times = None, triangles = None, player = "exact", max_pieces = 24))]
fn certify(
    py: Python<'_>,
    animation: &Bound<'_, PyAny>,
    times: Option<Vec<f64>>,
    triangles: Option<&Bound<'_, PyAny>>,
    player: &str,
    max_pieces: usize,
) -> PyResult<CertifyReport> {
    let player = parse_choice("player", player, &Player::ALL.map(|p| (p, p.name())))?;
    if max_pieces == 0 {
        return Err(PyValueError::new_err("max_pieces must be at least 1"));
    }
    let (anim, file) = if animation.is_instance_of::<PyBytes>() {
        let bytes: Vec<u8> = animation.extract()?;
        let label = "<bytes>".to_string();
        let anim = py
            .detach(|| read_animation(&bytes, &label))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        (anim, label)
    } else if animation.is_instance_of::<PyString>() || animation.hasattr("__fspath__")? {
        let os = py.import("os")?;
        let path: String = os.call_method1("fspath", (animation,))?.extract()?;
        let anim = py
            .detach(|| {
                read_bounded(&path)
                    .and_then(|b| read_animation(&b, &path).map_err(|e| e.to_string()))
            })
            .map_err(PyValueError::new_err)?;
        (anim, path)
    } else {
        (
            animation_of_shapes(animation, times, triangles)?,
            "keys".to_string(),
        )
    };
    let options = MotionOptions { max_pieces };
    let inner = py.detach(|| certify_animation(&anim, player, options));
    Ok(CertifyReport { inner, file })
}

// ---------------------------------------------------------------- module

/// Tween closed curves that cross themselves: every in-between is the
/// boundary of an immersed disk.
#[pymodule]
fn _immerse(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add(
        "NotSelfOverlapping",
        m.py().get_type::<NotSelfOverlapping>(),
    )?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(triangulate, m)?)?;
    m.add_function(wrap_pyfunction!(certify, m)?)?;
    m.add_class::<CheckResult>()?;
    m.add_class::<Triangulation>()?;
    m.add_class::<Frame>()?;
    m.add_class::<MorphReport>()?;
    m.add_class::<Tween>()?;
    m.add_class::<Sequence>()?;
    m.add_class::<CertifyReport>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
