//! Allocations sized by user input, made fallible: a request the allocator cannot meet (or whose
//! size in bytes overflows `usize`) is an [`AllocationError`] carrying the bytes asked for and what
//! they were for, which each subsystem's error wraps (`LinalgError::OutOfMemory`,
//! `DynamicsError::OutOfMemory`) and Python raises as `MemoryError`. Rust's `vec![..; n]` and
//! `Vec::with_capacity` abort the process instead (`memory allocation of N bytes failed`), which
//! takes the Python interpreter down with them.

use alloc::vec::Vec;

/// `bytes` could not be allocated for `what`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("cannot allocate {bytes} bytes for {what}")]
pub struct AllocationError {
    /// The bytes asked for (`usize::MAX` when the size itself overflows).
    pub bytes: usize,
    /// What they were for.
    pub what: &'static str,
}

/// The bytes of `len` values of `T`, `usize::MAX` on overflow.
pub fn bytes_of<T>(len: usize) -> usize {
    len.saturating_mul(core::mem::size_of::<T>())
}

/// An empty vector with room for exactly `len` values of `T`.
///
/// # Errors
/// [`AllocationError`] with `len * size_of::<T>()` bytes when the allocator refuses, or when that
/// size exceeds `isize::MAX` (which no allocation may).
pub fn try_vec<T>(len: usize, what: &'static str) -> Result<Vec<T>, AllocationError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| AllocationError { bytes: bytes_of::<T>(len), what })?;
    Ok(v)
}

/// `len` copies of `value`, allocated as [`try_vec`].
///
/// # Errors
/// As [`try_vec`].
pub fn try_filled<T: Clone>(len: usize, value: T, what: &'static str) -> Result<Vec<T>, AllocationError> {
    let mut v = try_vec(len, what)?;
    v.resize(len, value);
    Ok(v)
}

/// Room for `additional` more values in `v` (a growing trajectory), exactly.
///
/// # Errors
/// As [`try_vec`], with the bytes of the whole grown vector.
pub fn try_grow<T>(v: &mut Vec<T>, additional: usize, what: &'static str) -> Result<(), AllocationError> {
    v.try_reserve_exact(additional)
        .map_err(|_| AllocationError { bytes: bytes_of::<T>(v.len().saturating_add(additional)), what })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_size_beyond_isize_max_is_an_error_with_the_bytes() {
        // 2^60 values of 8 bytes: 2^63 bytes, one more than isize::MAX.
        let err = try_vec::<f64>(1 << 60, "frames").unwrap_err();
        assert_eq!(err, AllocationError { bytes: 1 << 63, what: "frames" });
        let err = try_vec::<f64>(usize::MAX / 2, "frames").unwrap_err();
        assert_eq!(err.bytes, usize::MAX, "overflowing size");
        assert_eq!(err.to_string(), format!("cannot allocate {} bytes for frames", usize::MAX));
    }

    #[test]
    fn a_size_that_fits_is_allocated() {
        let v = try_filled(5, 1.5f64, "values").unwrap();
        assert_eq!(v, [1.5; 5]);
    }
}
