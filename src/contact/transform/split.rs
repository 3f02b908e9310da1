//! A 2D FFT convolution with its three passes split across threads, and how many threads
//! an apply gets. The passes: the forward row transforms by rows, the column transforms and
//! the kernel product by columns, the inverse row transforms by rows. It serves the DC-FFT
//! apply (rows and columns zero-padded to twice the grid) and the periodic
//! [`crate::contact::FourierInverse`] (no padding). Each pass is a `std::thread::scope`: its
//! end is the barrier the next pass needs, and each thread owns a contiguous slice of the
//! buffer it writes, so no locking and no unsafe code is needed. Spawning costs a few tens
//! of microseconds per pass against milliseconds of work per apply from N = 256 on. The
//! threads do not share scratch: each has its own rows and FFT scratch, and the plans
//! themselves are shared read-only.
//!
//! The row spectra go through a row-major buffer (`spectra`, `ny` x `nx + 1` complex
//! values) between the forward row pass and the column pass, 16 bytes per cell (8 in f32),
//! and the columns stay in a buffer of all of them for the inverse row pass. The one-thread
//! passes ([`super::Passes`]) bring each block of columns back into the row spectra
//! instead; split, a thread's block of columns spans every row, not a contiguous slice of
//! the row spectra that the thread could own.

use std::num::NonZeroUsize;

use rustfft::num_complex::Complex;

use super::{BLOCK, Plans, Real, forward_row, inverse_row, packed_len, store_row, transpose};

/// The most threads an apply may be split across (the bound of the scene's
/// `numerics.threads`).
pub const MAX_SPLIT_THREADS: usize = 64;

/// Grid cells from which an automatic thread count splits an apply, or `None`: never.
/// The passes run on a pool whose threads stay up between them (rayon's), where a thread
/// spawned per pass cost about 60 us. `tribosim bench threads` on the idle 2-core machine:
/// two threads take 1/1.37 of one thread's time at N = 256 and 1/1.71 at 512 (with a
/// thread spawned per pass, 1/0.78 and 1/1.47). From 384 x 384 cells the 2 um rough example
/// of `docs/scene.md` splits from its first windows: its first 300 cycles took 0.70 of the
/// wall time of the spawned split from 512 x 512 (`docs/accuracy.md`, "Rough wear: the
/// solver's passes on two threads"), for 1.10 of the CPU time. The 4 um rough disc's
/// windows stay below it, on one thread (seed 1's results are the same to the bit; seeds 2
/// and 5 reach it late in their 600 cycles): there the split would gain
/// less (1/1.37 at N = 256) for that CPU time, by which the rough default is measured
/// (`docs/accuracy.md`, "the default by speed against error"). Under load from other work the
/// split lost (0.67-0.86 at N >= 512, load average 6-8): the second thread waits for a busy
/// core, which is why the service gives each of its workers one core's share.
pub const SPLIT_MIN_CELLS: Option<usize> = Some(384 * 384);

/// The threads of an apply on `cells` cells: `requested`, or (automatic, `None`) one below
/// [`SPLIT_MIN_CELLS`] and, from there on, the cores the process may use divided among the
/// `concurrent_runs` runs solving at the same time (the service's workers, a study's
/// threads), at least one. The results do not depend on it: the split apply equals the
/// one-thread apply to the last bit.
pub fn split_threads(
    requested: Option<usize>,
    cells: usize,
    concurrent_runs: NonZeroUsize,
) -> usize {
    requested.unwrap_or_else(|| {
        if SPLIT_MIN_CELLS.is_none_or(|min| cells < min) {
            return 1;
        }
        let cores = std::thread::available_parallelism().map_or(1, usize::from);
        (cores / concurrent_runs).max(1)
    })
}

