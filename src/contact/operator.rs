//! The linear map from cell pressures to surface displacements. The solver only needs
//! `apply`, so it runs unchanged on the fast [`super::DcFft`], on the [`DenseOperator`]
//! reference, or on a [`SumOperator`] of both kernels; an operator may also offer an
//! approximate inverse ([`Preconditioner`]) to speed the solver up.

use super::influence::Kernel;

/// A linear operator on fields over an `nx` x `ny` grid (row-major, x fastest).
pub trait Operator {
    /// Cells along x and y.
    fn shape(&self) -> (usize, usize);

    /// `output = K input`. Takes `&mut self` so implementations keep their scratch buffers
    /// and allocate nothing per call.
    fn apply(&mut self, input: &[f64], output: &mut [f64]);

    /// An approximate inverse the solver may precondition with; `None` (the default)
    /// runs plain conjugate gradients.
    fn preconditioner(&mut self) -> Option<&mut dyn Preconditioner> {
        None
    }

    /// Adds the operator applied to a field that is zero except at `cells` (index and value)
    /// to `output`, when the operator can do that for less than an apply; false (the
    /// default), with `output` untouched, when it cannot.
    fn add_sparse(&mut self, _cells: &[(usize, f64)], _output: &mut [f64]) -> bool {
        false
    }

    /// The first half of an apply whose transform is kept: `input . K input`, or `None`
    /// (the default) when the operator does not keep one. After `Some`,
    /// [`Operator::add_kept`] adds `K (extra + scale input)` to a field for the cost of
    /// what remains of the apply and of one forward transform of `extra`.
    fn keep(&mut self, _input: &[f64]) -> Option<f64> {
        None
    }

    /// Adds `K (extra + scale input)` to `output`, `input` that of the last
    /// [`Operator::keep`] that returned `Some` (`extra` zero when `None`). Only called
    /// after one did: the default has nothing kept.
    fn add_kept(&mut self, _extra: Option<&[f64]>, _scale: f64, _output: &mut [f64]) {
        unreachable!("add_kept without a kept transform");
    }

    /// Whether the operator wraps around the grid's edges (a periodic surface), so a
    /// contact on the edge cells is as valid as anywhere; `false` (the default) for the
    /// half-space operators, whose edge cells stand for a domain that ends there.
    fn is_periodic(&self) -> bool {
        false
    }

    /// The threads an apply is split over, which the solver's passes over the grid take
    /// too, in fixed blocks; 1 (the default) where the operator does not split.
    fn threads(&self) -> usize {
        1
    }

    /// Whether every coefficient is nonnegative, so a nonnegative pressure displaces every
    /// cell by a nonnegative amount: a cell the separation alone keeps open stays open.
    /// `false` (the default) when the operator does not know.
    fn is_nonnegative(&self) -> bool {
        false
    }
}

/// An approximate inverse `M^-1` of an operator, applied to the solver's gap on the free
/// cells (e.g. [`super::FourierInverse`]). It only changes how fast the solver converges,
/// never what it converges to: the stopping test is on the true residual.
pub trait Preconditioner {
    /// `output = M^-1 input`. Takes `&mut self` so implementations keep their scratch
    /// buffers and allocate nothing per call.
    fn apply(&mut self, input: &[f64], output: &mut [f64]);

    /// `M^-1`'s diagonal entry, the same on every cell: the inverse is a convolution.
    fn diagonal(&self) -> f64;

    /// The response of `M^-1` to a unit value on one cell, within [`NEAR_REACH`] cells of it
    /// along each axis: `(2 NEAR_REACH + 1)^2` entries, y-major, the diagonal in the middle.
    fn near_field(&self) -> &[f64];
}

/// How far [`Preconditioner::near_field`] reaches, in cells.
pub const NEAR_REACH: usize = 2;

/// Direct summation `u_I = sum_J K(I - J) p_J`, O(N^4): the reference the FFT operator is
/// tested against, and fast enough for grids of a few thousand cells.
#[derive(Debug, Clone)]
pub struct DenseOperator {
    kernel: Kernel,
}

impl DenseOperator {
    /// The direct-summation operator of `kernel`.
    pub fn new(kernel: Kernel) -> Self {
        Self { kernel }
    }
}

impl Operator for DenseOperator {
    fn shape(&self) -> (usize, usize) {
        self.kernel.shape()
    }

    fn apply(&mut self, input: &[f64], output: &mut [f64]) {
        let (nx, ny) = self.shape();
        for (i, out) in output.iter_mut().enumerate() {
            let (ix, iy) = ((i % nx) as isize, (i / nx) as isize);
            let mut sum = 0.0;
            for (j, &p) in input.iter().enumerate() {
                if p != 0.0 {
                    let (jx, jy) = ((j % nx) as isize, (j / nx) as isize);
                    sum += self.kernel.value(ix - jx, iy - jy) * p;
                }
            }
            *out = sum;
        }
        debug_assert_eq!(output.len(), nx * ny);
    }
}

/// `A + B`: the normal and the coupling operators together, e.g. for checking a coupled
/// solution against the full (non-symmetric) operator.
#[derive(Debug)]
pub struct SumOperator<A, B> {
    first: A,
    second: B,
    scratch: Vec<f64>,
}

impl<A: Operator, B: Operator> SumOperator<A, B> {
    /// The sum of two operators of the same shape.
    pub fn new(first: A, second: B) -> Self {
        assert_eq!(first.shape(), second.shape(), "operator shapes differ");
        let (nx, ny) = first.shape();
        Self {
            first,
            second,
            scratch: vec![0.0; nx * ny],
        }
    }
}

impl<A: Operator, B: Operator> Operator for SumOperator<A, B> {
    fn shape(&self) -> (usize, usize) {
        self.first.shape()
    }

    fn apply(&mut self, input: &[f64], output: &mut [f64]) {
        self.first.apply(input, output);
        self.second.apply(input, &mut self.scratch);
        for (o, s) in output.iter_mut().zip(&self.scratch) {
            *o += s;
        }
    }
}
