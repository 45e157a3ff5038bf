//! Groups of batch points gathered into fixed-size local arrays, the form the vectoriser can
//! prove apart from a batch's output slices (the structure-of-arrays contact kernels of
//! [`crate::dim`] and [`crate::spatial::geometry`]).

/// `L` entries of `a` from `start`, of which the first `len` (`1 ≤ len ≤ L`) are valid; the
/// last valid entry fills the rest of a group at the end of a batch (its results are not
/// stored).
#[inline(always)]
pub(crate) fn gather<const L: usize>(a: &[f64], start: usize, len: usize) -> [f64; L] {
    std::array::from_fn(|l| a[start + l.min(len - 1)])
}

#[cfg(test)]
mod tests {
    // Reference: the entries read one by one.
    #[test]
    fn a_short_group_repeats_its_last_valid_entry() {
        let a = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        assert_eq!(super::gather::<4>(&a, 0, 4), [1.0, 2.0, 3.0, 4.0]);
        assert_eq!(super::gather::<4>(&a, 4, 2), [5.0, 6.0, 6.0, 6.0]);
    }
}
