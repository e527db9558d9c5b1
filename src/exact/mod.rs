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

/// Allowed disagreement relative to a face's projected area.
pub(crate) const REL_TOL: f64 = 1e-9;
/// Allowed disagreement from rounding alone, in ulps (2^-52) of the scene's largest screen
/// coordinate times the face's projected perimeter: any f64 output of a face's outline is
/// that far from the exact one (a sliver face may have less area than that).
pub(crate) const ROUNDING_ULPS: f64 = 16.0;

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
    /// The allowed mismatch: 1e-9 of the projected area plus 16 ulps of rounding.
    pub tolerance: f64,
}

impl FaceCheck {
    /// True when claim and answer agree within the tolerance.
    pub fn agrees(&self) -> bool {
        self.mismatch <= self.tolerance
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
}

impl ExactReport {
    /// The faces whose claim disagrees with the answer.
    pub fn disagreements(&self) -> Vec<&FaceCheck> {
        self.faces.iter().filter(|f| !f.agrees()).collect()
    }

    /// Total claimed area.
    pub fn claimed(&self) -> f64 {
        self.faces.iter().map(|f| f.claimed).sum()
    }

    /// True when every face agrees and the totals agree to 1e-9 of the projected area.
    pub fn agrees(&self) -> bool {
        self.disagreements().is_empty()
            && (self.claimed() - self.visible).abs() <= REL_TOL * self.projected
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
        .visible
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
    let perimeter: f64 = own
        .iter()
        .map(|p| {
            let n = p.ring.len();
            (0..n)
                .map(|i| {
                    let (a, b) = (&p.ring[i], &p.ring[(i + 1) % n]);
                    f(&(&b.x - &a.x)).hypot(f(&(&b.y - &a.y)))
                })
                .sum::<f64>()
        })
        .sum();
    let projected = a.projected;
    Some(FaceCheck {
        face: id,
        visible: a.visible,
        claimed: a.claimed,
        mismatch: a.mismatch,
        projected,
        tolerance: REL_TOL * projected + ROUNDING_ULPS * f64::EPSILON * scale * perimeter,
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
