//! An independent exact check of a render: every face's visible region decided in rational
//! arithmetic, with no floating-point decision, no tolerance and no boolean engine, for
//! small scenes (slow: big rationals, a trapezoidal decomposition per face).
//!
//! The scene is what kepler renders: world points as f64 (the leaf transforms applied as the
//! scene defines them), faces split into planar pieces by the warped-face rule
//! ([`crate::view::screen::planar_pieces`]), the camera's f64 matrix and near plane. From
//! there everything is exact: projection, near-plane clipping, depth planes, every crossing,
//! and the owner of every trapezoid. Faces are two-sided, edge-on faces show and hide
//! nothing, nothing is culled, and where two faces are coplanar the earlier one is in front
//! (docs/design.md). Against that, [`check`] measures each face's claimed visible region (a
//! [`Visibility`]) by the exact area of its symmetric difference with the answer.

pub(crate) mod fraction;
pub(crate) mod project;
pub(crate) mod rational;
pub(crate) mod trapezoids;

use rayon::prelude::*;

use crate::scene::{FaceId, Scene};
use crate::view::Camera;
use crate::visibility::Visibility;

use project::{exact_pieces, ExactPiece};
use rational::{q, QPt, Q};
use trapezoids::face_areas;

/// The default allowance per face, in units of output rounding: a face agrees when the area of
/// its symmetric difference with the exact answer is at most this many units, one unit being
/// 2^-52 · S · P (S the largest |screen coordinate| of the scene's projected faces, P the face's
/// exact projected perimeter): what moving every point of its outline by one ulp of S can
/// change. Constructions rounded once and output rounded once stay within it
/// (docs/numerics.md).
pub const ALLOWANCE_UNITS: f64 = 4.0;

/// One face's claim against the exact answer.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceCheck {
    /// The face.
    pub face: FaceId,
    /// Exactly visible area.
    pub visible: f64,
    /// Claimed visible area (inside and outside the face).
    pub claimed: f64,
    /// Area of the symmetric difference of claim and answer.
    pub mismatch: f64,
    /// The face's exact projected area.
    pub projected: f64,
    /// One unit of output rounding for this face: 2^-52 · S · perimeter.
    pub unit: f64,
    /// The mismatch in units of output rounding (`mismatch / unit`).
    pub units: f64,
    /// The allowed mismatch: [`ALLOWANCE_UNITS`] units.
    pub tolerance: f64,
}

impl FaceCheck {
    /// True when claim and answer agree within [`ALLOWANCE_UNITS`] units.
    pub fn agrees(&self) -> bool {
        self.agrees_within(ALLOWANCE_UNITS)
    }

    /// True when claim and answer agree within `units` units of output rounding.
    pub fn agrees_within(&self, units: f64) -> bool {
        self.mismatch <= units * self.unit
    }
}

/// The whole check.
#[derive(Debug, Clone, PartialEq)]
pub struct ExactReport {
    /// Every face that shows area or has a claim, in global order.
    pub faces: Vec<FaceCheck>,
    /// Total exactly visible area.
    pub visible: f64,
    /// Total projected area of all faces.
    pub projected: f64,
    /// S: the largest |screen coordinate| of the projected faces (the scale of one unit).
    pub scale: f64,
}

impl ExactReport {
    /// The faces whose claim disagrees with the answer by more than [`ALLOWANCE_UNITS`].
    pub fn disagreements(&self) -> Vec<&FaceCheck> {
        self.disagreements_within(ALLOWANCE_UNITS)
    }

    /// The faces whose claim disagrees with the answer by more than `units`.
    pub fn disagreements_within(&self, units: f64) -> Vec<&FaceCheck> {
        self.faces
            .iter()
            .filter(|f| !f.agrees_within(units))
            .collect()
    }

    /// Total claimed area.
    pub fn claimed(&self) -> f64 {
        self.faces.iter().map(|f| f.claimed).sum()
    }

    /// The largest mismatch of any face, in units of output rounding (0 with no face).
    pub fn worst_units(&self) -> f64 {
        self.faces.iter().map(|f| f.units).fold(0.0, f64::max)
    }

