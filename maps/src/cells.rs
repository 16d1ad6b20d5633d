//! A map's cells, owned or shared: a row-major grid that is either a `Vec` (a map read or
//! generated in memory) or a range of bytes someone else keeps, such as a memory-mapped baked
//! map file (`footprint_maps::baked`). Both read as a slice.

use std::fmt;
use std::ops::{Deref, Range};
use std::sync::Arc;

use bytemuck::Pod;

/// Bytes that stay put while they are shared: a memory map, or a `Vec<u8>` read whole.
pub trait Bytes: Send + Sync + 'static {
    /// The bytes.
    fn bytes(&self) -> &[u8];
}

impl<B: AsRef<[u8]> + Send + Sync + 'static> Bytes for B {
    fn bytes(&self) -> &[u8] {
        self.as_ref()
    }
}

/// A grid of `T` (heights `u16` or colours `Rgb`), owned or lent from shared bytes; it reads as
/// `&[T]`.
pub struct Cells<T> {
    store: Store<T>,
}

/// Where the cells live.
enum Store<T> {
    Owned(Vec<T>),
    /// `range` of `bytes`, checked at construction to be a whole, aligned run of `T`.
    Shared {
        bytes: Arc<dyn Bytes>,
        range: Range<usize>,
    },
}

impl<T: Pod> Cells<T> {
    /// The cells in `range` of `bytes`, read in place (native byte order).
    ///
    /// Errors: a range past the bytes' end, a length that is not a whole number of `T`, or a
    /// start not aligned for `T`.
    pub fn shared(bytes: Arc<dyn Bytes>, range: Range<usize>) -> Result<Self, &'static str> {
        let all = bytes.bytes();
        let slice = all
            .get(range.clone())
            .ok_or("the range ends past the bytes")?;
        bytemuck::try_cast_slice::<u8, T>(slice)
            .map_err(|_| "the range is not a whole, aligned run of cells")?;
        Ok(Self {
            store: Store::Shared { bytes, range },
        })
    }

    /// Whether the cells are lent from shared bytes rather than owned.
    pub fn is_shared(&self) -> bool {
        matches!(self.store, Store::Shared { .. })
    }
}

impl<T> From<Vec<T>> for Cells<T> {
    fn from(cells: Vec<T>) -> Self {
        Self {
            store: Store::Owned(cells),
        }
    }
}

impl<T: Pod> Deref for Cells<T> {
    type Target = [T];

    #[inline]
    fn deref(&self) -> &[T] {
        match &self.store {
            Store::Owned(cells) => cells,
            // `shared` checked this very cast, and the bytes do not move or shrink.
            Store::Shared { bytes, range } => bytes
                .bytes()
                .get(range.clone())
                .and_then(|b| bytemuck::try_cast_slice(b).ok())
                .unwrap_or_default(),
        }
    }
}

impl<'a, T: Pod> IntoIterator for &'a Cells<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<T: Clone> Clone for Cells<T> {
    /// Owned cells are copied; shared ones share the same bytes.
    fn clone(&self) -> Self {
        let store = match &self.store {
            Store::Owned(cells) => Store::Owned(cells.clone()),
            Store::Shared { bytes, range } => Store::Shared {
                bytes: Arc::clone(bytes),
                range: range.clone(),
            },
        };
        Self { store }
    }
}

impl<T: Pod + PartialEq> PartialEq for Cells<T> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: Pod> fmt::Debug for Cells<T> {
    /// The count and where they live; the cells are far too many to print.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let place = if self.is_shared() { "shared" } else { "owned" };
        write!(f, "[{} values, {place}]", self.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shared cells read the bytes in place; a misaligned or ragged range is refused.
    #[test]
    fn shared_cells_read_in_place_and_refuse_bad_ranges() {
        let words: Vec<u16> = vec![1, 2, 3, 4];
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_ne_bytes()).collect();
        // A Vec<u8>'s buffer is at least 2-aligned on every allocator this runs on; skip the
        // aligned half of the test if not.
        let bytes: Arc<dyn Bytes> = Arc::new(bytes);
        if bytes.bytes().as_ptr() as usize % 2 == 0 {
            let cells = Cells::<u16>::shared(Arc::clone(&bytes), 2..8).unwrap();
            assert_eq!(&*cells, &[2, 3, 4]);
            assert_eq!(cells.clone(), Cells::from(vec![2, 3, 4]));
            assert!(cells.is_shared());
            assert!(Cells::<u16>::shared(Arc::clone(&bytes), 1..3).is_err());
        }
        assert!(Cells::<u16>::shared(Arc::clone(&bytes), 2..7).is_err());
        assert!(Cells::<u16>::shared(bytes, 2..10).is_err());
    }
}
