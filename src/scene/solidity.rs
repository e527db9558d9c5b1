//! Whether a mesh is a proven solid (its back faces may be culled), or why not; decided in
//! the prepare stage ([`mod@crate::prepare::solidity`]).

/// Whether a mesh is a proven solid, or why not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Solidity {
    /// Closed, consistently and outward oriented, free of self-intersection: back faces
    /// may be culled.
    Solid,
    /// Some edge is used by one face only.
    Open,
    /// Some edge is used twice in one direction, or by more than two faces.
    Inconsistent,
    /// A face is not simple, or triangulates into a triangle of zero area.
    Degenerate,
    /// Two faces meet other than in their shared vertices and edges (the count of crossing
    /// triangle pairs).
    SelfIntersecting(u64),
    /// A connected piece of the surface has negative (or zero) signed volume.
    InsideOut,
}

impl Solidity {
    /// True when back faces may be culled.
    pub fn is_solid(self) -> bool {
        self == Solidity::Solid
    }

    /// Why back faces are not culled (empty for a solid).
    pub fn reason(self) -> String {
        match self {
            Solidity::Solid => String::new(),
            Solidity::Open => "open (an edge has one face)".into(),
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

    /// One word for the state: solid, open, inconsistent, degenerate, self-intersecting,
    /// inside-out.
    pub fn word(self) -> &'static str {
        match self {
            Solidity::Solid => "solid",
            Solidity::Open => "open",
            Solidity::Inconsistent => "inconsistent",
            Solidity::Degenerate => "degenerate",
            Solidity::SelfIntersecting(_) => "self-intersecting",
            Solidity::InsideOut => "inside-out",
        }
    }
}
