//! The regions of faces nothing hides, made from the screen faces when read, are the ones
//! the pass kept before (issue 35): ring, start, orientation and area to the bit.

use std::borrow::Cow;

use super::common::{load, prepare, render_plain, top};
use crate::geom::poly2::multipolygon_area;
use crate::geom::poly2::{canonicalize, MultiPolygon, Pt2};
use crate::geom::ring_check::ring_defect;
use crate::scene::FaceId;
use crate::view::Camera;
use crate::view::{PieceId, ScreenFaces};

/// What the pass kept for a face nothing hides before its region was made when read
/// (issue 35, code as it was): its one piece's ring, counter-clockwise, canonicalised.
fn kept_before(screen: &ScreenFaces, id: FaceId) -> MultiPolygon {
    let pieces = screen.piece_span(id..id.offset(1));
    assert_eq!(pieces.len(), 1, "face {id}: a whole face is one piece");
    let ring = screen.ring_ccw(PieceId(pieces.start as u32));
    assert!(ring_defect(&ring, true).is_none(), "face {id}");
    let mut visible = vec![vec![ring]];
    canonicalize(&mut visible);
    visible
}

#[test]
fn whole_regions_read_as_they_were_kept() {
    let sorted = |mut v: Vec<Pt2>| {
        v.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        v
    };
    for name in ["polyhedra", "town", "assembly"] {
        let mut scene = load(format!("scenes/{name}.kdl").as_ref());
        prepare(&mut scene);
        for camera in [Camera::three_quarter(), top()] {
            let r = render_plain(&scene, &camera);
            let (view, vis) = (&r.view, &r.visibility);
            let mut whole = 0;
            for (id, fv) in vis.iter() {
                let region = fv.visible();
                // The area is the region's, to the bit, as the pass measured it (an empty
                // region's area is 0, not the empty sum's -0).
                if !region.is_empty() {
                    let area = multipolygon_area(&region);
                    assert_eq!(fv.area.to_bits(), area.to_bits(), "{name}: face {id}");
                }
                assert_eq!(fv.is_empty(), region.is_empty(), "{name}: face {id}");
                let pts = fv.fold_points(Vec::new(), |mut v, p| {
                    v.push(p);
                    v
                });
                let all: Vec<Pt2> = region.iter().flatten().flatten().copied().collect();
                assert_eq!(sorted(pts), sorted(all), "{name}: face {id}");
                if fv.whole() {
                    whole += 1;
                    assert!(matches!(region, Cow::Owned(_)));
                    assert_eq!(*region, kept_before(&view.screen, id), "{name}: face {id}");
                }
                assert_eq!(vis.face(id), fv);
            }
            assert!(whole > 0, "{name}: no face left whole");
        }
    }
}
