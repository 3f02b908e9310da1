//! Influence coefficients: the normal surface displacement at a cell centre due to a uniform
//! pressure on another rectangular cell (Love; Bjorklund & Andersson; paper eqs. 5-10 and
//! Appendix A).
//!
//! With `X = x - xi`, `Y = y - eta` and the cell `[-a, a] x [-b, b]`, two integrals appear:
//! - the Boussinesq term `I_n = int int 1 / r` (Appendix A's `g_xx^A + g_xx^B`);
//! - the Cerruti coupling term `I_c = int int X / r^2` (eq. 9's `g_xz`).
//!
//! Both are evaluated in closed form as corner sums of an antiderivative `F(X, Y)` with
//! `d^2 F / dX dY` = the integrand: `I = F(x+a, y+b) - F(x+a, y-b) - F(x-a, y+b) + F(x-a, y-b)`.
//!
//! # The sign of the coupling term
//! Appendix A prints `g_xz` with the opposite sign to the eq. 9 integral (expand its corner
//! sum: every term is the negative of the one below). We therefore derive the coupling
//! from the physics instead of from either printed formula. Cerruti's solution (Johnson,
//! Contact Mechanics, eq. 3.86c) for a tangential force `Q` in +x on a half-space whose z
//! axis points into the body gives a normal surface displacement, positive into the body,
//! `u_z = -(1 - 2 nu) Q X / (4 pi G r^2)`: material ahead of the force rises. The ball
//! slides in +x over the disc, so friction pushes the disc surface with `+mu p` and the ball
//! surface with `-mu p`; each body's z axis points into itself, and the gap closes by
//! `u_z1 + u_z2`. Summing the two bodies:
//! `u_z = mu ((1 - 2 nu1)/G1 - (1 - 2 nu2)/G2) / (4 pi) int int p X / r^2
//!      = (1/2) delta_nu mu I_c / (2 pi G*)`,
//! using `delta_nu / G* = (1 - 2 nu1)/G1 - (1 - 2 nu2)/G2` (eq. 8). That is eq. 7 with a
//! plus sign on the eq. 9 integral, equivalently eq. 7's minus sign on Appendix A's `g_xz`.

use super::{ElasticPair, Grid};

/// `X asinh(Y / |X|)`, continuous at `X = 0` where it vanishes.
fn x_asinh(x: f64, y: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        x * (y / x.abs()).asinh()
    }
}

/// Antiderivative of `1 / r`: `X ln(Y + r) + Y ln(X + r)` with the `X ln|X| + Y ln|Y|` part
/// dropped, since it cancels in every corner sum. The asinh form has no cancellation when
/// `Y + r` is tiny (Y large and negative).
fn normal_antiderivative(x: f64, y: f64) -> f64 {
    x_asinh(x, y) + x_asinh(y, x)
}

/// [`normal_antiderivative`] where `x, y > 0`, all [`Kernel::build`] evaluates: each
/// `asinh(t)` as `ln_1p(t + t^2 / (1 + sqrt(1 + t^2)))`, the two terms sharing one square
/// root `r` (each `asinh` computes its own `hypot`). The normal kernel's build at N = 256
/// took 5.2 ms instead of 7.8 ms (`kernel_build_time` below, before the quadrant copy of
/// [`Kernel::build`]), the two forms at most 2.3 ulp apart.
fn normal_antiderivative_positive(x: f64, y: f64) -> f64 {
    let r = (x * x + y * y).sqrt();
    x * (y / x + y * y / (x * (r + x))).ln_1p() + y * (x / y + x * x / (y * (r + y))).ln_1p()
}

/// Antiderivative of `X / r^2`: `X atan(Y / X) + (Y / 2) ln(X^2 + Y^2)`. The single-argument
/// arctangent is the right branch: `X atan(Y / X)` is continuous across `X = 0`, while an
/// `atan2` form jumps there and gives wrong values inside the cell.
fn coupling_antiderivative(x: f64, y: f64) -> f64 {
    let r2 = x * x + y * y;
    let atan_term = if x == 0.0 { 0.0 } else { x * (y / x).atan() };
    let log_term = if y == 0.0 { 0.0 } else { 0.5 * y * r2.ln() };
    atan_term + log_term
}

fn corner_sum(f: impl Fn(f64, f64) -> f64, x: f64, y: f64, a: f64, b: f64) -> f64 {
    f(x + a, y + b) - f(x + a, y - b) - f(x - a, y + b) + f(x - a, y - b)
}

