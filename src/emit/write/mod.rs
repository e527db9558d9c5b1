//! The writers: a solved view or its picture as SVG ([`svg`]), PNG ([`png`]) and the canonical
//! visible-polygon JSON ([`json`], rounding dust left out by [`dust`]).

pub(crate) mod dust;
pub(crate) mod json;
pub(crate) mod png;
pub(crate) mod svg;
