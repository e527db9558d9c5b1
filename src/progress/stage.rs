//! The stages of a run and the phases within them, each with the unit it counts.

/// A stage of the pipeline, for times and progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Stage {
    /// Loading the scene (timed by the caller).
    Load,
    /// Level-of-detail substitution.
    Lod,
    /// INBOXes (the caller's, or the substitutes' under `lod`).
    Prepare,
    /// HIDDEN subtrees from boxes, before any face is projected.
    Cull,
    /// Projection of the remaining faces and the view tree.
    View,
    /// Every face's VTP.
    Visibility,
    /// The line drawing: edges and intersection curves clipped to the VTPs.
    Lines,
    /// JSON, SVG and PNG into memory.
    Emit,
}

impl Stage {
    /// Every stage, in pipeline order.
    pub const ALL: [Stage; 8] = [
        Stage::Load,
        Stage::Lod,
        Stage::Prepare,
        Stage::Cull,
        Stage::View,
        Stage::Visibility,
        Stage::Lines,
        Stage::Emit,
    ];

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Load => "load",
            Stage::Lod => "lod",
            Stage::Prepare => "prepare",
            Stage::Cull => "cull",
            Stage::View => "view",
            Stage::Visibility => "visibility",
            Stage::Lines => "lines",
            Stage::Emit => "emit",
        }
    }
}

/// A phase of a stage: a pass with a count of its own (a stage without phases is
/// [`Phase::Whole`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Phase {
    /// The stage as one piece of work (counted in the stage's own items, or not at all).
    Whole,
    /// Load: reading a file into memory (bytes).
    Read,
    /// Load: parsing a mesh file (bytes).
    Parse,
    /// Load: merging, checking and orienting a mesh file's faces (faces).
    Cleanup,
    /// Prepare: which meshes are solids, open meshes' caps (faces, each mesh once).
    Solidity,
    /// Prepare: INBOXes of closed meshes (faces, each mesh once).
    Inboxes,
    /// Prepare: object trees of large meshes (faces, each mesh once).
    Trees,
    /// View: faces projected to the screen (faces).
    Project,
    /// View: the screen-space object tree (faces placed in it).
    Tree,
    /// Lines: every face in world space with its normal and box (faces).
    World,
    /// Lines: the mesh edges and their kinds (faces).
    Edges,
    /// Lines: the curves where faces cross (faces).
    Intersections,
    /// Lines: every edge clipped to the visible regions beside it (edges).
    Clip,
    /// Emit: the JSON visible-polygon set (faces written).
    Json,
    /// Emit: the picture's hatching, face by visible face (faces).
    Hatch,
    /// Emit: the picture's lines placed on the page and clipped to its drawing area
    /// (segments).
    Page,
    /// Emit: the picture's lines on the page, each piece drawn once (segments looked at).
    Dedup,
    /// Emit: the picture's lines joined into strokes, hidden ones dashed (segments joined).
    Join,
    /// Emit: each layer's pen order, the tour of its strokes (strokes).
    Order,
    /// Emit: the picture's flat-shaded fills, face by visible face (faces).
    Fill,
    /// Emit: the SVG document, its fills' rings and its strokes written (polylines).
    Svg,
    /// Emit: the PNG picture, its fills' rings and its strokes painted, then the pixels
    /// encoded (polylines).
    Png,
}

impl Phase {
    /// Lower-case name ("" for [`Phase::Whole`]).
    pub fn name(self) -> &'static str {
        match self {
            Phase::Whole => "",
            Phase::Read => "read",
            Phase::Parse => "parse",
            Phase::Cleanup => "cleanup",
            Phase::Solidity => "solidity",
            Phase::Inboxes => "inboxes",
            Phase::Trees => "trees",
            Phase::Project => "project",
            Phase::Tree => "tree",
            Phase::World => "world",
            Phase::Edges => "edges",
            Phase::Intersections => "intersections",
            Phase::Clip => "clip",
            Phase::Json => "json",
            Phase::Hatch => "hatch",
            Phase::Page => "page",
            Phase::Fill => "fill",
            Phase::Dedup => "dedup",
            Phase::Join => "join",
            Phase::Order => "order",
            Phase::Svg => "svg",
            Phase::Png => "png",
        }
    }

    /// What the phase counts.
    pub fn unit(self) -> Unit {
        match self {
            Phase::Whole => Unit::Items,
            Phase::Read | Phase::Parse => Unit::Bytes,
            Phase::Clip => Unit::Edges,
            Phase::Page | Phase::Dedup | Phase::Join => Unit::Segments,
            Phase::Order => Unit::Strokes,
            Phase::Svg | Phase::Png => Unit::Polylines,
            _ => Unit::Faces,
        }
    }

    /// Every phase, in the order of the stages that have them.
    pub(crate) const ALL: [Phase; 22] = [
        Phase::Whole,
        Phase::Read,
        Phase::Parse,
        Phase::Cleanup,
        Phase::Solidity,
        Phase::Inboxes,
        Phase::Trees,
        Phase::Project,
        Phase::Tree,
        Phase::World,
        Phase::Edges,
        Phase::Intersections,
        Phase::Clip,
        Phase::Json,
        Phase::Hatch,
        Phase::Page,
        Phase::Dedup,
        Phase::Join,
        Phase::Order,
        Phase::Fill,
        Phase::Svg,
        Phase::Png,
    ];
}

/// What a phase counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Unit {
    /// The stage's own items (the visibility stage's are faces' planar pieces).
    Items,
    /// Bytes of a file.
    Bytes,
    /// Faces.
    Faces,
    /// Edges of the line drawing.
    Edges,
    /// Straight pieces of the picture's lines on the page.
    Segments,
    /// Strokes of the picture: what a plotter draws with its pen down.
    Strokes,
    /// Polylines of the finished picture: its strokes and its fills' rings.
    Polylines,
}

impl Unit {
    /// The unit's plural noun ("" for [`Unit::Items`]).
    pub fn name(self) -> &'static str {
        match self {
            Unit::Items => "",
            Unit::Bytes => "bytes",
            Unit::Faces => "faces",
            Unit::Edges => "edges",
            Unit::Segments => "segments",
            Unit::Strokes => "strokes",
            Unit::Polylines => "polylines",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_phase_is_listed_once_with_a_name() {
        for (k, p) in Phase::ALL.iter().enumerate() {
            assert_eq!(Phase::ALL.iter().position(|q| q == p), Some(k));
            assert_eq!(p.name().is_empty(), *p == Phase::Whole);
        }
        assert_eq!(Phase::Parse.unit(), Unit::Bytes);
        assert_eq!(Phase::Clip.unit().name(), "edges");
        assert_eq!(Phase::Order.unit().name(), "strokes");
        assert_eq!(Stage::ALL.map(Stage::name)[5], "visibility");
    }
}