/// The threads of an unpadded (periodic) transform of `cells` cells beside an apply split
/// `threads` ways: `threads` from [`SPLIT_MIN_CELLS`] on, as the apply's, else one: the
/// preconditioner's transforms run on the same window as the apply. With the pool's
/// threads, the apply and these transforms split from 131,072 cells instead of 512 x 512
/// and 1024 x 1024 took 0.976 of the wall time (`scripts/rough_ab.py --scene
/// scenes/bench-rough-2um-300um.json`, 3 pairs, against the spawned split).
pub(crate) fn periodic_threads(threads: usize, cells: usize) -> usize {
    if SPLIT_MIN_CELLS.is_some_and(|min| cells >= min) {
        threads
    } else {
        1
    }
}

/// The per-thread state and the shared row-spectrum buffer of a split apply.
pub(crate) struct Split<T: Real = f64> {
    workers: Vec<Worker<T>>,
    spectra: Vec<Complex<T>>,
    /// Half-spectrum row length `row_len / 2 + 1`.
    half: usize,
}

/// The product of column `k` of the spectrum with the kernel's, in place.
pub(crate) type ColumnProduct<'a, T> = &'a (dyn Fn(usize, &mut [Complex<T>]) + Sync);

/// How a row of an inverse transform, held in pairs, goes into the output: stored, or
/// added.
pub(crate) type RowPut<T> = fn(&mut [f64], &[Complex<T>]);

/// One thread's scratch.
struct Worker<T: Real> {
    plans: Plans<T>,
    row_packed: Vec<Complex<T>>,
    row_block: Vec<Complex<T>>,
}

/// The sizes of the apply, shared by every thread.
#[derive(Clone, Copy)]
struct Shape {
    nx: usize,
    ny: usize,
    half: usize,
    col_len: usize,
    stride: usize,
}

impl<T: Real> Split<T> {
    /// Scratch for `threads` threads on `ny` rows transformed at length `row_len` (the
    /// grid's `nx`, or more when zero-padded), with copies of `plans`' transforms.
    pub(crate) fn new(threads: usize, plans: &Plans<T>, row_len: usize, ny: usize) -> Self {
        let half = row_len / 2 + 1;
        Self {
            workers: (0..threads)
                .map(|_| Worker {
                    plans: plans.clone(),
                    row_packed: vec![Complex::default(); packed_len(row_len)],
                    row_block: vec![Complex::default(); BLOCK * half],
                })
                .collect(),
            spectra: vec![Complex::default(); ny * half],
            half,
        }
    }

    /// The number of threads.
    pub(crate) fn threads(&self) -> usize {
        self.workers.len()
    }

    /// `output = K input` on the `nx` x `ny` grid, the columns transformed at length
    /// `col_len` (`ny`, or more when zero-padded), `product` multiplying each by the
    /// kernel's spectrum, using `columns` (the operator's transposed work buffer of
    /// half-spectrum columns `stride` apart) for the column pass.
    pub(crate) fn apply(
        &mut self,
        shape: (usize, usize, usize, usize),
        product: ColumnProduct<T>,
        columns: &mut [Complex<T>],
        input: &[f64],
        output: &mut [f64],
    ) {
        self.passes(
            shape,
            product,
            columns,
            Some(input),
            Some((output, store_row)),
        );
    }

    /// The passes of [`Self::apply`], each where asked: the forward transforms of `input`
    /// (`None`: `product` makes each column from nothing), `product` on each column, and
    /// the inverse transforms, their rows `put` into `output` (`None`: the columns keep the
    /// forward transform, after `product`).
    pub(crate) fn passes(
        &mut self,
        (nx, ny, col_len, stride): (usize, usize, usize, usize),
        product: ColumnProduct<T>,
        columns: &mut [Complex<T>],
        input: Option<&[f64]>,
        output: Option<(&mut [f64], RowPut<T>)>,
    ) {
        let shape = Shape {
            nx,
            ny,
            half: self.half,
            col_len,
            stride,
        };
        let threads = self.workers.len();
        let rows = ny.div_ceil(threads);
        let cols = shape.half.div_ceil(threads);
        if let Some(input) = input {
            let spectra = &mut self.spectra;
            in_parallel(
                self.workers
                    .iter_mut()
                    .zip(spectra.chunks_mut(rows * shape.half))
                    .zip(input.chunks(rows * nx)),
                |((worker, spectra), input)| worker.forward_rows(shape, input, spectra),
            );
        }
        let (spectra, forward, inverse) = (&self.spectra, input.is_some(), output.is_some());
        in_parallel(
            self.workers
                .iter_mut()
                .zip(columns.chunks_mut(cols * stride))
                .enumerate(),
            |(i, (worker, columns))| {
                let first = i * cols;
                worker.columns(shape, product, (spectra, forward, inverse), first, columns);
            },
        );
        let Some((output, put)) = output else {
            return;
        };
        let columns = &*columns;
        in_parallel(
            self.workers
                .iter_mut()
                .zip(output.chunks_mut(rows * nx))
                .enumerate(),
            |(i, (worker, output))| worker.inverse_rows(shape, columns, i * rows, (output, put)),
        );
    }
}

