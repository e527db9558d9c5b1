//! The `--hierarchy` flag of render and query: which object tree flat meshes get.

use clap::{Args, ValueEnum};
use kepler_hsr::{HierarchyKind, PrepareOptions};

/// `--hierarchy` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum HierarchyArg {
    /// Paper 002: components of simplified models, merged bottom-up (prepared once).
    Simplify,
    /// The median split (made per view for rendering; in 3D for --interfere).
    Median,
}

/// The flag itself.
#[derive(Args, Debug, Clone, Copy, Default)]
pub(crate) struct HierarchyArgs {
    /// Object tree of flat meshes: simplify (paper 002) or median; answers are identical.
    /// Default, the faster as measured: for render, simplify for meshes placed more than
    /// once and median for a mesh drawn once; for --interfere, simplify.
    #[arg(long, value_enum, value_name = "KIND")]
    pub(crate) hierarchy: Option<HierarchyArg>,
}

impl HierarchyArgs {
    /// The kind asked for (None: the default choice).
    pub(crate) fn kind(&self) -> Option<HierarchyKind> {
        self.hierarchy.map(|h| match h {
            HierarchyArg::Simplify => HierarchyKind::Simplify,
            HierarchyArg::Median => HierarchyKind::Median,
        })
    }

    /// The name of the choice, for --stats.
    pub(crate) fn name(&self) -> &'static str {
        self.kind().map_or(
            "default (simplify for shared prototypes, else median)",
            HierarchyKind::name,
        )
    }

    /// The prepare options for it.
    pub(crate) fn prepare(&self) -> PrepareOptions {
        PrepareOptions {
            hierarchy: self.kind(),
            ..PrepareOptions::default()
        }
    }
}
