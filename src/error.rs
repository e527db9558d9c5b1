//! Error and warning types of the library: every problem names where it was found.

use std::fmt;
use std::path::{Path, PathBuf};

/// A position inside a source: a text line and column, a byte offset, or nothing finer than the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pos {
    /// The whole file.
    File,
    /// 1-based line and column in a text file.
    Line {
        /// 1-based line.
        line: usize,
        /// 1-based column (characters).
        col: usize,
    },
    /// Byte offset in a binary file.
    Byte(u64),
}

/// Where a problem was found: a file and a position in it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file (as given on the command line or resolved from an include).
    pub file: PathBuf,
    /// The position inside the file.
    pub pos: Pos,
}

impl Location {
    /// The whole file.
    pub fn file(file: &Path) -> Self {
        Location {
            file: file.to_path_buf(),
            pos: Pos::File,
        }
    }
    /// A 1-based line and column of a text file.
    pub fn line(file: &Path, line: usize, col: usize) -> Self {
        Location {
            file: file.to_path_buf(),
            pos: Pos::Line { line, col },
        }
    }
    /// A byte offset of a binary file.
    pub fn byte(file: &Path, offset: u64) -> Self {
        Location {
            file: file.to_path_buf(),
            pos: Pos::Byte(offset),
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let file = self.file.display();
        match self.pos {
            Pos::File => write!(f, "{file}"),
            Pos::Line { line, col } => write!(f, "{file}:{line}:{col}"),
            Pos::Byte(b) => write!(f, "{file}: byte {b}"),
        }
    }
}

/// Everything that can go wrong in the library.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{0}: {1}")]
    Io(Location, std::io::Error),
    /// Malformed input: bad syntax, truncated data, unknown keys.
    #[error("{0}: {1}")]
    Parse(Location, String),
    /// Well-formed input that is invalid: NaN coordinates, indices out of range, include cycles.
    #[error("{0}: {1}")]
    Invalid(Location, String),
    /// A request that makes no sense for this scene (an unknown object path, a degenerate camera).
    #[error("{0}")]
    Usage(String),
    /// An error in a file that another file asked for: the asking node (an include or a
    /// `mesh` node), then the error, so that a chain reads
    /// `scene.kdl:12:5 -> part.kdl:3:1 -> mesh.obj:88:1: ...`.
    #[error("{0} -> {1}")]
    Via(Location, Box<Error>),
    /// An output the caller handed over as a writer could not be written (the caller knows
    /// its name).
    #[error("{0}")]
    Write(std::io::Error),
}

impl Error {
    /// A parse error at a location.
    pub fn parse(loc: Location, msg: impl Into<String>) -> Self {
        Error::Parse(loc, msg.into())
    }
    /// An invalid-input error at a location.
    pub fn invalid(loc: Location, msg: impl Into<String>) -> Self {
        Error::Invalid(loc, msg.into())
    }

    /// This error as found through the node at `at` (an include or `mesh` node): unchanged
    /// when it is already reported there.
    pub fn via(self, at: &Location) -> Self {
        match &self {
            Error::Io(l, _) | Error::Parse(l, _) | Error::Invalid(l, _) if l == at => self,
            _ => Error::Via(at.clone(), Box::new(self)),
        }
    }

    /// Where the error is, innermost: the file and position the user fixes (None for a
    /// usage error).
    pub fn location(&self) -> Option<&Location> {
        match self {
            Error::Io(l, _) | Error::Parse(l, _) | Error::Invalid(l, _) => Some(l),
            Error::Via(_, inner) => inner.location(),
            Error::Usage(_) | Error::Write(_) => None,
        }
    }
}

/// Result with the library's error.
pub(crate) type Result<T> = std::result::Result<T, Error>;

/// A recoverable defect that was repaired, reported to the user.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// Where the defect is.
    pub location: Location,
    /// What was wrong and what was done.
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "warning: {}: {}", self.location, self.message)
    }
}

/// Collected warnings of one load.
pub(crate) type Warnings = Vec<Warning>;
