//! Work shared between the cores and given back in its order: the renderers print each page
//! on its own, and a build's bytes must not depend on which thread finished first.

use std::sync::atomic::{AtomicUsize, Ordering};

/// At most this many threads: the machine's cores, and a build's memory grows with each.
const MAX_THREADS: usize = 2;

/// `f` of each item, on up to two threads, in the items' order.
pub fn map_in_order<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(MAX_THREADS)
        .min(items.len());
    if threads <= 1 {
        return items.iter().map(f).collect();
    }
    let next = AtomicUsize::new(0);
    let mut done: Vec<Option<R>> = std::iter::repeat_with(|| None).take(items.len()).collect();
    let (tell, told) = std::sync::mpsc::channel();
    std::thread::scope(|scope| {
        for _ in 0..threads {
            let (tell, next, f) = (tell.clone(), &next, &f);
            scope.spawn(move || {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(item) = items.get(i) else { break };
                    if tell.send((i, f(item))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tell);
        for (i, r) in told {
            done[i] = Some(r);
        }
    });
    done.into_iter()
        .map(|r| r.expect("every item is done"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::map_in_order;

    #[test]
    fn results_come_in_the_items_order_whoever_finishes_first() {
        // The first items take longest: on two threads they finish after those behind them.
        let items: Vec<u64> = (0..40).collect();
        let out = map_in_order(&items, |&k| {
            std::thread::sleep(std::time::Duration::from_millis(40u64.saturating_sub(k)));
            (k * k, std::thread::current().id())
        });
        let squares: Vec<u64> = out.iter().map(|r| r.0).collect();
        assert_eq!(squares, items.iter().map(|k| k * k).collect::<Vec<_>>());
        let threads: std::collections::BTreeSet<_> =
            out.iter().map(|r| format!("{:?}", r.1)).collect();
        if std::thread::available_parallelism().map_or(1, |n| n.get()) > 1 {
            assert_eq!(threads.len(), 2, "the work was not shared");
        }
        assert!(map_in_order(&[] as &[u8], |&b| b).is_empty());
    }
}
