//! Checking a render: against the independent exact answer ([`exact`]), against a golden
//! `kepler-visible/1` set ([`VisibleSet`], [`compare`] with a scene's projected areas, [`diff`]
//! without one; the report, [`Comparison`], as text or `kepler-diff/1` JSON), and the areas
//! such checks measure (the one boolean adapter: [`xor_area`], [`union`] on a fixed grid;
//! [`multipolygon_area`]).
//!
//! ```
//! use kepler_hsr::check::{diff, ChangeKind, VisibleSet};
//!
//! let golden = r#"{"format":"kepler-visible/1","faces":[{"id":3,"object":"a","visible":[[[[0,0],[1,0],[0,1]]]]}]}"#;
//! let current = golden.replace("[0,1]", "[0,2]");
//! let golden = VisibleSet::parse(golden, "golden.json".as_ref())?;
//! let current = VisibleSet::parse(&current, "current.json".as_ref())?;
//! assert!(diff(&golden, &golden, 1e-9).is_same());
//! let report = diff(&golden, &current, 0.1);
//! assert_eq!(report.changes[0].kind, ChangeKind::Changed);
//! assert!((report.changes[0].relative - 0.5).abs() < 1e-12); // half the larger region
//! assert!(report.to_json().contains("\"kind\":\"changed\""));
//! assert!(diff(&golden, &current, 0.6).is_same());
//! # Ok::<(), kepler_hsr::Error>(())
//! ```

mod compare;
mod report;
mod visible_set;

pub use crate::exact::{check as exact, ExactReport, FaceCheck, ALLOWANCE_UNITS};
pub use crate::geom::boolean::{union, xor_area};
pub use crate::geom::poly2::{multipolygon_area, ring_area, MultiPolygon, Polygon, Pt2, Ring};
pub use compare::{compare, diff, Change, ChangeKind, Comparison, FLOOR};
pub use visible_set::{SetFace, VisibleSet};
