//! Two visible-polygon sets compared face by face: the area of each face's symmetric
//! difference (i_overlay Xor on a fixed i64 grid) relative to the face's size.

use std::collections::BTreeSet;

use super::VisibleSet;
use crate::geom::boolean::xor_area;
use crate::geom::poly2::multipolygon_area;

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

/// One face that differs.
#[derive(Debug, Clone, PartialEq)]
pub struct Change {
    /// The face's id.
    pub id: u64,
    /// Its object path (the current set's, else the golden's).
    pub object: String,
    /// How it differs.
    pub kind: ChangeKind,
    /// For [`ChangeKind::Changed`]: the symmetric difference relative to the face's size.
    pub relative: f64,
}

/// What [`compare`] found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Comparison {
    /// The faces that differ, by id.
    pub changes: Vec<Change>,
    /// Whether the two sets' camera matrices differ (or one set has none).
    pub camera_differs: bool,
}

/// Compares `current` with `golden`. A face present in both changes when the area of the
/// symmetric difference of its two regions, relative to the largest of its projected area
/// (`projected(id)`, 0 where unknown), its two visible areas and 1e-12 of the current set's
/// visible area, exceeds `tol`. A face present on one side only is always a change.
pub fn compare(
    golden: &VisibleSet,
    current: &VisibleSet,
    tol: f64,
    projected: impl Fn(u64) -> f64,
) -> Comparison {
    let scene_area: f64 = current
        .faces
        .values()
        .map(|f| multipolygon_area(&f.visible).abs())
        .sum();
    let ids: BTreeSet<u64> = golden
        .faces
        .keys()
        .chain(current.faces.keys())
        .copied()
        .collect();
    let changes = ids
        .into_iter()
        .filter_map(|id| {
            let change = |object: &str, kind, relative| Change {
                id,
                object: object.to_string(),
                kind,
                relative,
            };
            match (golden.faces.get(&id), current.faces.get(&id)) {
                (Some(g), Some(c)) => {
                    let diff = xor_area(&g.visible, &c.visible);
                    let area = projected(id)
                        .max(multipolygon_area(&g.visible).abs())
                        .max(multipolygon_area(&c.visible).abs())
                        .max(1e-12 * scene_area);
                    let rel = if area > 0.0 { diff / area } else { diff };
                    (rel > tol).then(|| change(&c.object, ChangeKind::Changed, rel))
                }
                (Some(g), None) => Some(change(&g.object, ChangeKind::Removed, 0.0)),
                (None, Some(c)) => Some(change(&c.object, ChangeKind::Added, 0.0)),
                (None, None) => None,
            }
        })
        .collect();
    let camera_differs = golden.matrix != current.matrix;
    Comparison {
        changes,
        camera_differs,
    }
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
                },
            );
        }
        s
    }

    #[test]
    fn finds_a_moved_face_and_nothing_else() {
        let a = set(&[(1, [0.0, 1.0]), (2, [5.0, 1.0])]);
        let b = set(&[(1, [0.0, 1.0]), (2, [5.0, 1.1])]);
        let r = compare(&a, &b, 1e-9, |_| 0.0);
        assert_eq!(r.changes.len(), 1);
        assert_eq!(
            (r.changes[0].id, r.changes[0].kind),
            (2, ChangeKind::Changed)
        );
        assert!((r.changes[0].relative - 0.1 / 1.1).abs() < 1e-9);
        assert!(compare(&a, &a, 1e-9, |_| 0.0).changes.is_empty());
        // Below the tolerance it is no change.
        assert!(compare(&a, &b, 0.5, |_| 0.0).changes.is_empty());
    }

    #[test]
    fn added_and_removed_faces() {
        let a = set(&[(1, [0.0, 1.0])]);
        let b = set(&[(2, [0.0, 1.0])]);
        let kinds: Vec<_> = compare(&a, &b, 1e-9, |_| 0.0)
            .changes
            .iter()
            .map(|c| (c.id, c.kind))
            .collect();
        assert_eq!(kinds, [(1, ChangeKind::Removed), (2, ChangeKind::Added)]);
    }
}
