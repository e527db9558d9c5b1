//! Two visible-polygon sets compared face by face: the area of each face's symmetric
//! difference (i_overlay Xor on a fixed i64 grid) relative to the face's size, one rule for
//! faces that change, appear and vanish.

use std::collections::BTreeSet;

use super::visible_set::SetFace;
use super::VisibleSet;
use crate::geom::boolean::xor_area;
use crate::geom::poly2::{multipolygon_area, MultiPolygon};

/// How a face differs between two sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChangeKind {
    /// Visible in both, with regions that differ by more than the tolerance.
    Changed,
    /// Visible in the golden set only.
    Removed,
    /// Visible in the current set only.
    Added,
}

impl ChangeKind {
    /// The kind's name in reports: `changed`, `removed` or `added`.
    pub fn name(self) -> &'static str {
        match self {
            ChangeKind::Changed => "changed",
            ChangeKind::Removed => "removed",
            ChangeKind::Added => "added",
        }
    }
}

/// One face that differs.
#[derive(Debug, Clone, PartialEq)]
pub struct Change {
    /// The face's id.
    pub id: u64,
    /// Its object path (the current set's, else the golden's).
    pub object: String,
    /// How it differs.
    pub kind: ChangeKind,
    /// Its visible area in the golden set (0 where it is not visible there).
    pub golden_area: f64,
    /// Its visible area in the current set (0 where it is not visible there).
    pub current_area: f64,
    /// The area of the symmetric difference of its two visible regions (for a face visible
    /// on one side only, its area there).
    pub xor_area: f64,
    /// [`Change::xor_area`] relative to the face's size (see [`compare`]): what the
    /// tolerance bounds.
    pub relative: f64,
}

impl Change {
    /// The current area less the golden area.
    pub fn area_delta(&self) -> f64 {
        self.current_area - self.golden_area
    }
}

/// What [`compare`] or [`diff`] found: the report of `kepler check` and `kepler diff`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Comparison {
    /// The faces that differ by more than the tolerance, by id.
    pub changes: Vec<Change>,
    /// Whether the two sets' camera matrices differ (or one set has none). Reported only: it
    /// does not make the sets differ.
    pub camera_differs: bool,
    /// The tolerance the faces were judged by.
    pub tol: f64,
    /// The least size a face is measured against: [`FLOOR`] times the larger of the two
    /// sets' total visible areas.
    pub floor: f64,
    /// How many faces were compared (visible in either set).
    pub compared: usize,
}

/// A face's size is never taken below this fraction of the larger set's total visible area,
/// so that a face of a nearly empty region, or one seen on one side only without a scene to
/// give its projected area, is measured against the scene and not against itself.
pub const FLOOR: f64 = 1e-12;

/// Compares `current` with `golden`, one rule for every face visible in either: its change
/// is the area of the symmetric difference of its two visible regions (a region absent from a
/// set is empty), relative to the face's size, the largest of its projected area
/// (`projected(id)`, 0 where unknown), its two visible areas and the floor ([`FLOOR`] of the
/// larger set's total visible area). The face is listed when that exceeds `tol`: as
/// [`ChangeKind::Added`] or [`ChangeKind::Removed`] when it is visible on one side only,
/// else as [`ChangeKind::Changed`]. A face visible on one side only therefore counts 1 (its
/// whole region) unless its projected area or the floor is larger than its region.
pub fn compare(
    golden: &VisibleSet,
    current: &VisibleSet,
    tol: f64,
    projected: impl Fn(u64) -> f64,
) -> Comparison {
    let total = |s: &VisibleSet| -> f64 { s.faces.values().map(|f| area(&f.visible)).sum() };
    let floor = FLOOR * total(golden).max(total(current));
    let ids: BTreeSet<u64> = golden
        .faces
        .keys()
        .chain(current.faces.keys())
        .copied()
        .filter(|&id| visible(golden, id).is_some() || visible(current, id).is_some())
        .collect();
    let compared = ids.len();
    let changes = ids
        .into_iter()
        .filter_map(|id| {
            let (g, c) = (visible(golden, id), visible(current, id));
            let region = |f: Option<&SetFace>| f.map_or(0.0, |f| area(&f.visible));
            let (golden_area, current_area) = (region(g), region(c));
            let (kind, xor) = match (g, c) {
                (Some(g), Some(c)) => (ChangeKind::Changed, xor_area(&g.visible, &c.visible)),
                (Some(_), None) => (ChangeKind::Removed, golden_area),
                (None, _) => (ChangeKind::Added, current_area),
            };
            let size = projected(id).max(golden_area).max(current_area).max(floor);
            let relative = if size > 0.0 { xor / size } else { xor };
            let object = c.or(g).map_or(String::new(), |f| f.object.clone());
            (relative > tol).then_some(Change {
                id,
                object,
                kind,
                golden_area,
                current_area,
                xor_area: xor,
                relative,
            })
        })
        .collect();
    Comparison {
        changes,
        camera_differs: golden.matrix != current.matrix,
        tol,
        floor,
        compared,
    }
}

