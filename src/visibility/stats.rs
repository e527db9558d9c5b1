//! Counters of the visibility pass: what was pruned, clipped and emptied, per face summed.

use std::ops::AddAssign;

/// Work counters (summed over faces; identical whatever the thread count).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Faces solved with a tree walk.
    pub faces_walked: u64,
    /// Faces edge-on or behind the near plane (invisible, no work).
    pub faces_edge_on: u64,
    /// Back faces of solids, and of capped open meshes away from their caps (hidden by their
    /// own surface, no work).
    pub faces_culled: u64,
    /// Faces inside a subtree found HIDDEN as a whole before any face work.
    pub faces_in_hidden_subtrees: u64,
    /// Subtrees whose CBOX the cull tested against inboxes (before projecting faces).
    pub subtrees_tested: u64,
    /// Subtrees found HIDDEN as a whole by an inbox before any face work.
    pub subtrees_hidden: u64,
    /// Tree nodes visited by the walks (each node popped counts once per face walked).
    pub nodes_visited: u64,
    /// Tree nodes skipped because their CBOX cannot hide the face.
    pub skipped_by_cbox: u64,
    /// VTPs emptied at once by an INBOX that hides the whole face.
    pub emptied_by_inbox: u64,
    /// VTPs emptied at once by a single face covering the whole face.
    pub emptied_by_face: u64,
    /// VTPs emptied at once by several faces whose regions together cover the face.
    pub emptied_by_patch: u64,
    /// Candidate faces examined at the leaves.
    pub faces_examined: u64,
    /// Occluder regions passed to clipping.
    pub occluders: u64,
    /// Faces that needed a boolean call.
    pub faces_clipped: u64,
    /// Faces left whole (nothing in front).
    pub faces_whole: u64,
}

impl AddAssign for Counters {
    fn add_assign(&mut self, o: Counters) {
        self.faces_walked += o.faces_walked;
        self.faces_edge_on += o.faces_edge_on;
        self.faces_culled += o.faces_culled;
        self.faces_in_hidden_subtrees += o.faces_in_hidden_subtrees;
        self.subtrees_tested += o.subtrees_tested;
        self.subtrees_hidden += o.subtrees_hidden;
        self.nodes_visited += o.nodes_visited;
        self.skipped_by_cbox += o.skipped_by_cbox;
        self.emptied_by_inbox += o.emptied_by_inbox;
        self.emptied_by_face += o.emptied_by_face;
        self.emptied_by_patch += o.emptied_by_patch;
        self.faces_examined += o.faces_examined;
        self.occluders += o.occluders;
        self.faces_clipped += o.faces_clipped;
        self.faces_whole += o.faces_whole;
    }
}

impl Counters {
    /// Lines of `name value` for printing.
    pub fn lines(&self) -> Vec<(&'static str, u64)> {
        vec![
            ("faces walked", self.faces_walked),
            ("faces edge-on or clipped", self.faces_edge_on),
            (
                "faces culled (back faces of solids and capped meshes)",
                self.faces_culled,
            ),
            (
                "subtrees box-tested before projection",
                self.subtrees_tested,
            ),
            ("subtrees hidden by inboxes", self.subtrees_hidden),
            ("faces in hidden subtrees", self.faces_in_hidden_subtrees),
            ("tree nodes visited", self.nodes_visited),
            ("subtrees skipped by CBOX", self.skipped_by_cbox),
            ("VTPs emptied by an INBOX", self.emptied_by_inbox),
            ("VTPs emptied by one covering face", self.emptied_by_face),
            (
                "VTPs emptied by covering faces together",
                self.emptied_by_patch,
            ),
            ("candidate faces examined", self.faces_examined),
            ("occluders clipped", self.occluders),
            ("faces clipped (boolean calls)", self.faces_clipped),
            ("faces left whole", self.faces_whole),
        ]
    }
}
