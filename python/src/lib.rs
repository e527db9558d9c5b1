//! The native half of the Python package `kepler`: load a scene once, render it for the
//! command's flags with the interpreter's lock released, and hand back the command's bytes.
//!
//! Everything a user calls is in `python/kepler/` (keyword arguments become the command's
//! flags there); this module only crosses the language boundary.

use std::path::PathBuf;

use kepler_cli::embed::{self, Loaded, Want};
use kepler_hsr::check::{self, VisibleSet};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

create_exception!(
    _kepler,
    KeplerError,
    PyException,
    "A scene that cannot be read or rendered, with the file and line where it can say."
);

/// An error as the command prints it, raised as `KeplerError`.
fn raise(e: anyhow::Error) -> PyErr {
    KeplerError::new_err(format!("{e:#}"))
}

/// A scene loaded and prepared once, to render in as many views as asked.
#[pyclass(frozen, name = "NativeScene", module = "kepler._kepler")]
struct NativeScene {
    loaded: Loaded,
}

/// What one render made: JSON text, SVG text, PNG bytes (each `None` unless asked for) and
/// the render's warnings.
type Outputs = (
    Option<String>,
    Option<String>,
    Option<Py<PyBytes>>,
    Vec<String>,
);

#[pymethods]
impl NativeScene {
    /// Renders for `flags` (the command's, as `--name=value`), making the outputs asked for.
    #[pyo3(signature = (flags, json=false, svg=false, png=false))]
    fn render(
        &self,
        py: Python<'_>,
        flags: Vec<String>,
        json: bool,
        svg: bool,
        png: bool,
    ) -> PyResult<Outputs> {
        let want = Want { json, svg, png };
        let made = py
            .detach(|| embed::render(&self.loaded, &flags, want))
            .map_err(raise)?;
        Ok(outputs(py, made))
    }

    /// How many views the `--turntable N` or `--views FILE` in `flags` makes.
    fn frame_count(&self, py: Python<'_>, flags: Vec<String>) -> PyResult<usize> {
        py.detach(|| embed::frame_count(&self.loaded, &flags))
            .map_err(raise)
    }

    /// Renders views `frames` (0-based) of the turntable or views file in `flags`, each as
    /// the command renders it in the whole run.
    #[pyo3(signature = (flags, frames, json=false, svg=false, png=false))]
    fn render_frames(
        &self,
        py: Python<'_>,
        flags: Vec<String>,
        frames: Vec<usize>,
        json: bool,
        svg: bool,
        png: bool,
    ) -> PyResult<Vec<Outputs>> {
        let want = Want { json, svg, png };
        let made = py
            .detach(|| embed::render_frames(&self.loaded, &flags, want, &frames))
            .map_err(raise)?;
        Ok(made.into_iter().map(|m| outputs(py, m)).collect())
    }

    /// The file the scene was read from.
    #[getter]
    fn path(&self) -> PathBuf {
        self.loaded.path.clone()
    }

    /// The number of faces once instances are placed (the JSON ids run below it).
    #[getter]
    fn face_count(&self) -> usize {
        self.loaded.scene.face_count()
    }

    /// What the reader had to say about the file, one message a warning.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.loaded
            .warnings
            .iter()
            .map(ToString::to_string)
            .collect()
    }
}

/// One render's outputs as Python values.
fn outputs(py: Python<'_>, made: embed::Made) -> Outputs {
    let png = made.png.map(|b| PyBytes::new(py, &b).unbind());
    (made.json, made.svg, png, made.warnings)
}

/// The file the command writes view `k` (0-based) of `total` to, for an output `path`.
#[pyfunction]
fn frame_path(path: PathBuf, k: usize, total: usize) -> PathBuf {
    embed::frame_path(&path, k, total)
}

/// Checks render flags as the command would for the scene file `path`, before any loading.
#[pyfunction]
#[pyo3(signature = (path, flags, one_view=true))]
fn check_flags(path: PathBuf, flags: Vec<String>, one_view: bool) -> PyResult<()> {
    embed::check_flags(&path, &flags, one_view).map_err(raise)
}

/// Compares two `kepler-visible/1` sets (JSON text; the names are what errors cite) as
/// `kepler diff` does, returning its `kepler-diff/1` report.
#[pyfunction]
fn diff(
    py: Python<'_>,
    golden: &str,
    golden_name: PathBuf,
    current: &str,
    current_name: PathBuf,
    tol: f64,
) -> PyResult<String> {
    let report = py.detach(|| -> Result<String, kepler_hsr::Error> {
        let golden = VisibleSet::parse(golden, &golden_name)?;
        let current = VisibleSet::parse(current, &current_name)?;
        Ok(check::diff(&golden, &current, tol).to_json())
    });
    report.map_err(|e| KeplerError::new_err(e.to_string()))
}

/// Loads and prepares a scene file or mesh, as `kepler render PATH FLAGS` does (the flags
/// of loading: `--max-faces`, `--include-root`, `--hierarchy`).
#[pyfunction]
#[pyo3(signature = (path, flags=Vec::new()))]
fn load(py: Python<'_>, path: PathBuf, flags: Vec<String>) -> PyResult<NativeScene> {
    let loaded = py.detach(|| embed::load(&path, &flags)).map_err(raise)?;
    Ok(NativeScene { loaded })
}

/// The module `kepler._kepler`.
#[pymodule]
fn _kepler(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeScene>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(frame_path, m)?)?;
    m.add_function(wrap_pyfunction!(check_flags, m)?)?;
    m.add_function(wrap_pyfunction!(diff, m)?)?;
    m.add("KeplerError", m.py().get_type::<KeplerError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