/// [`compare`] without a scene (no projected areas): `kepler diff`, and what a binding calls
/// with two parsed sets.
pub fn diff(golden: &VisibleSet, current: &VisibleSet, tol: f64) -> Comparison {
    compare(golden, current, tol, |_| 0.0)
}

/// Face `id` of `s` when it is visible there (listed with a non-empty region).
fn visible(s: &VisibleSet, id: u64) -> Option<&SetFace> {
    s.faces.get(&id).filter(|f| !f.visible.is_empty())
}

/// A region's area (its rings' orientation gives the sign; the magnitude is what counts).
fn area(m: &MultiPolygon) -> f64 {
    multipolygon_area(m).abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::SetFace;

    fn set(faces: &[(u64, [f64; 2])]) -> VisibleSet {
        let mut s = VisibleSet::default();
        for &(id, [x, w]) in faces {
            let ring = vec![[x, 0.0], [x + w, 0.0], [x + w, 1.0], [x, 1.0]];
            s.faces.insert(
                id,
                SetFace {
                    object: format!("o{id}"),
                    visible: vec![vec![ring]],
                    section: false,
                },
            );
        }
        s
    }

    #[test]
    fn finds_a_moved_face_and_nothing_else() {
        let a = set(&[(1, [0.0, 1.0]), (2, [5.0, 1.0])]);
        let b = set(&[(1, [0.0, 1.0]), (2, [5.0, 1.1])]);
        let r = diff(&a, &b, 1e-9);
        assert_eq!(r.changes.len(), 1);
        let c = &r.changes[0];
        assert_eq!((c.id, c.kind), (2, ChangeKind::Changed));
        assert!((c.relative - 0.1 / 1.1).abs() < 1e-9);
        assert!((c.xor_area - 0.1).abs() < 1e-12 && (c.area_delta() - 0.1).abs() < 1e-12);
        assert_eq!((c.golden_area, c.object.as_str()), (1.0, "o2"));
        assert_eq!((r.compared, r.camera_differs), (2, false));
        assert!(diff(&a, &a, 1e-9).changes.is_empty());
        // Below the tolerance it is no change.
        assert!(diff(&a, &b, 0.5).changes.is_empty());
    }

    #[test]
    fn added_and_removed_faces() {
        let a = set(&[(1, [0.0, 1.0])]);
        let b = set(&[(2, [0.0, 1.0])]);
        let r = diff(&a, &b, 1e-9);
        let kinds: Vec<_> = r.changes.iter().map(|c| (c.id, c.kind)).collect();
        assert_eq!(kinds, [(1, ChangeKind::Removed), (2, ChangeKind::Added)]);
        // A face on one side only changed by its whole region.
        assert!(r
            .changes
            .iter()
            .all(|c| c.relative == 1.0 && c.xor_area == 1.0));
        assert_eq!(
            (r.changes[0].current_area, r.changes[1].golden_area),
            (0.0, 0.0)
        );
        // A face listed with an empty region is not visible there.
        let mut e = a.clone();
        e.faces.get_mut(&1).unwrap().visible.clear();
        assert_eq!(diff(&a, &e, 1e-9).changes[0].kind, ChangeKind::Removed);
        assert_eq!(diff(&e, &e, 1e-9).compared, 0);
    }

    /// The noise: after one vertex moved, a face appears with an area of 2.09e-19 in
    /// a scene of visible area 2. It is judged by the tolerance like any other change:
    /// measured against the floor (2e-12), it changed by about 1e-7.
    #[test]
    fn appearing_and_vanishing_faces_obey_the_tolerance() {
        let a = set(&[(1, [0.0, 2.0])]);
        let mut b = a.clone();
        let dust = vec![vec![vec![[0.0, 3.0], [1e-9, 3.0], [0.0, 3.0 + 4.18e-10]]]];
        b.faces.insert(
            7,
            SetFace {
                object: "o7".into(),
                visible: dust,
                section: false,
            },
        );
        let rel = 2.09e-19 / 2e-12;
        for (x, y) in [(&a, &b), (&b, &a)] {
            let r = diff(x, y, 1e-9);
            assert_eq!(r.changes.len(), 1);
            assert!((r.changes[0].relative - rel).abs() < 1e-3 * rel, "{r:?}");
            assert!((r.floor - 2e-12).abs() < 1e-24);
            // Both sides of the threshold.
            assert_eq!(diff(x, y, 0.99 * rel).changes.len(), 1);
            assert!(diff(x, y, 1.01 * rel).changes.is_empty());
            assert!(diff(x, y, 0.05).changes.is_empty());
        }
        // With a scene, the face's projected area is its size.
        let r = compare(&a, &b, 1e-17, |id| if id == 7 { 1e-3 } else { 0.0 });
        assert!((r.changes[0].relative - 2.09e-16).abs() < 1e-18);
        // A face that appears with a real region counts whole, on either side of any tol < 1.
        let c = set(&[(1, [0.0, 2.0]), (9, [3.0, 0.5])]);
        assert_eq!(diff(&a, &c, 0.99).changes[0].kind, ChangeKind::Added);
        assert!(diff(&a, &c, 1.0).changes.is_empty());
        assert_eq!(diff(&c, &a, 0.99).changes[0].kind, ChangeKind::Removed);
    }
}
