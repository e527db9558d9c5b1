//! Franklin's queries on a scene, by object path and world point: INCLUDE (is a point inside
//! the scene's solids), VISP (is a point visible in a view), VISOBJ (what one object does to
//! another in a view), and the interference of objects (whose faces really meet).

use crate::error::{Error, Result};
use crate::geom::{M4, P3};
use crate::scene::Scene;
use crate::view::View;

pub use crate::tribox::interfere::{Interference, Method as InterfereMethod};
pub use crate::visibility::include::Inclusion;
pub use crate::visibility::visfac::Verdict;
pub use crate::visibility::visp::PointVisibility;

/// INCLUDE: whether `p` lies inside the scene's solids.
pub fn include(scene: &Scene, p: &P3) -> Inclusion {
    crate::visibility::include(&scene.root, &M4::identity(), p)
}

/// VISP: whether `p` is visible in `view` (hidden by no face of the scene).
pub fn visp(view: &View, p: &P3) -> PointVisibility {
    crate::visibility::visp(view, view.tree.root(), p, None)
}

/// VISOBJ: what object `a` does to object `b` in `view` (paths as `kepler info` prints them):
/// hides it wholly, leaves it wholly visible, or hides a part.
pub fn visobj(view: &View, a: &str, b: &str) -> Result<Verdict> {
    let find = |p: &str| {
        view.tree
            .object(p)
            .ok_or_else(|| Error::Usage(format!("no object '{p}' (see `kepler info`)")))
    };
    let (oa, ob) = (find(a)?, find(b)?);
    Ok(crate::visibility::visobj(view, oa.node, ob.faces.clone()))
}

/// The pairs of leaf objects whose triboxes meet, each with whether their faces intersect
/// (touching included), faces compared by `method` (every method gives the same answer).
pub fn interfere(scene: &Scene, method: InterfereMethod) -> Interference {
    crate::tribox::interfere::interfere_with(scene, method)
}