/// Runs `job` on every item, the first on this thread and the others on the pool's.
fn in_parallel<I: Iterator + Send>(mut items: I, job: impl Fn(I::Item) + Sync)
where
    I::Item: Send,
{
    let job = &job;
    rayon::scope(|scope| {
        let first = items.next();
        for item in items {
            scope.spawn(move |_| job(item));
        }
        if let Some(item) = first {
            job(item);
        }
    });
}

impl<T: Real> Worker<T> {
    /// Real-to-complex transforms of the zero-padded rows of `input` into `spectra`.
    fn forward_rows(&mut self, shape: Shape, input: &[f64], spectra: &mut [Complex<T>]) {
        let nx = shape.nx;
        for (row, out) in input
            .chunks_exact(nx)
            .zip(spectra.chunks_exact_mut(shape.half))
        {
            forward_row(&mut self.plans, row, &mut self.row_packed, out);
        }
    }

    /// The columns `first..` held in `columns`: gathered from the row spectra in blocks of
    /// [`BLOCK`] columns, zero-padded and transformed (if `forward`), multiplied by the
    /// kernel spectrum (`product`) and transformed back (if `inverse`).
    fn columns(
        &mut self,
        shape: Shape,
        product: ColumnProduct<T>,
        (spectra, forward, inverse): (&[Complex<T>], bool, bool),
        first: usize,
        columns: &mut [Complex<T>],
    ) {
        let (ny, half, stride) = (shape.ny, shape.half, shape.stride);
        for (b, block) in columns.chunks_mut(BLOCK * stride).enumerate() {
            let k0 = first + b * BLOCK;
            let width = block.len() / stride;
            if forward {
                transpose(&spectra[k0..], half, (ny, width), block, stride);
            }
            for (j, column) in block.chunks_mut(stride).enumerate() {
                let column = &mut column[..shape.col_len];
                if forward {
                    column[ny..].fill(Complex::default());
                    self.plans
                        .col_forward
                        .process_with_scratch(column, &mut self.plans.complex_scratch);
                }
                product(k0 + j, column);
                if inverse {
                    self.plans
                        .col_inverse
                        .process_with_scratch(column, &mut self.plans.complex_scratch);
                }
            }
        }
    }

    /// Complex-to-real transforms of the rows `first..` of the columns, `put` into `output`.
    fn inverse_rows(
        &mut self,
        shape: Shape,
        columns: &[Complex<T>],
        first: usize,
        (output, put): (&mut [f64], RowPut<T>),
    ) {
        let (nx, half, stride) = (shape.nx, shape.half, shape.stride);
        for (b, rows) in output.chunks_mut(BLOCK * nx).enumerate() {
            let iy0 = first + b * BLOCK;
            let count = rows.len() / nx;
            transpose(
                &columns[iy0..],
                stride,
                (half, count),
                &mut self.row_block,
                half,
            );
            for (slot, out) in rows.chunks_exact_mut(nx).enumerate() {
                let row = &mut self.row_block[slot * half..(slot + 1) * half];
                inverse_row(&mut self.plans, row, &mut self.row_packed);
                put(out, &self.row_packed);
            }
        }
    }
}
