//! The contact core: influence coefficients, the DC-FFT operator and the bounded solver.
