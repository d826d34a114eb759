//! A slice mapped on all cores by rayon's pool: what the mesher and the ground truth share.

use rayon::prelude::*;

/// `f` over `items` on all cores (in order); on one core, or where threads cannot be made
/// (WebAssembly), in this thread.
pub fn par_map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    if items.len() < 64 || threads() == 1 {
        return items.iter().map(f).collect();
    }
    let f = &f;
    items.par_iter().map(f).collect()
}

/// Everything `f` gives for each of `items`, in order, on all cores.
pub fn par_flat_map<T: Sync, I: IntoIterator>(
    items: &[T],
    f: impl Fn(&T) -> I + Sync,
) -> Vec<I::Item>
where
    I::Item: Send,
{
    if items.len() < 64 || threads() == 1 {
        return items.iter().flat_map(f).collect();
    }
    let f = &f;
    items.par_iter().flat_map_iter(f).collect()
}

/// Sorts `items` by `key` on all cores (not stable).
pub fn par_sort_unstable_by_key<T: Send, K: Ord>(items: &mut [T], key: impl Fn(&T) -> K + Sync) {
    if threads() == 1 {
        return items.sort_unstable_by_key(key);
    }
    items.par_sort_unstable_by_key(key)
}

/// `f` over the chunks of `items` of `size` (the last may be shorter) on all cores, their
/// results in order; on one core, in this thread.
pub fn par_chunks_mut<T: Send, R: Send>(
    items: &mut [T],
    size: usize,
    f: impl Fn(&mut [T]) -> R + Sync,
) -> Vec<R> {
    if items.len() <= size || threads() == 1 {
        return items.chunks_mut(size.max(1)).map(f).collect();
    }
    let f = &f;
    items.par_chunks_mut(size).map(f).collect()
}

/// The cores to use, asked once (the question reads the cgroup's files each time: tens of
/// microseconds, more than a small map's work).
fn threads() -> usize {
    static THREADS: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *THREADS.get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The maps keep their items' order, below and above the sizes that run in parallel.
    #[test]
    fn maps_keep_order() {
        for n in [0, 5, 63, 64, 1000] {
            let items: Vec<u32> = (0..n).collect();
            assert_eq!(
                par_map(&items, |&i| 2 * i),
                items.iter().map(|&i| 2 * i).collect::<Vec<_>>()
            );
            let flat = par_flat_map(&items, |&i| (0..i % 3).map(move |k| (i, k)));
            let want: Vec<_> = items
                .iter()
                .flat_map(|&i| (0..i % 3).map(move |k| (i, k)))
                .collect();
            assert_eq!(flat, want);
            let mut chunks = items.clone();
            let sums = par_chunks_mut(&mut chunks, 7, |c| c.iter().sum::<u32>());
            let want: Vec<u32> = items.chunks(7).map(|c| c.iter().sum()).collect();
            assert_eq!(sums, want);
            let mut sorted: Vec<u32> = items.iter().rev().copied().collect();
            par_sort_unstable_by_key(&mut sorted, |&i| i);
            assert_eq!(sorted, items);
        }
    }
}
