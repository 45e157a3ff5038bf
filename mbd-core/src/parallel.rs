//! Matrix–vector products split row-wise between the calling thread and one persistent worker
//! thread ([`ProductWorker`], [`SplitProduct`]).
//!
//! The hot products of small dense models stepped in real time (the explicit inverse of the
//! generalized-α iteration matrix, the rolling tire's stacked force matrix, issue #16) stream a
//! few MB per step from the shared L3 cache: the product `y = A x` with `Aᵀ` stored (column `i`
//! of the stored matrix is row `i` of `A`, contiguous) is split into the rows `0..k` (computed
//! by the caller) and `k..n` (computed by the worker), both read from the caller's matrix, so
//! that each core streams (and keeps in its private L2 cache as far as it fits) half of it.
//!
//! Every output entry is the same dot product, over the same contiguous column, with the same
//! kernel ([`crate::linalg::matvec`], whose reduction order per row does not depend on the other
//! rows: tested bitwise in this module), so the split product equals the one-thread product bit
//! for bit.
//!
//! Hand-off, without locks or copies: the caller publishes the addresses and shape of the
//! worker's part (its columns of the matrix, the right-hand side, the output rows) in atomics
//! and bumps a sequence number (release); the worker spins on it for [`ProductWorker::new`]'s
//! `spin` window after its last job and then parks (`std::thread::park`, woken by the next
//! job), so a machine does not lose a core to spinning between runs of products. Whoever comes
//! first claims the second half (a compare-and-swap): the worker, or the caller once its own
//! half is done (the worker descheduled on a loaded machine, or parked): the caller then
//! computes it itself with the same kernel, so a late worker never makes the product slower
//! than on one thread. When the worker has claimed it, the caller waits (spinning briefly, then
//! yielding) until the worker has written the rows into the caller's output; the borrowed
//! matrix, right-hand side and output therefore outlive the worker's use of them.

use crate::linalg::matvec;
use faer::MatRef;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicIsize, AtomicPtr, AtomicUsize, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The worker's part of the current job: `out[..m] = Bᵀ x[..k]` with `B` the `k × m` view at
/// `b` with strides `(rs, cs)` (published before the job's sequence number, read after it).
struct Job {
    b: AtomicPtr<f64>,
    rs: AtomicIsize,
    cs: AtomicIsize,
    x: AtomicPtr<f64>,
    k: AtomicUsize,
    out: AtomicPtr<f64>,
    m: AtomicUsize,
}

struct Shared {
    /// Jobs posted so far.
    seq: AtomicUsize,
    /// Jobs claimed so far (by the worker or, when it is late, by the caller).
    claimed: AtomicUsize,
    /// Jobs finished by the worker so far.
    done: AtomicUsize,
    stop: AtomicBool,
    job: Job,
    spin: Duration,
    /// Products applied so far, consecutive products in which the worker did not help, and
    /// the product count up to which the products run on the caller alone (see
    /// [`SplitProduct::apply`]).
    count: AtomicUsize,
    slow: AtomicUsize,
    off_until: AtomicUsize,
    /// Whether the worker is parked (idle longer than its spin window, e.g. while the caller
    /// writes output between steps): a product it misses then does not count as slow.
    parked: AtomicBool,
}

/// One persistent worker thread that computes the second half of [`SplitProduct`]s (several
/// products may share it, one at a time: e.g. the rolling tire's force matrix and the explicit
/// inverse of its iteration matrix, which are applied one after the other in a step).
pub struct ProductWorker {
    shared: Arc<Shared>,
    handle: Option<JoinHandle<()>>,
}

impl std::fmt::Debug for ProductWorker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ProductWorker")
            .field("spin", &self.shared.spin)
            .finish_non_exhaustive()
    }
}

/// Default spin window of the worker after a job \[s\]: a little longer than the work between
/// the products of one tire step, far shorter than a time slice.
pub const DEFAULT_SPIN: Duration = Duration::from_micros(200);

