//! The elements of an array variable, in row-major order, shared between copies of the state until
//! one of them writes.

use super::value::Value;
use super::var_type::VarType;
use std::sync::Arc;

/// Arrays have at most three dimensions (reference §8.1; two in older versions).
pub const MAX_DIMENSIONS: usize = 3;

/// The indexes of the `position`-th element of an array of `dimensions`, the last index counting
/// fastest: the order in which initial values and whole arrays are written.
pub fn element_indexes(mut position: usize, dimensions: &[usize]) -> Vec<usize> {
    let mut indexes = vec![0; dimensions.len()];
    for (slot, size) in indexes.iter_mut().zip(dimensions).rev() {
        *slot = position % size;
        position /= size;
    }
    indexes
}

/// Arrays with more elements keep their shape (so that indexes are still checked) but not their
/// values: a copy of the state is taken every 512 blocks, and an array written in every interval is
/// copied each time.
pub const MAX_FOLLOWED_ELEMENTS: usize = 1024;

/// Why indexes do not select an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IndexError {
    /// The variable has `expected` dimensions (0 for a scalar), and another number of indexes was given.
    Count { expected: usize },
    /// `index` is not below `size`, the size of dimension `dimension` (0-based) (alarm 17020).
    OutOfRange {
        dimension: usize,
        index: usize,
        size: usize,
    },
}

#[derive(Debug, Clone)]
pub(super) struct Array {
    /// The sizes of the first `rank` dimensions; the rest are 1.
    dimensions: [usize; MAX_DIMENSIONS],
    rank: usize,
    /// The number of elements, `None` when it overflows a `usize`.
    len: Option<usize>,
    elements: Elements,
}

/// The elements in row-major order.
#[derive(Debug, Clone, PartialEq)]
enum Elements {
    Numbers(Vec<Option<f64>>),
    Texts(Vec<Option<Arc<str>>>),
    /// Every element unknown: a large array, a FRAME array, or one whose values were forgotten.
    Unknown,
}

impl PartialEq for Array {
    fn eq(&self, other: &Array) -> bool {
        if self.dimensions != other.dimensions || self.rank != other.rank {
            return false;
        }
        if self.elements == other.elements {
            return true;
        }
        // The same values may be held in two forms (all unknown, or a vector of unknowns).
        (0..self.followed_len()).all(|offset| self.get(offset) == other.get(offset))
    }
}

impl Array {
    pub(super) fn new(var_type: VarType, dimensions: &[usize]) -> Array {
        let mut sizes = [1; MAX_DIMENSIONS];
        sizes[..dimensions.len()].copy_from_slice(dimensions);
        let len = dimensions
            .iter()
            .try_fold(1usize, |product, size| product.checked_mul(*size));
        let elements = match (len, var_type.zero()) {
            (Some(len), Some(zero)) if len <= MAX_FOLLOWED_ELEMENTS => match zero {
                Value::Number(number) => Elements::Numbers(vec![Some(number); len]),
                Value::Text(text) => Elements::Texts(vec![Some(text); len]),
            },
            _ => Elements::Unknown,
        };
        Array {
            dimensions: sizes,
            rank: dimensions.len(),
            len,
            elements,
        }
    }

    /// The row-major position of the element at `indexes`.
    pub(super) fn offset(&self, indexes: &[usize]) -> Result<usize, IndexError> {
        if indexes.len() != self.rank {
            return Err(IndexError::Count {
                expected: self.rank,
            });
        }
        let mut offset = 0usize;
        for (dimension, (&index, &size)) in indexes.iter().zip(&self.dimensions).enumerate() {
            if index >= size {
                return Err(IndexError::OutOfRange {
                    dimension,
                    index,
                    size,
                });
            }
            // Saturating: when the product of the sizes overflows, every element is unknown and the
            // offset selects nothing.
            offset = offset.saturating_mul(size).saturating_add(index);
        }
        Ok(offset)
    }

    pub(super) fn get(&self, offset: usize) -> Option<Value> {
        match &self.elements {
            Elements::Numbers(numbers) => numbers.get(offset).copied().flatten().map(Value::Number),
            Elements::Texts(texts) => texts.get(offset).cloned().flatten().map(Value::Text),
            Elements::Unknown => None,
        }
    }

    /// Stores a value already converted to the type.
    pub(super) fn set(&mut self, offset: usize, value: Option<Value>, var_type: VarType) {
        if matches!(self.elements, Elements::Unknown) {
            if value.is_none() {
                return;
            }
            // Values become followed again once one is known, if the array is small enough.
            match self.len {
                Some(len) if len <= MAX_FOLLOWED_ELEMENTS && var_type != VarType::Frame => {
                    self.elements = if var_type.holds_text() {
                        Elements::Texts(vec![None; len])
                    } else {
                        Elements::Numbers(vec![None; len])
                    };
                }
                _ => return,
            }
        }
        match (&mut self.elements, value) {
            (Elements::Numbers(numbers), Some(Value::Number(number))) => {
                numbers[offset] = Some(number)
            }
            (Elements::Texts(texts), Some(Value::Text(text))) => texts[offset] = Some(text),
            (Elements::Numbers(numbers), _) => numbers[offset] = None,
            (Elements::Texts(texts), _) => texts[offset] = None,
            (Elements::Unknown, _) => {}
        }
    }

    /// An array of the same shape with every element unknown.
    pub(super) fn unknown_like(&self) -> Array {
        Array {
            dimensions: self.dimensions,
            rank: self.rank,
            len: self.len,
            elements: Elements::Unknown,
        }
    }

    pub(super) fn is_unknown(&self) -> bool {
        matches!(self.elements, Elements::Unknown)
    }

    pub(super) fn dimensions(&self) -> &[usize] {
        &self.dimensions[..self.rank]
    }

    pub(super) fn same_shape(&self, other: &Array) -> bool {
        self.dimensions() == other.dimensions()
    }

    /// How many elements may hold a known value.
    pub(super) fn followed_len(&self) -> usize {
        self.len.unwrap_or(0).min(MAX_FOLLOWED_ELEMENTS)
    }
}
