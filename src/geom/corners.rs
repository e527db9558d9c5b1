//! A polygon's corners as indices into a table of points: a mesh's points held once a
//! vertex (shared by about six triangles), not once a corner.

use std::ops::Index;

use super::{newell_indexed, P3, V3};

/// The corners of one polygon: corner `k` is `table[at[k]]`. Read like a slice of points
/// (`c[k]`, [`Corners::len`], [`Corners::iter`]); no point is copied. The points are world
/// points ([`P3`]) unless said otherwise (the screen's are `[f64; 3]`).
pub(crate) struct Corners<'a, T = P3> {
    at: &'a [u32],
    table: &'a [T],
}

/// The corners' points, not the whole table.
impl<T: std::fmt::Debug> std::fmt::Debug for Corners<'_, T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let table = self.table;
        f.debug_list()
            .entries(self.at.iter().map(|&i| &table[i as usize]))
            .finish()
    }
}

impl<T> Clone for Corners<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Corners<'_, T> {}

impl<'a, T: Copy> Corners<'a, T> {
    /// The corners `table[at[0]], table[at[1]], …` (every index must be in `table`).
    #[inline]
    pub(crate) fn new(at: &'a [u32], table: &'a [T]) -> Self {
        Corners { at, table }
    }

    /// Number of corners.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.at.len()
    }

    #[cfg(test)]
    /// True when there is no corner.
    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        self.at.is_empty()
    }

    /// The corners' points, in order.
    #[inline]
    pub(crate) fn iter(&self) -> impl ExactSizeIterator<Item = &'a T> + Clone + 'a {
        let table = self.table;
        self.at.iter().map(move |&i| &table[i as usize])
    }

    #[cfg(test)]
    /// The corners' points, copied out.
    pub(crate) fn to_vec(self) -> Vec<T> {
        self.iter().copied().collect()
    }

    #[cfg(test)]
    /// The corners' indices into the table.
    #[inline]
    pub(crate) fn indices(&self) -> &'a [u32] {
        self.at
    }
}

impl Corners<'_, P3> {
    /// Newell's normal of the polygon ([`crate::geom::newell`] of [`Corners::to_vec`]).
    pub(crate) fn newell(&self) -> V3 {
        newell_indexed(self.table, self.at)
    }
}

impl<T> Index<usize> for Corners<'_, T> {
    type Output = T;

    #[inline]
    fn index(&self, k: usize) -> &T {
        &self.table[self.at[k] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::newell;

    #[test]
    fn reads_the_table_through_the_indices() {
        let table = [
            P3::new(0.0, 0.0, 0.0),
            P3::new(1.0, 0.0, 0.0),
            P3::new(1.0, 1.0, 0.0),
            P3::new(0.0, 1.0, 0.0),
        ];
        let c = Corners::new(&[3, 0, 1], &table);
        assert_eq!((c.len(), c.is_empty()), (3, false));
        assert_eq!(c[0], table[3]);
        assert_eq!(c.to_vec(), vec![table[3], table[0], table[1]]);
        assert_eq!(c.iter().len(), 3);
        assert_eq!(c.indices(), &[3, 0, 1]);
        assert_eq!(c.newell(), newell(&c.to_vec()));
        assert_eq!(c.newell(), V3::new(0.0, 0.0, 1.0));
        assert!(Corners::new(&[], &table).is_empty());
        // Debug shows the corners' points only.
        let one = Corners::new(&[2], &table);
        assert_eq!(format!("{one:?}"), format!("[{:?}]", table[2]));
    }
}
