//! Which document a typesetting worker takes next. Typst holds a document's whole layout in
//! memory until its PDF is made, so what is typeset at once is kept within a budget: the
//! largest waiting document that fits beside those under way is taken first, and one larger
//! than the budget is typeset alone. The order changes no output: each PDF depends only on
//! its own markup, and the build reports in the sources' order.

use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};

pub struct Queue {
    /// Each source's size (its markup and pictures, in bytes), by its index.
    sizes: Vec<usize>,
    budget: usize,
    /// Told, after each document, whether no other is under way; runs before another starts.
    give_back: fn(bool, usize),
    state: Mutex<Queued>,
    turn: Condvar,
}

/// A worker's turn at a document: the k-th started, of source `source`. Ending it (dropping it,
/// also when typesetting panics) makes room for the next, so no worker waits for room forever.
pub struct Turn<'a> {
    pub k: usize,
    pub source: usize,
    queue: &'a Queue,
}

impl Drop for Turn<'_> {
    fn drop(&mut self) {
        self.queue.done(self.source);
    }
}

struct Queued {
    /// The sources not yet started, the largest first.
    waiting: Vec<usize>,
    /// The summed size of the documents under way, and how many they are.
    running: usize,
    busy: usize,
    started: usize,
}

impl Queue {
    /// A queue of the sources `todo`, of the given `sizes`, typeset at once within `budget`;
    /// `give_back` is told after each document whether no other is under way, and the
    /// document's size.
    pub fn new(
        sizes: Vec<usize>,
        todo: &[usize],
        budget: usize,
        give_back: fn(bool, usize),
    ) -> Queue {
        let mut waiting = todo.to_vec();
        // Stable, so that equal sizes go in the sources' order.
        waiting.sort_by_key(|&i| std::cmp::Reverse(sizes[i]));
        Queue {
            sizes,
            budget,
            give_back,
            state: Mutex::new(Queued {
                waiting,
                running: 0,
                busy: 0,
                started: 0,
            }),
            turn: Condvar::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, Queued> {
        // The state is a few counters, left consistent by every holder of the lock.
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The next document to typeset, once it fits beside those under way; `None` when none is
    /// left. Waits for room.
    pub fn next(&self) -> Option<Turn<'_>> {
        let mut q = self.lock();
        loop {
            let fits = q
                .waiting
                .iter()
                .position(|&i| q.busy == 0 || q.running + self.sizes[i] <= self.budget);
            match fits {
                Some(at) => {
                    let i = q.waiting.remove(at);
                    q.running += self.sizes[i];
                    q.busy += 1;
                    q.started += 1;
                    return Some(Turn {
                        k: q.started - 1,
                        source: i,
                        queue: self,
                    });
                }
                None if q.waiting.is_empty() => return None,
                None => q = self.turn.wait(q).unwrap_or_else(PoisonError::into_inner),
            }
        }
    }

    /// Source `i` is typeset (or failed to be).
    fn done(&self, i: usize) {
        let mut q = self.lock();
        q.running -= self.sizes[i];
        q.busy -= 1;
        (self.give_back)(q.busy == 0, self.sizes[i]);
        self.turn.notify_all();
    }

    /// No further document is started; those under way finish.
    pub fn stop(&self) {
        self.lock().waiting.clear();
        self.turn.notify_all();
    }
}

#[cfg(test)]
mod tests {
    use super::Queue;
    use std::sync::Mutex;

    /// Runs `queue` on `workers` threads, each document "typeset" for a moment; returns the
    /// sources in the order they started, and the largest summed size seen under way when
    /// more than one document was.
    fn run(queue: &Queue, workers: usize, sizes: &[usize]) -> (Vec<usize>, usize) {
        // Each start as (k, source); the summed size and count under way; the most with company.
        let log = Mutex::new((Vec::new(), (0usize, 0usize), 0usize));
        std::thread::scope(|scope| {
            for _ in 0..workers {
                scope.spawn(|| {
                    while let Some(turn) = queue.next() {
                        let i = turn.source;
                        {
                            let mut l = log.lock().unwrap();
                            l.0.push((turn.k, i));
                            l.1 = (l.1.0 + sizes[i], l.1.1 + 1);
                            if l.1.1 > 1 {
                                l.2 = l.2.max(l.1.0);
                            }
                        }
                        std::thread::sleep(std::time::Duration::from_millis(2));
                        {
                            let mut l = log.lock().unwrap();
                            l.1 = (l.1.0 - sizes[i], l.1.1 - 1);
                        }
                        drop(turn);
                    }
                });
            }
        });
        let (mut started, _, most) = log.into_inner().unwrap();
        started.sort_unstable();
        // The k-th started is numbered k.
        for (n, (k, _)) in started.iter().enumerate() {
            assert_eq!(n, *k);
        }
        (started.into_iter().map(|(_, i)| i).collect(), most)
    }

    fn nothing(_: bool, _: usize) {}

    #[test]
    fn the_largest_go_first_and_what_is_typeset_at_once_stays_within_the_budget() {
        let sizes = vec![10, 380, 40, 220, 130, 2, 240];
        let todo: Vec<usize> = (0..sizes.len()).collect();
        let queue = Queue::new(sizes.clone(), &todo, 300, nothing);
        let (order, most) = run(&queue, 2, &sizes);
        // Each document once, the one over the budget first (and alone).
        let mut all = order.clone();
        all.sort_unstable();
        assert_eq!(all, todo);
        assert_eq!(order[0], 1);
        assert!(most > 0 && most <= 300, "{most}");
        // Without a budget the two largest are typeset at once: the second is given while the
        // first is under way. (Asked of the queue itself: two threads' timing under a loaded
        // machine did not always overlap.)
        let unbounded = Queue::new(sizes.clone(), &todo, usize::MAX, nothing);
        let first = unbounded.next().expect("a document to typeset");
        let first_source = first.source;
        let second = std::thread::scope(|scope| {
            let (sent, received) = std::sync::mpsc::channel();
            let queue = &unbounded;
            scope.spawn(move || {
                let _ = sent.send(queue.next().map(|t| t.source));
            });
            // A queue that held the second back would give it only once the first is done.
            let second = received
                .recv_timeout(std::time::Duration::from_secs(10))
                .ok()
                .flatten();
            drop(first);
            second
        });
        assert_eq!((first_source, second), (1, Some(6)));
    }

    #[test]
    fn documents_typeset_together_never_sum_past_the_budget() {
        // Sizes from a small generator: many runs, two and three workers.
        let mut x: u64 = 7;
        for round in 0..20 {
            let sizes: Vec<usize> = (0..12)
                .map(|_| {
                    x = x
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    ((x >> 33) % 500) as usize
                })
                .collect();
            let todo: Vec<usize> = (0..sizes.len()).collect();
            let queue = Queue::new(sizes.clone(), &todo, 400, nothing);
            let (order, most) = run(&queue, 2 + round % 2, &sizes);
            assert_eq!(order.len(), sizes.len());
            assert!(most <= 400, "{most} of {sizes:?}");
        }
    }

    static TOLD: Mutex<Vec<bool>> = Mutex::new(Vec::new());

    #[test]
    fn give_back_is_told_when_no_other_document_is_under_way() {
        fn tell(alone: bool, _: usize) {
            TOLD.lock().unwrap().push(alone);
        }
        let queue = Queue::new(vec![5, 5], &[0, 1], 100, tell);
        let (a, b) = (queue.next().unwrap(), queue.next().unwrap());
        assert_eq!((a.k, b.k), (0, 1));
        drop(a);
        drop(b);
        assert_eq!(*TOLD.lock().unwrap(), vec![false, true]);
        assert!(queue.next().is_none());
    }

    #[test]
    fn a_stopped_queue_starts_nothing_more() {
        let queue = Queue::new(vec![1, 2, 3], &[0, 1, 2], 100, nothing);
        let first = queue.next().unwrap();
        queue.stop();
        assert!(queue.next().is_none());
        drop(first);
    }

    #[test]
    fn a_worker_that_panics_still_makes_room_for_the_others() {
        // Two documents that do not fit together: the first worker's panic must not leave the
        // second waiting for room.
        let queue = Queue::new(vec![300, 300], &[0, 1], 400, nothing);
        let typeset = std::sync::atomic::AtomicUsize::new(0);
        let panicked = std::thread::scope(|scope| {
            let first = scope.spawn(|| {
                let _turn = queue.next().unwrap();
                std::thread::sleep(std::time::Duration::from_millis(20));
                panic!("Typst panicked");
            });
            std::thread::sleep(std::time::Duration::from_millis(5));
            let second = scope.spawn(|| {
                while let Some(_turn) = queue.next() {
                    typeset.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                }
            });
            second.join().unwrap();
            first.join().is_err()
        });
        assert!(panicked);
        assert_eq!(typeset.into_inner(), 1);
    }
}
