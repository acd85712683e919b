//! The caller's arrays (`short *pSyncAxArray`, `double *pPosArray` …): read and written only
//! here, always with a length the caller's own count argument gave and that was checked
//! against the function's limit first.

/// `count` as a length when it lies in `[0, max]`; 0 otherwise (the server then refuses the
/// count, naming the range, and no caller memory is read on its word).
pub(crate) fn bounded(count: i64, max: usize) -> usize {
    usize::try_from(count)
        .ok()
        .filter(|n| *n <= max)
        .unwrap_or(0)
}

/// The first `n` elements of the caller's array at `p` (none if `p` is null).
pub(crate) fn load_slice<T>(p: *const T, n: usize) -> Vec<T> {
    if p.is_null() {
        return Vec::new();
    }
    (0..n)
        // SAFETY: non-null, checked above; the caller's array holds at least `n` elements,
        // the count it passed (bounded by the function's limit), by the C contract.
        // Unaligned reads tolerate packed callers.
        .map(|i| unsafe { p.add(i).read_unaligned() })
        .collect()
}

/// Write `items` into the caller's array at `p`, at most `capacity` of them.
pub(crate) fn store_slice<T>(p: *mut T, capacity: usize, items: impl IntoIterator<Item = T>) {
    if p.is_null() {
        return;
    }
    for (i, v) in items.into_iter().take(capacity).enumerate() {
        // SAFETY: non-null, checked above; i < capacity, the number of elements the caller
        // asked for (or the manual's fixed size), which its array holds by the C contract.
        unsafe { p.add(i).write_unaligned(v) }
    }
}
