//! Sorted lists: merging them, and moving the items that match a test from one sorted list into
//! another. The step keeps its awake and parked (sleeping) lists sorted, so that results do not
//! depend on when an item moved between them.

/// Merges the sorted `added` (no key also in `target`) into the sorted vector `target`, by `key`,
/// in place from the back: the items of `target` before the first added key do not move, and a
/// vector with room allocates nothing.
pub(crate) fn merge_into<T: Copy, K: Ord>(target: &mut Vec<T>, added: &[T], key: impl Fn(&T) -> K) {
    let (mut kept, mut new) = (target.len(), added.len());
    target.extend_from_slice(added);
    while new > 0 {
        let place = kept + new - 1;
        if kept > 0 && key(&target[kept - 1]) > key(&added[new - 1]) {
            target[place] = target[kept - 1];
            kept -= 1;
        } else {
            target[place] = added[new - 1];
            new -= 1;
        }
    }
}

/// The items of two sorted sequences in one sorted sequence.
pub(crate) fn merged<T: Ord>(
    a: impl Iterator<Item = T>,
    b: impl Iterator<Item = T>,
) -> impl Iterator<Item = T> {
    let (mut a, mut b) = (a.peekable(), b.peekable());
    std::iter::from_fn(move || match (a.peek(), b.peek()) {
        (Some(x), Some(y)) if y < x => b.next(),
        (Some(_), _) => a.next(),
        (None, _) => b.next(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merging_keeps_the_order() {
        let mut target = vec![1, 4, 9];
        merge_into(&mut target, &[0, 5, 10], |&x| x);
        assert_eq!(target, [0, 1, 4, 5, 9, 10]);
        let all: Vec<_> = merged([2, 3, 8].into_iter(), [1, 9].into_iter()).collect();
        assert_eq!(all, [1, 2, 3, 8, 9]);
    }
}
