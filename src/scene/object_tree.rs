//! The object tree B(T) of a flat mesh (paper 002) as the scene holds it: its nodes, CBOXes
//! and face ranges, the component tree C(T) it was built from, and what building it took.
//! The prepare stage builds it ([`mod@crate::prepare::trees`]); the view and interference
//! queries walk it.

use std::ops::Range;
use std::time::Duration;

use crate::geom::Box3;

/// Which object tree a flat mesh gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum HierarchyKind {
    /// Paper 002: components of simplified models, merged bottom-up, median split below.
    #[default]
    Simplify,
    /// The median split alone (kepler's tree before paper 002).
    Median,
}

impl HierarchyKind {
    /// Lower-case name, as the `--hierarchy` flag spells it.
    pub fn name(self) -> &'static str {
        match self {
            HierarchyKind::Simplify => "simplify",
            HierarchyKind::Median => "median",
        }
    }
}

/// A node of B(T): a set of faces (a range of [`ObjectTree::faces`]) and its CBOX.
#[derive(Debug, Clone, PartialEq)]
pub struct TreeNode {
    /// CBOX of the node's faces, in the mesh's frame.
    pub cbox: Box3,
    /// The node's faces: a range of [`ObjectTree::faces`].
    pub faces: Range<u32>,
    /// The two children, if not a leaf.
    pub children: Option<[u32; 2]>,
    /// True for a node of the upper BV-tree: a component of C(T) or a merge of components.
    pub component: bool,
    /// An INBOX of the node's region (a box inside the closed mesh within the node's CBOX),
    /// where the prepare stage found one.
    pub inbox: Option<Box3>,
}

/// Preprocessing times, split as the paper's Table 1.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BuildTimes {
    /// Simplification plus component computation.
    pub components: Duration,
    /// Bottom-up conversion of C(T) to the upper levels of B(T).
    pub bottom_up: Duration,
    /// Top-down split below the leaf components (all of the median tree).
    pub top_down: Duration,
}

/// Size of a tree, for `kepler info`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TreeShape {
    /// Nodes.
    pub nodes: usize,
    /// Depth (a lone root has depth 0).
    pub depth: usize,
    /// Leaves.
    pub leaves: usize,
    /// Nodes of the upper BV-tree (components and their merges).
    pub component_nodes: usize,
}

/// B(T) of one mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectTree {
    /// How it was built.
    pub kind: HierarchyKind,
    /// The nodes, in depth-first order; the root is node 0.
    pub nodes: Vec<TreeNode>,
    /// Local face indices, ordered so that every node's faces are contiguous.
    pub faces: Vec<u32>,
    /// C(T) (empty for the median tree).
    pub components: ComponentTree,
    /// Preprocessing times.
    pub times: BuildTimes,
}

impl ObjectTree {
    /// The local faces of node `n`.
    pub fn faces_of(&self, n: u32) -> &[u32] {
        let r = &self.nodes[n as usize].faces;
        &self.faces[r.start as usize..r.end as usize]
    }

    /// Nodes, depth, leaves and upper nodes.
    pub fn shape(&self) -> TreeShape {
        let mut s = TreeShape::default();
        let mut stack = vec![(0u32, 0usize)];
        while let Some((n, d)) = stack.pop() {
            let node = &self.nodes[n as usize];
            s.nodes += 1;
            s.depth = s.depth.max(d);
            s.component_nodes += node.component as usize;
            match node.children {
                Some([l, r]) => stack.extend([(l, d + 1), (r, d + 1)]),
                None => s.leaves += 1,
            }
        }
        s
    }

    /// Sum of the CBOX volumes of all nodes (the paper's "bounding volume per instance").
    pub fn total_volume(&self) -> f64 {
        self.nodes.iter().map(|n| n.cbox.volume()).sum()
    }
}

/// A node of C(T): a component (a set of the original faces).
#[derive(Debug, Clone, PartialEq)]
pub struct Component {
    /// Level of the simplified model that made it (0: the whole mesh, 1: the coarsest model).
    pub level: usize,
    /// Its faces (local face indices, ascending).
    pub faces: Vec<u32>,
    /// Its sub-components (indices into [`ComponentTree::nodes`]); empty for a leaf.
    pub children: Vec<u32>,
}

/// C(T) with the simplified models that made it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ComponentTree {
    /// Cell width of each simplified model, coarsest first.
    pub widths: Vec<f64>,
    /// Vertices left in each simplified model (clusters).
    pub clusters: Vec<usize>,
    /// Components made from each simplified model (new nodes of that level).
    pub per_level: Vec<usize>,
    /// The nodes; the root (all faces) is node 0.
    pub nodes: Vec<Component>,
}
