//! Whether a mesh is a proven solid (its back faces may be culled), a capped open mesh (its
//! back faces may be culled away from its holes), or why not; decided in the prepare stage
//! ([`mod@crate::prepare::solidity`], [`mod@crate::prepare::solidity::caps`]).

/// Whether a mesh is a proven solid, or why not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Solidity {
    /// Closed, consistently and outward oriented, free of self-intersection: back faces
    /// may be culled.
    Solid,
    /// Some edge is used by one face only, and capping the holes does not make a solid
    /// (why: the defect of the capped surface).
    Open(CapFailure),
    /// Some edge is used by one face only, and the mesh with its holes capped by virtual
    /// faces ([`Mesh::caps`](crate::scene::Mesh::caps)) is a solid: back faces may be culled
    /// where no cap facing the viewer lies over them (the number of caps).
    Capped(u32),
    /// Some edge is used twice in one direction, or by more than two faces.
    Inconsistent,
    /// A face is not simple, or triangulates into a triangle of zero area.
    Degenerate,
    /// Two faces of one edge-connected piece meet other than in their shared vertices and
    /// edges (the count of crossing triangle pairs).
    SelfIntersecting(u64),
    /// A connected piece of the surface has negative (or zero) signed volume.
    InsideOut,
}

/// The edge-connected pieces of a mesh proven solid one by one where the whole mesh is not
/// ([`Mesh::proven`](crate::scene::Mesh::proven)): each closed (with its holes capped),
/// free of self-intersection and outward, so its back faces may be culled, away from its
/// caps. The culling argument is piece by piece ([`mod@crate::prepare::solidity`]).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub(crate) struct ProvenPieces {
    /// By face of the mesh: true on a proven piece.
    pub faces: Vec<bool>,
    /// Number of edge-connected pieces (of the capped surface, for an open mesh).
    pub pieces: u32,
    /// Number of them proven.
    pub proven: u32,
}

impl ProvenPieces {
    /// Number of the mesh's faces on proven pieces.
    pub(crate) fn proven_faces(&self) -> usize {
        self.faces.iter().filter(|&&f| f).count()
    }
}

/// Why an open mesh with its holes capped is not a solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum CapFailure {
    /// Capping was not tried (the mesh was decided before caps existed, or is too small to
    /// enclose anything).
    NotTried,
    /// A face of the mesh itself is not simple or has a triangle of zero area.
    MeshDegenerate,
    /// The mesh itself crosses itself (pairs of triangles).
    MeshSelfIntersecting(u64),
    /// A hole has zero area (its corners on one line: a crack along a T-junction) and an
    /// edge across it is not on a triangle, so it cannot be closed by splitting that edge
    /// (triangles are, [`crate::prepare::solidity::caps`]), and no cap triangle can close it.
    Slit,
    /// A cap has a triangle of zero area, fanned or ear-clipped.
    Degenerate,
    /// Caps cross the mesh or each other, fanned or ear-clipped (the number of holes whose
    /// caps cross: each cap's test stops at its first crossing).
    SelfIntersecting(u64),
    /// A connected piece of the capped surface has negative or zero volume (the mesh is
    /// wound inwards, or is a sheet with nothing inside).
    InsideOut,
    /// The capped surface is not closed and consistent: an ear-clipped cap repeats a face of
    /// the mesh (a face with all three corners on the loop, as at a height field's corner
    /// cells), so an edge gets three faces.
    Inconsistent,
}

impl Solidity {
    /// True when every back face may be culled.
    pub(crate) fn is_solid(self) -> bool {
        self == Solidity::Solid
    }

    /// True when back faces may be culled away from the caps.
    pub(crate) fn is_capped(self) -> bool {
        matches!(self, Solidity::Capped(_))
    }

    /// Why back faces are not culled (empty for a solid; for a capped mesh, where not).
    pub(crate) fn reason(self) -> String {
        match self {
            Solidity::Solid => String::new(),
            Solidity::Open(why) => format!("open (an edge has one face); {}", why.reason()),
            Solidity::Capped(n) => {
                format!("open, capped: back faces culled except near {n} caps")
            }
            Solidity::Inconsistent => {
                "inconsistent (an edge used twice in one direction or by more than two faces)"
                    .into()
            }
            Solidity::Degenerate => "degenerate (a face is not simple or has zero area)".into(),
            Solidity::SelfIntersecting(n) => {
                format!("self-intersecting ({n} pairs of triangles cross)")
            }
            Solidity::InsideOut => "inside out (a closed piece has negative volume)".into(),
        }
    }

    /// One word for the state: solid, open, capped, inconsistent, degenerate,
    /// self-intersecting, inside-out.
    pub(crate) fn word(self) -> &'static str {
        match self {
            Solidity::Solid => "solid",
            Solidity::Open(_) => "open",
            Solidity::Capped(_) => "capped",
            Solidity::Inconsistent => "inconsistent",
            Solidity::Degenerate => "degenerate",
            Solidity::SelfIntersecting(_) => "self-intersecting",
            Solidity::InsideOut => "inside-out",
        }
    }
}

impl CapFailure {
    /// Why capping failed, in words.
    pub(crate) fn reason(self) -> String {
        match self {
            CapFailure::NotTried => "capping not tried".into(),
            CapFailure::MeshDegenerate => {
                "not capped: a face is not simple or has zero area".into()
            }
            CapFailure::MeshSelfIntersecting(n) => {
                format!("not capped: the mesh crosses itself ({n} pairs of triangles)")
            }
            CapFailure::Slit => {
                "not capped: a T-junction crack (a hole of zero area) along a face that is not a triangle"
                    .into()
            }
            CapFailure::Degenerate => "capping failed: a cap triangle has zero area".into(),
            CapFailure::SelfIntersecting(n) => {
                format!(
                    "capping failed: caps cross the mesh or each other (the caps of {n} holes)"
                )
            }
            CapFailure::InsideOut => {
                "capping failed: the capped surface has a piece of negative or zero volume".into()
            }
            CapFailure::Inconsistent => {
                "capping failed: the capped surface is not closed and consistent (a cap repeats a face)"
                    .into()
            }
        }
    }
}
