//! kepler: exact hidden-surface removal for polyhedral scenes, after W.R. Franklin's KEPLER
//! (1981). For a view it computes exactly which part of every face is visible — to the
//! precision of f64 arithmetic, not to a pixel — and draws it as SVG line drawings, PNG
//! pictures and canonical JSON visible-polygon sets.
//!
//! Data flows one way: [`load_scene`] → [`prepare()`] → a [`Camera`] and a [`View`] → every
//! face's [`Visibility`] → the emitted outputs ([`Rendered`]), and [`render()`] runs the
//! stages after `prepare` as one call. Every operation takes a [`Progress`] last: its default
//! observes nothing and costs nothing; a watcher thread (a progress bar) reads one that the
//! work reports its counts to, and watching never changes a result.
//!
//! ```
//! use kepler_hsr::{load_scene, prepare, render, Camera, CameraRequest, LoadOptions, Outputs};
//! use kepler_hsr::{PrepareOptions, Progress, RenderOptions};
//!
//! let progress = Progress::default(); // observes nothing
//! let mut warnings = Vec::new();
//! let path = "scenes/assembly.kdl".as_ref();
//! let mut scene = load_scene(path, &LoadOptions::default(), &mut warnings, &progress)?;
//! // INBOXes: optional, they only make it faster
//! prepare(&mut scene, &PrepareOptions::default(), &progress);
//! let camera = Camera::for_scene(&scene, &CameraRequest::default())?;
//! let outputs = Outputs { svg: true, json: true, ..Outputs::default() };
//! let opts = RenderOptions { outputs, ..Default::default() };
//! let rendered = render(&scene, &camera, &opts, &progress)?;
//! println!("{} faces visible", rendered.visibility.iter().filter(|(_, f)| f.area > 0.0).count());
//! std::fs::write(std::env::temp_dir().join("assembly.svg"), rendered.svg.unwrap())?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The papers' names are kept (docs/papers.md says which module implements which section):
//! Franklin's queries [`query::include`], [`query::visp`] and [`query::visobj`]; CBOX and
//! INBOX on every [`Object`]; Crosnier and Rossignac's triboxes and Tan, Chong and Low's
//! object trees in [`tribox`]. Beside the root: [`lines`] (the line drawing), [`plot`] (pages,
//! pens and hatching), [`stats`] (what a render did), [`check`] (exact and golden checks).
//! ARCHITECTURE.md maps the modules behind them.

pub mod check;
mod chunked;
mod count;
mod describe;
mod emit;
mod error;
mod exact;
mod geom;
#[cfg(test)]
mod layering;
mod load;
mod pipeline;
mod prepare;
mod primitives;
mod progress;
pub mod query;
mod rank_sort;
mod renumber;
mod scene;
pub mod tribox;
mod view;
mod visibility;

#[cfg(test)]
mod tests;

pub use error::{Error, Location, Pos, Warning};
pub use geom::box3::Box3;
pub use geom::{M4, P3, V3};
pub use load::limits::LoadOptions;
pub use load::load_scene;
pub use pipeline::{render, render_to, Outputs, RenderOptions, Rendered};
pub use prepare::{prepare, PrepareOptions};
pub use progress::Progress;
pub use scene::face_id::FaceId;
pub use scene::flatten::FlatMesh;
pub use scene::object::{Content, Face, FaceIndices, Instance, Mesh, Object};
pub use scene::object_tree::HierarchyKind;
pub use scene::Scene;
pub use view::camera::{Camera, CameraRequest, Projection};
pub use view::lod::LodOptions;
pub use view::View;
pub use visibility::result::{FaceVisibility, Visibility};

/// The line drawing: which edges are drawn, and the visible and hidden strokes a render makes.
pub mod lines {
    pub use crate::emit::lines::edges::{EdgeKind, EdgeOptions, EdgeSet};
    pub use crate::emit::lines::{Drawing, LineOptions, Stroke};
}

/// Plotter pages and pens: page sizes, layers, hatching, colours, and what building a
/// picture did.
pub mod plot {
    pub use crate::emit::plot::color::Rgb;
    pub use crate::emit::plot::dedup::DedupStats;
    pub use crate::emit::plot::hatch::HatchOptions;
    pub use crate::emit::plot::page::PageSize;
    pub use crate::emit::plot::picture::{LayerMode, LayerSummary, Pen, PictureOptions, PlotStats};
    pub use crate::geom::rect::Rect;
    pub use crate::scene::style::Style;
}

/// What a render did: stage times, progress stages and phases, and the counters of the cull,
/// the visibility pass and level-of-detail substitution.
pub mod stats {
    pub use crate::pipeline::RenderStats;
    pub use crate::progress::cpu::{
        process_cpu_time, serial_share, worker_threads, Spent, Stopwatch,
    };
    pub use crate::progress::stage::{Phase, Stage, Unit};
    pub use crate::progress::PhaseCount;
    pub use crate::view::lod::LodStats;
    pub use crate::view::CullSummary;
    pub use crate::visibility::stats::Counters;
}

/// The README's code, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