impl ProductWorker {
    /// Starts the worker thread; after each job it spins for `spin` waiting for the next one,
    /// then parks. Errors if the thread cannot be spawned.
    pub fn new(spin: Duration) -> std::io::Result<Arc<Self>> {
        let null = || AtomicPtr::new(std::ptr::null_mut());
        let shared = Arc::new(Shared {
            seq: AtomicUsize::new(0),
            claimed: AtomicUsize::new(0),
            done: AtomicUsize::new(0),
            stop: AtomicBool::new(false),
            job: Job {
                b: null(),
                rs: AtomicIsize::new(0),
                cs: AtomicIsize::new(0),
                x: null(),
                k: AtomicUsize::new(0),
                out: null(),
                m: AtomicUsize::new(0),
            },
            spin,
            count: AtomicUsize::new(0),
            slow: AtomicUsize::new(0),
            off_until: AtomicUsize::new(0),
            parked: AtomicBool::new(false),
        });
        let s = Arc::clone(&shared);
        let handle = std::thread::Builder::new()
            .name("mbd-product".into())
            .spawn(move || worker_loop(&s))?;
        Ok(Arc::new(Self {
            shared,
            handle: Some(handle),
        }))
    }

    /// A worker when `threads ≥ 2` (the products use two threads; more are not used), `None`
    /// for one thread or when the thread cannot be spawned (the products then run on the
    /// calling thread alone, with the same results).
    pub fn for_threads(threads: usize) -> Option<Arc<Self>> {
        if threads >= 2 {
            Self::new(DEFAULT_SPIN).ok()
        } else {
            None
        }
    }

    /// The worker's POSIX thread (e.g. to read its CPU clock with `pthread_getcpuclockid`).
    #[cfg(unix)]
    pub fn pthread(&self) -> Option<std::os::unix::thread::RawPthread> {
        use std::os::unix::thread::JoinHandleExt;
        self.handle.as_ref().map(|h| h.as_pthread_t())
    }

    fn wake(&self) {
        if let Some(h) = &self.handle {
            h.thread().unpark();
        }
    }
}

impl Drop for ProductWorker {
    fn drop(&mut self) {
        self.shared.stop.store(true, Ordering::Release);
        self.wake();
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

fn worker_loop(s: &Shared) {
    let mut last = 0;
    let mut since = Instant::now();
    loop {
        let mut spins = 0u32;
        loop {
            let seq = s.seq.load(Ordering::Acquire);
            if seq != last {
                last = seq;
                break;
            }
            if s.stop.load(Ordering::Acquire) {
                return;
            }
            spins += 1;
            if spins.is_multiple_of(64) && since.elapsed() > s.spin {
                // a job posted after this check unparks us (park returns at once if the
                // unpark came first)
                s.parked.store(true, Ordering::Release);
                std::thread::park();
                s.parked.store(false, Ordering::Release);
                since = Instant::now();
            } else {
                std::hint::spin_loop();
            }
        }
        // the caller computes the job itself if it finishes its half before we claim it
        if s.claimed
            .compare_exchange(last - 1, last, Ordering::AcqRel, Ordering::Acquire)
            .is_err()
        {
            continue;
        }
        let j = &s.job;
        let (k, m) = (j.k.load(Ordering::Relaxed), j.m.load(Ordering::Relaxed));
        // SAFETY: the caller published this job's views before its sequence number (read with
        // acquire above) and does not return from `SplitProduct::apply`, i.e. keeps the
        // matrix, the right-hand side and the output borrowed and untouched, until we store
        // `done` below; we claimed the job, so the caller does not write these output rows
        unsafe {
            let b = MatRef::from_raw_parts(
                j.b.load(Ordering::Relaxed),
                k,
                m,
                j.rs.load(Ordering::Relaxed),
                j.cs.load(Ordering::Relaxed),
            );
            let x = std::slice::from_raw_parts(j.x.load(Ordering::Relaxed), k);
            let out = std::slice::from_raw_parts_mut(j.out.load(Ordering::Relaxed), m);
            matvec(b.transpose(), x, out);
        }
        s.done.store(last, Ordering::Release);
        since = Instant::now();
    }
}

/// The product `y = A x` with the stored `Aᵀ` (`n_x × n_y`, column `i` = row `i` of `A`), its
/// rows split between the calling thread and a [`ProductWorker`] (module documentation).
/// Without a worker it is the one-thread product.
pub struct SplitProduct {
    worker: Option<Arc<ProductWorker>>,
    /// Rows of `A` computed by the caller (`0..split`).
    split: usize,
    /// Shape of `Aᵀ` at the last [`SplitProduct::set`].
    shape: (usize, usize),
}

impl std::fmt::Debug for SplitProduct {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SplitProduct")
            .field("threads", &(1 + usize::from(self.worker.is_some())))
            .field("split", &self.split)
            .field("shape", &self.shape)
            .finish()
    }
}

impl SplitProduct {
    /// A product on `worker` (`None`: the calling thread alone); no matrix yet.
    pub fn new(worker: Option<Arc<ProductWorker>>) -> Self {
        Self {
            worker,
            split: 0,
            shape: (0, 0),
        }
    }

