//! Long faces (a prism of 300 sides, a 500-gon through the boxes) against small ones: the visibility
//! pass with long occluders cut to each face's window (view::ring_index) gives the same
//! visible polygons as the pass on whole rings, in several views.

use super::common::*;
use crate::geom::{P3, V3};
use crate::primitives::prism;
use crate::scene::{Mesh, Scene};
use crate::view::{Camera, View};
use crate::visibility::{solve, PassOptions};

/// A 300-sided prism (about 48 across, 1 tall) lying over a row of small boxes and a
/// 500-gon cutting through them (exactly planar, so it stays one piece).
fn scene_of_long_faces() -> Scene {
    let mut objs = vec![("prism", prim(prism(300).expect("prism")))];
    let boxes: Vec<Mesh> = (0..8)
        .map(|i| {
            let x = -30.0 + 8.0 * i as f64;
            cuboid([x, -2.0, -3.0], [x + 3.0, 2.0, -1.5])
        })
        .collect();
    let names: Vec<String> = (0..boxes.len()).map(|i| format!("box{i}")).collect();
    for (n, b) in names.iter().zip(boxes) {
        objs.push((n.as_str(), b));
    }
    let n = 500;
    let pts: Vec<[f64; 3]> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            [20.0 * a.cos(), 20.0 * a.sin(), -2.25]
        })
        .collect();
    let ring: Vec<u32> = (0..n as u32).collect();
    let disc = mesh(&pts, &[&ring]);
    objs.push(("disc", disc));
    scene(objs)
}

#[test]
fn cut_rings_give_the_whole_rings_answer() {
    let scene = scene_of_long_faces();
    let cameras = [
        top(),
        Camera::orthographic(V3::new(-0.3, -0.5, -1.0), V3::y()).unwrap(),
        Camera::orthographic(V3::new(0.7, 0.2, -0.4), V3::z()).unwrap(),
        Camera::perspective(
            P3::new(5.0, -60.0, 40.0),
            P3::new(0.0, 0.0, -1.0),
            V3::z(),
            45.0,
            0.1,
        )
        .unwrap(),
    ];
    let mut indexed = 0;
    for cam in cameras {
        let view = View::new(&scene, cam);
        indexed += view.screen.ring_indexes.len();
        let cut = solve(&view, PassOptions::default(), Default::default());
        let mut whole_view = view.clone();
        std::sync::Arc::make_mut(&mut whole_view.screen)
            .ring_indexes
            .clear();
        let whole = solve(&whole_view, PassOptions::default(), Default::default());
        let total: f64 = whole.by_id().iter().map(|f| f.area).sum();
        assert!(total > 0.0);
        for (a, b) in cut.by_id().iter().zip(whole.by_id()) {
            // The same regions: equal areas (up to the boolean's grid), and most bit for bit.
            close(a.area, b.area, 1e-9);
        }
    }
    assert!(
        indexed >= 4 * 3,
        "the prism's caps and the disc are indexed: {indexed}"
    );
}
