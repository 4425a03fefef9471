//! Bounded lists in rig, pose and edits files: each list is refused while it is read, as soon
//! as it holds one element more than its limit ([`crate::limits`]), so a file of ten million
//! radii never builds a ten-million-element `Vec`.
//!
//! The sweep and key being read are kept per thread while a document is deserialized, so that
//! the error names them (zero-based, as `sweeps[2].keys[5].radii`); serde_json then adds the
//! line and column.

use std::cell::Cell;
use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, Deserialize, Deserializer, IgnoredAny, SeqAccess, Visitor};

use crate::limits::{MAX_EDITS, MAX_KEYS_PER_SWEEP, MAX_RADII_PER_KEY, MAX_RADII_PER_RIG, MAX_SWEEPS, MAX_VERTICES};

thread_local! {
    /// The index of the sweep being read.
    static SWEEP: Cell<Option<usize>> = const { Cell::new(None) };
    /// The index of the key being read.
    static KEY: Cell<Option<usize>> = const { Cell::new(None) };
    /// The radii read so far in the current document.
    static RADII: Cell<usize> = const { Cell::new(0) };
}

/// Sets a position cell for the element being read and restores the previous value on drop,
/// also when reading fails.
struct At {
    cell: &'static std::thread::LocalKey<Cell<Option<usize>>>,
    previous: Option<usize>,
}

impl At {
    fn new(cell: &'static std::thread::LocalKey<Cell<Option<usize>>>, index: Option<usize>) -> At {
        At { cell, previous: cell.with(|c| c.replace(index)) }
    }
}

impl Drop for At {
    fn drop(&mut self) {
        self.cell.with(|c| c.set(self.previous));
    }
}

/// Where in the document the list being read lies, as `sweeps[2].keys[5]`.
fn here() -> String {
    match (SWEEP.with(Cell::get), KEY.with(Cell::get)) {
        (Some(sweep), Some(key)) => format!("sweeps[{sweep}].keys[{key}]"),
        (Some(sweep), None) => format!("sweeps[{sweep}]"),
        _ => String::new(),
    }
}

/// A list of at most `max` elements.
struct Bounded<T> {
    max: usize,
    /// The list's field name, for the message.
    field: &'static str,
    /// What the limit bounds, for the message ("the most a key may have").
    limit: &'static str,
    /// The position cell that takes each element's index, if any.
    index: Option<&'static std::thread::LocalKey<Cell<Option<usize>>>>,
    element: PhantomData<T>,
}

impl<T> Bounded<T> {
    fn too_many<E: de::Error>(&self) -> E {
        let place = here();
        let place = if place.is_empty() { String::new() } else { format!("{place}.") };
        E::custom(format!("{place}{}: more than {} values ({})", self.field, self.max, self.limit))
    }
}

impl<'de, T: Deserialize<'de>> Visitor<'de> for Bounded<T> {
    type Value = Vec<T>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a list of at most {} values", self.max)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
        let mut values = Vec::new();
        loop {
            if values.len() == self.max {
                return match seq.next_element::<IgnoredAny>()? {
                    Some(_) => Err(self.too_many()),
                    None => Ok(values),
                };
            }
            let _at = self.index.map(|cell| At::new(cell, Some(values.len())));
            match seq.next_element()? {
                Some(value) => values.push(value),
                None => return Ok(values),
            }
        }
    }
}

fn bounded<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
    list: Bounded<T>,
) -> Result<Vec<T>, D::Error> {
    deserializer.deserialize_seq(list)
}

/// The `sweeps` of a rig or pose file: at most [`MAX_SWEEPS`]. Starts the document's count of
/// radii.
pub(crate) fn sweeps<'de, D: Deserializer<'de>, T: Deserialize<'de>>(deserializer: D) -> Result<Vec<T>, D::Error> {
    RADII.with(|c| c.set(0));
    let _key = At::new(&KEY, None);
    let list = Bounded {
        max: MAX_SWEEPS,
        field: "sweeps",
        limit: "the most a rig may have",
        index: Some(&SWEEP),
        element: PhantomData,
    };
    bounded(deserializer, list)
}

/// The `keys` of a sweep: at most [`MAX_KEYS_PER_SWEEP`].
pub(crate) fn keys<'de, D: Deserializer<'de>, T: Deserialize<'de>>(deserializer: D) -> Result<Vec<T>, D::Error> {
    let list = Bounded {
        max: MAX_KEYS_PER_SWEEP,
        field: "keys",
        limit: "the most a sweep may have",
        index: Some(&KEY),
        element: PhantomData,
    };
    bounded(deserializer, list)
}

/// The `knots` of a sweep, or `null`: at most [`MAX_KEYS_PER_SWEEP`] (one per key).
pub(crate) fn knots<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<Vec<f64>>, D::Error> {
    struct OptionalKnots;
    impl<'de> Visitor<'de> for OptionalKnots {
        type Value = Option<Vec<f64>>;

        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "a list of knots or null")
        }

        fn visit_none<E: de::Error>(self) -> Result<Self::Value, E> {
            Ok(None)
        }

        fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
            Ok(None)
        }

        fn visit_some<D: Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
            let list = Bounded {
                max: MAX_KEYS_PER_SWEEP,
                field: "knots",
                limit: "one per key, and a sweep has at most that many keys",
                index: None,
                element: PhantomData,
            };
            bounded(deserializer, list).map(Some)
        }
    }
    deserializer.deserialize_option(OptionalKnots)
}

/// The `radii` of a key: at most [`MAX_RADII_PER_KEY`], and at most [`MAX_RADII_PER_RIG`] in
/// the whole document.
pub(crate) fn radii<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<f64>, D::Error> {
    let list = Bounded {
        max: MAX_RADII_PER_KEY,
        field: "radii",
        limit: "the most a key may have",
        index: None,
        element: PhantomData,
    };
    let radii: Vec<f64> = bounded(deserializer, list)?;
    let total = RADII.with(|c| {
        let total = c.get().saturating_add(radii.len());
        c.set(total);
        total
    });
    if total > MAX_RADII_PER_RIG {
        return Err(de::Error::custom(format!(
            "{}.radii: the rig holds more than {MAX_RADII_PER_RIG} radii in all (the most a rig may have)",
            here()
        )));
    }
    Ok(radii)
}

/// The vertex `indices` a sweep owns: at most [`MAX_VERTICES`].
pub(crate) fn indices<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<u32>, D::Error> {
    let list = Bounded {
        max: MAX_VERTICES,
        field: "vertices.indices",
        limit: "the most vertices of a mesh",
        index: None,
        element: PhantomData,
    };
    bounded(deserializer, list)
}

/// An edits file: at most [`MAX_EDITS`] edits.
pub(crate) fn edits<'de, D: Deserializer<'de>, T: Deserialize<'de>>(deserializer: D) -> Result<Vec<T>, D::Error> {
    let list = Bounded {
        max: MAX_EDITS,
        field: "edits",
        limit: "the most an edits file may have",
        index: None,
        element: PhantomData,
    };
    bounded(deserializer, list)
}