    /// Whether a worker computes part of the product.
    pub fn is_split(&self) -> bool {
        self.worker.is_some()
    }

    /// Takes the shape of the matrix `at = Aᵀ` and chooses the split of its columns (both
    /// threads read `at` itself in [`SplitProduct::apply`]); call again when the shape changes.
    pub fn set(&mut self, at: MatRef<'_, f64>) {
        self.shape = (at.nrows(), at.ncols());
        let n = at.ncols();
        // an even split of the rows (the worker's half a little larger when odd: the caller
        // also pays the hand-off)
        self.split = if self.worker.is_some() { n / 2 } else { n };
    }

    /// `out = A x` with `at = Aᵀ` of the shape of the last [`SplitProduct::set`]. Panics if the
    /// shapes differ from that matrix's.
    pub fn apply(&self, at: MatRef<'_, f64>, x: &[f64], out: &mut [f64]) {
        assert_eq!(
            (at.nrows(), at.ncols()),
            self.shape,
            "SplitProduct::apply on a matrix other than the one set"
        );
        assert!(x.len() == at.nrows() && out.len() == at.ncols());
        let n = at.ncols();
        let Some(w) = self.worker.as_ref().filter(|_| self.split < n) else {
            matvec(at.transpose(), x, out);
            return;
        };
        let s = &w.shared;
        // while the worker does not help (a loaded machine: it is descheduled or late), the
        // products run on the caller alone for a while, then the worker is tried again
        let count = s.count.fetch_add(1, Ordering::Relaxed);
        if count < s.off_until.load(Ordering::Relaxed) {
            matvec(at.transpose(), x, out);
            return;
        }
        let theirs = at.subcols(self.split, n - self.split);
        let (head, tail) = out.split_at_mut(self.split);
        let j = &s.job;
        j.b.store(theirs.as_ptr().cast_mut(), Ordering::Relaxed);
        j.rs.store(theirs.row_stride(), Ordering::Relaxed);
        j.cs.store(theirs.col_stride(), Ordering::Relaxed);
        j.x.store(x.as_ptr().cast_mut(), Ordering::Relaxed);
        j.k.store(x.len(), Ordering::Relaxed);
        j.out.store(tail.as_mut_ptr(), Ordering::Relaxed);
        j.m.store(tail.len(), Ordering::Relaxed);
        // a parked worker (idle beyond its spin window: the caller paused, e.g. for output) is
        // woken and misses this product without counting as slow
        let asleep = s.parked.load(Ordering::Acquire);
        let seq = s.seq.fetch_add(1, Ordering::AcqRel) + 1;
        w.wake();
        let start = Instant::now();
        matvec(at.subcols(0, self.split).transpose(), x, head);
        let own = start.elapsed();
        // the worker has not taken the job yet (e.g. descheduled on a loaded machine): compute
        // the second half here, with the same kernel
        let helped = if s
            .claimed
            .compare_exchange(seq - 1, seq, Ordering::AcqRel, Ordering::Acquire)
            .is_ok()
        {
            matvec(theirs.transpose(), x, tail);
            false
        } else {
            // the worker writes `tail` until it stores `done` (acquire: its writes are then
            // visible here); `out`, `x` and `at` stay borrowed until then
            let mut spins = 0u32;
            while s.done.load(Ordering::Acquire) != seq {
                spins += 1;
                if spins > 4096 {
                    std::thread::yield_now();
                } else {
                    std::hint::spin_loop();
                }
            }
            // waiting longer than the own half took: no gain from the worker
            start.elapsed() < 2 * own
        };
        if helped {
            s.slow.store(0, Ordering::Relaxed);
        } else if !asleep && s.slow.fetch_add(1, Ordering::Relaxed) + 1 >= OFF_AFTER {
            s.slow.store(0, Ordering::Relaxed);
            s.off_until.store(count + OFF_FOR, Ordering::Relaxed);
        }
    }
}

/// Consecutive products without help from the worker after which the products run on the
/// caller alone for [`OFF_FOR`] products (the worker then parks).
const OFF_AFTER: usize = 8;
/// See [`OFF_AFTER`] (about 0.1 s of the rolling tire's steps).
const OFF_FOR: usize = 2000;

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// The split product equals the one-thread product bit for bit (same kernel, same
    /// reduction order per row; module documentation), for shapes around the SIMD widths and
    /// for two products sharing one worker.
    #[test]
    fn split_product_equals_one_thread_product_bitwise() {
        let worker = ProductWorker::new(DEFAULT_SPIN).expect("worker thread");
        for (nx, ny) in [(1, 1), (3, 2), (7, 5), (64, 33), (337, 336), (670, 336)] {
            let at = Mat::<f64>::from_fn(nx, ny, |i, j| {
                ((i * 7919 + j * 104_729) % 1000) as f64 / 997.0 - 0.5 + 1e-3 * (i as f64).sin()
            });
            let x: Vec<f64> = (0..nx).map(|i| (0.37 * i as f64).cos()).collect();
            let mut one = vec![0.0; ny];
            let mut seq = SplitProduct::new(None);
            seq.set(at.as_ref());
            seq.apply(at.as_ref(), &x, &mut one);
            // independent reference: the plain dot products (to round-off)
            for (j, o) in one.iter().enumerate() {
                let r: f64 = (0..nx).map(|i| at[(i, j)] * x[i]).sum();
                assert!(
                    (o - r).abs() <= 1e-12 * (1.0 + r.abs()),
                    "{nx}x{ny} row {j}"
                );
            }
            let mut a = SplitProduct::new(Some(Arc::clone(&worker)));
            let mut b = SplitProduct::new(Some(Arc::clone(&worker)));
            a.set(at.as_ref());
            let at2 = Mat::<f64>::from_fn(nx, ny, |i, j| at[(i, j)] * 2.0 - 1.0);
            b.set(at2.as_ref());
            assert!(a.is_split());
            // many hand-offs: some halves computed by the worker, some by the caller
            for _ in 0..50 {
                let mut two = vec![f64::NAN; ny];
                a.apply(at.as_ref(), &x, &mut two);
                assert_eq!(one, two, "{nx}x{ny}");
                let mut two2 = vec![f64::NAN; ny];
                let mut one2 = vec![0.0; ny];
                b.apply(at2.as_ref(), &x, &mut two2);
                matvec(at2.as_ref().transpose(), &x, &mut one2);
                assert_eq!(one2, two2, "{nx}x{ny} second slot");
            }
            // after the worker has parked
            std::thread::sleep(Duration::from_millis(2));
            let mut two = vec![f64::NAN; ny];
            a.apply(at.as_ref(), &x, &mut two);
            assert_eq!(one, two, "{nx}x{ny} after parking");
        }
    }
}
