//! What can be wrong with a PLY header before its data is read.

use thiserror::Error;

use crate::mesh::LimitError;

/// A declaration of a PLY header that this reader refuses, found before the data is parsed.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum PlyHeaderError {
    /// Two `element` lines of the same name: the second would silently replace the first.
    #[error("element \"{element}\" is declared twice")]
    DuplicateElement {
        /// The element's name.
        element: String,
    },
    /// Two `property` lines of the same name in one element: the parser would keep one and
    /// misread every value after it.
    #[error("element \"{element}\" declares property \"{property}\" twice")]
    DuplicateProperty {
        /// The element's name.
        element: String,
        /// The property's name.
        property: String,
    },
    /// An element with entries but no property: its entries take no byte of a binary file, so
    /// a header alone could ask for any number of them.
    #[error("element \"{element}\" has {count} entries but no property")]
    NoProperties {
        /// The element's name.
        element: String,
        /// The count declared.
        count: u64,
    },
    /// An element count over a limit.
    #[error("element \"{element}\": {limit}")]
    Limit {
        /// The element's name.
        element: String,
        /// The limit and the count declared.
        limit: LimitError,
    },
}