    /// True when every face agrees within [`ALLOWANCE_UNITS`] (a per-face test: totals are
    /// not compared, as their rounding grows with the scene).
    pub fn agrees(&self) -> bool {
        self.disagreements().is_empty()
    }

    /// True when every face agrees within `units`.
    pub fn agrees_within(&self, units: f64) -> bool {
        self.disagreements_within(units).is_empty()
    }
}

/// Checks every face's claimed visible region in `vis` against the exact answer for
/// `scene` seen by `camera`. Only `faces` when given (ids in global order).
pub fn check(
    scene: &Scene,
    camera: &Camera,
    vis: &Visibility,
    faces: Option<&[FaceId]>,
) -> ExactReport {
    let pieces = exact_pieces(scene, camera);
    let scale = pieces
        .iter()
        .flat_map(|p| {
            [
                p.rect[0].abs(),
                p.rect[1].abs(),
                p.rect[2].abs(),
                p.rect[3].abs(),
            ]
        })
        .fold(0.0f64, f64::max);
    let all: Vec<FaceId> = (0..scene.face_count() as u32).map(FaceId).collect();
    let ids = faces.unwrap_or(&all);
    let results: Vec<FaceCheck> = ids
        .par_iter()
        .filter_map(|&id| face_check(id, &pieces, vis, scale))
        .collect();
    ExactReport {
        visible: results.iter().map(|f| f.visible).sum(),
        projected: results.iter().map(|f| f.projected).sum(),
        faces: results,
        scale,
    }
}

fn face_check(
    id: FaceId,
    pieces: &[ExactPiece],
    vis: &Visibility,
    scale: f64,
) -> Option<FaceCheck> {
    let own: Vec<&ExactPiece> = pieces.iter().filter(|p| p.face == id.0).collect();
    let claim: Vec<Vec<QPt>> = vis
        .face(id)
        .visible()
        .iter()
        .flatten()
        .map(|r| {
            r.iter()
                .map(|p| QPt {
                    x: q(p[0]),
                    y: q(p[1]),
                })
                .collect()
        })
        .collect();
    if own.is_empty() && claim.is_empty() {
        return None;
    }
    let a = if own.is_empty() {
        // Nothing of the face shows: all of the claim is wrong.
        let area: Q = claim.iter().map(|r| ring_area(r)).sum::<Q>();
        let area = area.to_f64().unwrap_or(f64::NAN).abs();
        trapezoids::FaceAreas {
            claimed: area,
            mismatch: area,
            ..Default::default()
        }
    } else {
        face_areas(&own, pieces, &claim)
    };
    let f = |x: &Q| x.to_f64().unwrap_or(f64::NAN);
    let ring_length = |r: &[QPt]| {
        let n = r.len();
        (0..n)
            .map(|i| {
                let (a, b) = (&r[i], &r[(i + 1) % n]);
                f(&(&b.x - &a.x)).hypot(f(&(&b.y - &a.y)))
            })
            .sum::<f64>()
    };
    // The face's own outline; a face that shows nothing but is claimed: the claim's.
    let perimeter: f64 = if own.is_empty() {
        claim.iter().map(|r| ring_length(r)).sum()
    } else {
        own.iter().map(|p| ring_length(&p.ring)).sum()
    };
    let unit = f64::EPSILON * scale * perimeter;
    let units = if a.mismatch == 0.0 {
        0.0
    } else {
        a.mismatch / unit
    };
    Some(FaceCheck {
        face: id,
        visible: a.visible,
        claimed: a.claimed,
        mismatch: a.mismatch,
        projected: a.projected,
        unit,
        units,
        tolerance: ALLOWANCE_UNITS * unit,
    })
}

/// Signed area of a ring (exact shoelace).
fn ring_area(r: &[QPt]) -> Q {
    let n = r.len();
    let mut s = Q::int(0);
    for i in 0..n {
        let (a, b) = (&r[i], &r[(i + 1) % n]);
        s += &a.x * &b.y - &b.x * &a.y;
    }
    s / Q::int(2)
}