/// `int_{-b}^{b} int_{-a}^{a} d xi d eta / r` at the point `(x, y)`, metres.
pub fn normal_integral(x: f64, y: f64, a: f64, b: f64) -> f64 {
    corner_sum(normal_antiderivative, x, y, a, b)
}

/// `int_{-b}^{b} int_{-a}^{a} (x - xi) / r^2 d xi d eta` at `(x, y)` (eq. 9's definition).
pub fn coupling_integral(x: f64, y: f64, a: f64, b: f64) -> f64 {
    corner_sum(coupling_antiderivative, x, y, a, b)
}

/// Influence coefficients as a function of the cell offset `(di, dj)`, for
/// `di in -(nx-1)..=nx-1`, `dj in -(ny-1)..=ny-1`: the displacement at cell `I` per unit
/// pressure on cell `J` is `value(iI - iJ, jI - jJ)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Kernel {
    nx: usize,
    ny: usize,
    values: Vec<f64>,
    symmetry: Symmetry,
}

/// The kernel's parity under `x -> -x` (both kernels are even in y). It fixes the spectrum's
/// type: an even real kernel has a real spectrum, an odd one a purely imaginary spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Symmetry {
    /// `K(-x, y) = K(x, y)`: the normal kernel.
    EvenInX,
    /// `K(-x, y) = -K(x, y)`: the coupling kernel.
    OddInX,
}

impl Kernel {
    /// Evaluates `scale * corner_sum(F)` for every offset. Neighbouring offsets share
    /// corners, so `F` is evaluated once per corner of the `2nx x 2ny` corner lattice
    /// (4x fewer transcendental calls than four corners per offset), and only on the
    /// quadrant `x, y > 0`: the lattice is symmetric about both axes and `F` has the
    /// parities `x_parity`, `y_parity` (+1 even, -1 odd), another 4x; `symmetric` says
    /// `F(x, y) = F(y, x)`, which halves the square part again on square cells. The corner
    /// sums are formed on the quadrant of offsets `>= 0` alone and copied out by the
    /// kernel's parities: a lattice of all the corners would be 2 MB at N = 256, and `perf`
    /// gave a quarter of a build that made one to its page faults. The normal kernel builds
    /// in 1.3 ms at N = 256 and 5.7 ms at 512 (`kernel_build_time`), against 5.2 and 23 ms
    /// with the whole lattice and no diagonal mirror.
    fn build(
        grid: &Grid,
        antiderivative: impl Fn(f64, f64) -> f64,
        (x_parity, y_parity): (f64, f64),
        symmetric: bool,
        scale: f64,
    ) -> Self {
        // F's parity is the opposite of the kernel's: a corner sum differences F once in
        // each direction.
        let symmetry = if x_parity < 0.0 {
            Symmetry::EvenInX
        } else {
            Symmetry::OddInX
        };
        let (nx, ny) = (grid.nx, grid.ny);
        // `F` at the corners of the quadrant, `corner[l * nx + k]` at ((k + 1/2) dx,
        // (l + 1/2) dy): the corners x + a and y + b of offset (k, l).
        // On square cells a symmetric `F` repeats itself across the diagonal: the corner
        // (k, l) with k < l is the corner (l, k) already computed, to the last bit (the
        // same operations with the operands of each sum swapped).
        let mirrored = symmetric && grid.dx.to_bits() == grid.dy.to_bits();
        let mut corner = Vec::with_capacity(nx * ny);
        for l in 0..ny {
            let y = (l as f64 + 0.5) * grid.dy;
            for k in 0..nx {
                corner.push(if mirrored && k < l && l < nx {
                    corner[k * nx + l]
                } else {
                    antiderivative((k as f64 + 0.5) * grid.dx, y)
                });
            }
        }
        // The corner before the first is its mirror image: `F(-x, y) = x_parity F(x, y)`.
        let before = |index: usize, parity: f64| match index {
            0 => (0, parity),
            _ => (index - 1, 1.0),
        };
        // The kernel on the offsets `(k, l) >= 0`, row by row.
        let mut quadrant = Vec::with_capacity(nx * ny);
        for l in 0..ny {
            let (below, sy) = before(l, y_parity);
            for k in 0..nx {
                let (left, sx) = before(k, x_parity);
                let sum =
                    corner[l * nx + k] - sy * corner[below * nx + k] - sx * corner[l * nx + left]
                        + sx * sy * corner[below * nx + left];
                quadrant.push(scale * sum);
            }
        }
        // The other three quadrants by the kernel's parities, the opposite of F's.
        let (kx, ky) = (-x_parity, -y_parity);
        let mut values = Vec::with_capacity((2 * nx - 1) * (2 * ny - 1));
        for dj in -(ny as isize - 1)..ny as isize {
            let row = &quadrant[dj.unsigned_abs() * nx..][..nx];
            let sign = if dj < 0 { ky } else { 1.0 };
            values.extend(row[1..].iter().rev().map(|&v| kx * sign * v));
            values.extend(row.iter().map(|&v| sign * v));
        }
        Self {
            nx,
            ny,
            values,
            symmetry,
        }
    }

