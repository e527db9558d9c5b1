//! The writers: a solved view or its picture as SVG ([`svg`]), PNG ([`png`]) and the canonical
//! visible-polygon JSON ([`json`]).

pub(crate) mod json;
pub(crate) mod png;
pub(crate) mod svg;
