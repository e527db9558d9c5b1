//! The writers: a solved view or its picture as SVG ([`svg`]), PNG ([`png`]) and the canonical
//! visible-polygon JSON ([`json`]).

pub mod json;
pub mod png;
pub mod svg;