    /// The normal (Boussinesq) kernel: `I_n / (pi E*)`, metres per pascal.
    pub fn normal(grid: &Grid, pair: &ElasticPair) -> Self {
        let scale = 1.0 / (std::f64::consts::PI * pair.reduced_modulus_pa);
        Self::build(
            grid,
            normal_antiderivative_positive,
            (-1.0, -1.0),
            true,
            scale,
        )
    }

    /// The friction coupling kernel for `q_x = mu p`: `(1/2) delta_nu mu I_c / (2 pi G*)`,
    /// metres per pascal of normal pressure (see the module notes for the sign).
    pub fn coupling(grid: &Grid, pair: &ElasticPair, friction_coefficient: f64) -> Self {
        let scale = 0.5 * pair.delta_nu * friction_coefficient
            / (2.0 * std::f64::consts::PI * pair.reduced_shear_modulus_pa);
        Self::build(grid, coupling_antiderivative, (1.0, -1.0), false, scale)
    }

    /// Parity in x.
    pub fn symmetry(&self) -> Symmetry {
        self.symmetry
    }

    /// Cells along x and y of the grid this kernel was built for.
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The coefficient for offset `(di, dj)`.
    pub fn value(&self, di: isize, dj: isize) -> f64 {
        self.values[offset_index(self.nx, self.ny, di, dj)]
    }

    /// Every coefficient, offset `(di, dj)` at [`offset_index`].
    pub(crate) fn values(&self) -> &[f64] {
        &self.values
    }
}

