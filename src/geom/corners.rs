//! A polygon's corners as indices into a table of points: a mesh's points held once a
//! vertex (shared by about six triangles), not once a corner.

use std::ops::Index;

use super::{newell_indexed, P3, V3};

/// The corners of one polygon: corner `k` is `table[at[k]]`. Read like a slice of points
/// (`c[k]`, [`Corners::len`], [`Corners::iter`]); no point is copied.
#[derive(Debug, Clone, Copy)]
pub struct Corners<'a> {
    at: &'a [u32],
    table: &'a [P3],
}

impl<'a> Corners<'a> {
    /// The corners `table[at[0]], table[at[1]], …` (every index must be in `table`).
    #[inline]
    pub fn new(at: &'a [u32], table: &'a [P3]) -> Self {
        Corners { at, table }
    }

    /// Number of corners.
    #[inline]
    pub fn len(&self) -> usize {
        self.at.len()
    }

    /// True when there is no corner.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.at.is_empty()
    }

    /// The corners' points, in order.
    #[inline]
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &'a P3> + Clone + 'a {
        let table = self.table;
        self.at.iter().map(move |&i| &table[i as usize])
    }

    /// The corners' points, copied out.
    pub fn to_vec(&self) -> Vec<P3> {
        self.iter().copied().collect()
    }

    /// The corners' indices into the table.
    #[inline]
    pub fn indices(&self) -> &'a [u32] {
        self.at
    }

    /// Newell's normal of the polygon ([`crate::geom::newell`] of [`Corners::to_vec`]).
    pub fn newell(&self) -> V3 {
        newell_indexed(self.table, self.at)
    }
}

impl Index<usize> for Corners<'_> {
    type Output = P3;

    #[inline]
    fn index(&self, k: usize) -> &P3 {
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
    }
}
