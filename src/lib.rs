//! kepler: exact hidden-surface removal for polyhedral scenes, after W.R. Franklin's KEPLER
//! (1981). For a view it computes exactly which part of every face is visible — to the
//! precision of f64 arithmetic, not to a pixel — and draws it as SVG line drawings, PNG
//! pictures and canonical JSON visible-polygon sets.
//!
//! Data flows one way, one module per stage:
//! [`load`] → [`mod@prepare`] → [`view`] → [`visibility`] → [`emit`], and [`render()`] runs the
//! stages after `prepare` as one call:
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
//! The papers' names are kept: [`visibility::visfac()`], [`visibility::visp()`],
//! [`visibility::visobj()`], [`visibility::include()`], CBOX and INBOX ([`scene::Object`]),
//! [`tribox`].

pub mod check;
mod count;
mod describe;
pub mod emit;
pub mod error;
pub mod exact;
pub mod geom;
#[cfg(test)]
mod layering;
pub mod load;
pub mod pipeline;
pub mod prepare;
pub mod primitives;
pub mod progress;
pub mod query;
pub mod scene;
pub mod tribox;
pub mod view;
pub mod visibility;

#[cfg(test)]
mod tests;

pub use emit::{Drawing, EdgeKind, EdgeOptions, EdgeSet, LineOptions};
pub use error::{Error, Location, Pos, Result, Warning, Warnings};
pub use geom::{Box3, M4, P3, V3};
pub use load::{load_scene, LoadOptions};
pub use pipeline::{
    render, render_to, Outputs, PictureOptions, RenderOptions, RenderStats, Rendered,
};
pub use prepare::{prepare, HierarchyKind, PrepareOptions};
pub use progress::{Phase, PhaseCount, Progress, Stage, Unit};
pub use scene::{Content, Face, FaceId, Instance, Mesh, Object, Scene, Solidity};
pub use view::{Camera, CameraRequest, LodOptions, PieceId, Projection, View};
pub use visibility::{FaceVisibility, Visibility};

/// The line drawing: which edges are drawn, and the visible and hidden strokes a render makes.
pub mod lines {
    pub use crate::emit::{Drawing, EdgeKind, EdgeOptions, EdgeSet, LineOptions, Stroke};
}

/// Plotter pages and pens: page sizes, layers, hatching, colours, and what building a
/// picture did.
pub mod plot {
    pub use crate::emit::{HatchOptions, LayerMode, PageSize, Pen, PictureOptions, PlotStats, Rgb};
    pub use crate::geom::Rect;
}

/// What a render did: stage times, progress stages and phases, and the counters of the cull,
/// the visibility pass and level-of-detail substitution.
pub mod stats {
    pub use crate::pipeline::RenderStats;
    pub use crate::progress::{Phase, PhaseCount, Stage, Unit};
    pub use crate::view::{CullSummary, LodStats};
    pub use crate::visibility::Counters;
}

/// The README's code, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