/// Where a kernel of an `nx` x `ny` grid keeps offset `(di, dj)`: row `dj + ny - 1` of
/// `2 nx - 1` offsets, so the offsets `di = a..b` of one `dj` are contiguous.
pub(crate) fn offset_index(nx: usize, ny: usize, di: isize, dj: isize) -> usize {
    let row = (dj + ny as isize - 1) as usize;
    let col = (di + nx as isize - 1) as usize;
    row * (2 * nx - 1) + col
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gauss-Legendre nodes and weights on [0, 1], by Newton iteration on P_n.
    fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
        let mut rule = Vec::with_capacity(n);
        for k in 0..n {
            let mut t = (std::f64::consts::PI * (k as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut derivative = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, t);
                for m in 2..=n {
                    let p2 = ((2 * m - 1) as f64 * t * p1 - (m - 1) as f64 * p0) / m as f64;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = n as f64 * (t * p1 - p0) / (t * t - 1.0);
                let step = p1 / derivative;
                t -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let weight = 2.0 / ((1.0 - t * t) * derivative * derivative);
            rule.push((0.5 * (t + 1.0), 0.5 * weight));
        }
        rule
    }

    /// Integral of `f(X, Y)` over the rectangle `0 <= X <= w`, `0 <= Y <= h` whose corner
    /// (0, 0) may hold an integrable 1/r-type singularity. The square `[0, s]^2`, `s` the
    /// short side, goes through Duffy's transform (two triangles with the singular vertex
    /// collapsed, both integrands smooth); the rest of the long side is cut into panels
    /// doubling in length, each at a distance from the corner comparable to its size.
    fn corner_rectangle(f: &impl Fn(f64, f64) -> f64, w: f64, h: f64, rule: &[(f64, f64)]) -> f64 {
        if w == 0.0 || h == 0.0 {
            return 0.0;
        }
        let s = w.min(h);
        let mut sum = 0.0;
        for &(u, wu) in rule {
            for &(v, wv) in rule {
                sum += wu * wv * s * s * u * (f(s * u, s * u * v) + f(s * u * v, s * u));
            }
        }
        let mut start = s;
        while start < w.max(h) {
            let end = (2.0 * start).min(w.max(h));
            for &(u, wu) in rule {
                for &(v, wv) in rule {
                    let along = start + (end - start) * u;
                    let across = s * v;
                    let value = if w > h {
                        f(along, across)
                    } else {
                        f(across, along)
                    };
                    sum += wu * wv * (end - start) * s * value;
                }
            }
            start = end;
        }
        sum
    }

    /// Quadrature of `int int f(x - xi, y - eta)` over the cell. With `X = x - xi`, the cell
    /// maps to `[x-a, x+a] x [y-b, y+b]`, written as four signed rectangles
    /// `R(P, Q) = int_0^P int_0^Q f` that each have the singular point at a corner.
    fn quadrature(f: impl Fn(f64, f64) -> f64, x: f64, y: f64, a: f64, b: f64) -> f64 {
        let rule = gauss_legendre(40);
        let signed_rectangle = |p: f64, q: f64| {
            let g = |u: f64, v: f64| f(p.signum() * u, q.signum() * v);
            p.signum() * q.signum() * corner_rectangle(&g, p.abs(), q.abs(), &rule)
        };
        signed_rectangle(x + a, y + b)
            - signed_rectangle(x + a, y - b)
            - signed_rectangle(x - a, y + b)
            + signed_rectangle(x - a, y - b)
    }

    fn points() -> Vec<(f64, f64)> {
        // Inside (centre, off-centre, near an edge), on an edge, near, far, diagonal.
        vec![
            (0.0, 0.0),
            (0.3, -0.2),
            (0.49, 0.1),
            (0.5, 0.2),
            (0.8, 0.1),
            (1.0, 0.0),
            (-1.0, 0.0),
            (2.0, 3.0),
            (-3.0, -1.5),
            (7.0, 0.5),
        ]
    }

    #[test]
    fn normal_integral_matches_quadrature() {
        let (a, b) = (0.5, 0.35);
        for (x, y) in points() {
            let exact = normal_integral(x, y, a, b);
            let numeric = quadrature(|u, v| 1.0 / u.hypot(v), x, y, a, b);
            // 40-point Gauss-Legendre on smooth Duffy integrands; the worst disagreement measured
            // over these points is 8e-14 relative, so 1e-12 leaves a 10x margin.
            assert!(
                (exact - numeric).abs() < 1e-12 * numeric.abs(),
                "at ({x}, {y}): closed form {exact}, quadrature {numeric}"
            );
        }
    }

    #[test]
    fn coupling_integral_matches_quadrature_with_eq9_sign() {
        let (a, b) = (0.5, 0.35);
        for (x, y) in points() {
            let exact = coupling_integral(x, y, a, b);
            let numeric = quadrature(|u, v| u / (u * u + v * v), x, y, a, b);
            assert!(
                (exact - numeric).abs() < 1e-12 * (1.0 + numeric.abs()),
                "at ({x}, {y}): closed form {exact}, quadrature {numeric}"
            );
        }
    }

    #[test]
    fn appendix_a_gxz_is_minus_the_eq9_integral() {
        // The printed Appendix A formula, transcribed literally with single-argument atan.
        let appendix = |x: f64, y: f64, a: f64, b: f64| {
            let sq = |u: f64, v: f64| u * u + v * v;
            (y - b) / 2.0 * (sq(x + a, y - b) / sq(x - a, y - b)).ln()
                + (y + b) / 2.0 * (sq(x - a, y + b) / sq(x + a, y + b)).ln()
                + (x - a) * (((y + b) / (x - a)).atan() - ((y - b) / (x - a)).atan())
                + (x + a) * (((y - b) / (x + a)).atan() - ((y + b) / (x + a)).atan())
        };
        for (x, y) in [(0.3, -0.2), (0.8, 0.1), (2.0, 3.0), (-3.0, -1.5)] {
            let ours = coupling_integral(x, y, 0.5, 0.35);
            assert!((appendix(x, y, 0.5, 0.35) + ours).abs() < 1e-13 * (1.0 + ours.abs()));
        }
    }

    #[test]
    fn the_positive_quadrant_form_equals_the_asinh_form() {
        // Both forms round a handful of operations: measured at most 2.3 ulp apart over
        // the corners of an N = 512 kernel, so 4 ulp of the value bound them.
        for i in -30..=30 {
            for j in -30..=30 {
                let (x, y) = (10f64.powf(i as f64 / 5.0), 10f64.powf(j as f64 / 5.0));
                let (fast, reference) = (
                    normal_antiderivative_positive(x, y),
                    normal_antiderivative(x, y),
                );
                assert!(
                    (fast - reference).abs() <= 4.0 * f64::EPSILON * reference.abs(),
                    "({x}, {y}): {fast} vs {reference}"
                );
            }
        }
    }

    /// The normal kernel's build at N = 256 and 512, medians of 31. Speed is printed, never
    /// asserted: `cargo test --release --lib -- --ignored --nocapture kernel_build_time`.
    #[test]
    #[ignore = "a timing, not a test"]
    fn kernel_build_time() {
        let pair = ElasticPair::new(
            crate::contact::Material::new(210e9, 0.3).expect("valid"),
            crate::contact::Material::new(210e9, 0.3).expect("valid"),
        );
        for n in [256, 512] {
            let grid = Grid::new(n, n, 1e-6, 1e-6).expect("valid");
            let mut times: Vec<f64> = (0..31)
                .map(|_| {
                    let started = std::time::Instant::now();
                    std::hint::black_box(Kernel::normal(&grid, &pair));
                    started.elapsed().as_secs_f64()
                })
                .collect();
            times.sort_by(f64::total_cmp);
            println!("N = {n}: Kernel::normal median {:.2} ms", times[15] * 1e3);
        }
    }

    #[test]
    fn kernel_lattice_equals_pointwise_integrals() {
        let pair = ElasticPair::new(
            crate::contact::Material::new(300e9, 0.21).expect("valid"),
            crate::contact::Material::new(205e9, 0.28).expect("valid"),
        );
        let normal_scale = 1.0 / (std::f64::consts::PI * pair.reduced_modulus_pa);
        let coupling_scale = 0.5 * pair.delta_nu * 0.45
            / (2.0 * std::f64::consts::PI * pair.reduced_shear_modulus_pa);
        // Oblong cells, and square ones (where the normal kernel's corners are mirrored
        // across the diagonal), on grids longer in x and in y.
        for (nx, ny, dx, dy) in [
            (5, 4, 1.0e-6, 1.5e-6),
            (6, 4, 1.0e-6, 1.0e-6),
            (3, 5, 2e-6, 2e-6),
        ] {
            let grid = Grid::new(nx, ny, dx, dy).expect("valid");
            let normal = Kernel::normal(&grid, &pair);
            let coupling = Kernel::coupling(&grid, &pair, 0.45);
            let (a, b) = (0.5 * dx, 0.5 * dy);
            for dj in 1 - ny as isize..ny as isize {
                for di in 1 - nx as isize..nx as isize {
                    let (x, y) = (di as f64 * dx, dj as f64 * dy);
                    let n = normal_scale * normal_integral(x, y, a, b);
                    let c = coupling_scale * coupling_integral(x, y, a, b);
                    // The same integrals, corners grouped differently: round-off only.
                    assert!((normal.value(di, dj) - n).abs() < 1e-13 * n.abs());
                    assert!((coupling.value(di, dj) - c).abs() < 1e-13 * normal_scale * dx);
                }
            }
        }
    }

    #[test]
    fn self_term_of_a_square_cell() {
        // Numerics notes: 4 h ln(1 + sqrt 2) for a square of side h at its own centre.
        let h = 2.0;
        let expected = 4.0 * h * (1.0 + 2f64.sqrt()).ln();
        assert!((normal_integral(0.0, 0.0, 1.0, 1.0) - expected).abs() < 1e-14 * expected);
        assert!(
            coupling_integral(0.0, 0.0, 1.0, 1.0).abs() < 1e-15,
            "odd in x"
        );
    }

    #[test]
    fn far_field_tends_to_point_forces() {
        // Far away the cell acts as a point force of area 4ab: 1/r and X/r^2.
        let (x, y, a, b): (f64, f64, f64, f64) = (300.0, 400.0, 0.5, 0.5);
        let r = x.hypot(y);
        assert!((normal_integral(x, y, a, b) / (1.0 / r) - 1.0).abs() < 1e-5);
        assert!((coupling_integral(x, y, a, b) / (x / (r * r)) - 1.0).abs() < 1e-5);
    }
}
