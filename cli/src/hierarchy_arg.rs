//! The `--hierarchy` flag of render and query: which object tree flat meshes get.

use clap::{Args, ValueEnum};
use kepler_hsr::prepare::{HierarchyKind, PrepareOptions};

/// `--hierarchy` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum HierarchyArg {
    /// Paper 002: components of simplified models, merged bottom-up (prepared once).
    #[default]
    Simplify,
    /// The median split (made per view for rendering; in 3D for --interfere).
    Median,
}

/// The flag itself.
#[derive(Args, Debug, Clone, Copy, Default)]
pub(crate) struct HierarchyArgs {
    /// Object tree of flat meshes: simplify (paper 002) or median; answers are identical.
    #[arg(long, value_enum, value_name = "KIND", default_value = "simplify")]
    pub(crate) hierarchy: HierarchyArg,
}

impl HierarchyArgs {
    /// The kind asked for.
    pub(crate) fn kind(&self) -> HierarchyKind {
        match self.hierarchy {
            HierarchyArg::Simplify => HierarchyKind::Simplify,
            HierarchyArg::Median => HierarchyKind::Median,
        }
    }

    /// The prepare options for it.
    pub(crate) fn prepare(&self) -> PrepareOptions {
        PrepareOptions {
            hierarchy: self.kind(),
        }
    }
}
