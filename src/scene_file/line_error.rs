//! A problem at a line of a text file read line by line (OBJ, MTL).

/// A problem at a line of an OBJ or MTL file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError {
    /// The line, counted from 1.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}
