//! Checking a render: against the independent exact answer ([`exact`]), against a golden
//! `kepler-visible/1` set ([`VisibleSet`], [`compare`]), and the areas such checks measure
//! (the one boolean adapter: [`xor_area`], [`union`] on a fixed grid; [`multipolygon_area`]).
//!
//! ```
//! use kepler_hsr::check::{compare, VisibleSet};
//!
//! let golden = r#"{"format":"kepler-visible/1","faces":[{"id":3,"object":"a","visible":[[[[0,0],[1,0],[0,1]]]]}]}"#;
//! let set = VisibleSet::parse(golden, "golden.json".as_ref())?;
//! let report = compare(&set, &set, 1e-9, |_| 0.0);
//! assert!(report.changes.is_empty());
//! # Ok::<(), kepler_hsr::Error>(())
//! ```

mod compare;
mod visible_set;

pub use crate::exact::{check as exact, ExactReport, FaceCheck};
pub use crate::geom::boolean::{union, xor_area};
pub use crate::geom::poly2::{multipolygon_area, ring_area, MultiPolygon, Polygon, Pt2, Ring};
pub use compare::{compare, Change, ChangeKind, Comparison};
pub use visible_set::{SetFace, VisibleSet};
