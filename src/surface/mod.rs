//! Rough and measured disc surfaces: a height map ([`HeightMap`]), the synthetic self-affine
//! surfaces of Fourier filtering ([`SelfAffine`]), the formats labs export ([`read()`]), the
//! statistics a result reports ([`Statistics`]) and the contact islands of a solved contact
//! ([`count_islands`]). Plain code in SI units; nothing else of the crate is used.
//!
//! A map is placed with its centre on the ball's apex and repeats periodically beyond its
//! sides: [`HeightMap::height_at`] samples it bilinearly anywhere, which is how the
//! simulation puts it on the contact grid's cell centres.

mod islands;
mod read;
mod spectrum;
mod spikes;
mod statistics;
mod synthetic;
mod unit;

use thiserror::Error;

pub use islands::count_islands;
pub use read::{Format, MAX_PIXEL_M, MIN_PIXEL_M, declared_pixels, read, read_as, read_file};
pub use spikes::SPIKE_RMS;
pub use statistics::{
    PsdFit, Statistics, measured_fit_range, psd_fit, psd_slope, rms_height, rms_slope,
};
pub use synthetic::{Roughness, SelfAffine};
pub use unit::HeightUnit;

/// The most pixels per side of a map: twice the contact grid's largest side (2048), so a
/// map finer than the finest grid can still be read; 4096^2 heights are 128 MiB in f64.
pub const MAX_MAP_SIDE: usize = 4096;

/// Why a surface could not be read or generated. Each names the problem and where it is.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SurfaceError {
    /// Not one of the formats read here.
    #[error(
        "not a surface format read here ({0}); give a Gwyddion .gsf file, a plain-text matrix \
         of heights in m with its pixel size, or three columns x y z in m"
    )]
    UnknownFormat(String),
    /// A header, a line or a number that cannot be read.
    #[error("line {line}: {message}")]
    Malformed {
        /// Line number, from 1 (0 for the binary part of a file).
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// A height missing or not a finite number.
    #[error("height at column {column}, row {row} is {value}: every height must be finite")]
    NonFinite {
        /// Column, from 0.
        column: usize,
        /// Row, from 0.
        row: usize,
        /// The value read, in words.
        value: String,
    },
    /// Points not on a uniform grid (XYZ).
    #[error("the points are not on a uniform grid: {0}")]
    NonUniform(String),
    /// Too many pixels.
    #[error("the map is {nx} x {ny} pixels; at most {MAX_MAP_SIDE} per side")]
    TooLarge {
        /// Pixels along x.
        nx: usize,
        /// Pixels along y.
        ny: usize,
    },
    /// Too few pixels for a surface.
    #[error("the map is {nx} x {ny} pixels; at least 2 per side")]
    TooSmall {
        /// Pixels along x.
        nx: usize,
        /// Pixels along y.
        ny: usize,
    },
    /// A single pixel standing far above or below all its neighbours: a measurement
    /// artefact that would carry the ball alone.
    #[error(
        "height at column {column}, row {row} stands {excess:.3} um {side} every neighbour, \
         {times:.0} times the map's rms height {rms:.4} um (pixels standing out that far: \
         {count}): a single-pixel spike is a measurement artefact and would carry the load \
         alone; remove the spikes (e.g. Gwyddion's Correct Data > Remove Spots, or Mask of \
         Outliers) and read the map again",
        excess = excess_m.abs() * 1e6,
        side = if *excess_m > 0.0 { "above" } else { "below" },
        times = excess_m.abs() / rms_m,
        rms = rms_m * 1e6
    )]
    Spike {
        /// Column of the tallest spike, from 0.
        column: usize,
        /// Row, from 0.
        row: usize,
        /// How far it stands above its highest neighbour (below its lowest if negative), m.
        excess_m: f64,
        /// The map's rms height, m.
        rms_m: f64,
        /// Pixels that stand out as far.
        count: usize,
    },
    /// A pixel size or a generator setting out of range.
    #[error("{0}")]
    Invalid(String),
    /// The file could not be read.
    #[error("reading {path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The system's message.
        message: String,
    },
}

/// Heights over a regular grid of pixels, row-major with x fastest like the contact grid.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    /// Pixels along x.
    pub nx: usize,
    /// Pixels along y.
    pub ny: usize,
    /// Pixel size along x, m.
    pub dx_m: f64,
    /// Pixel size along y, m.
    pub dy_m: f64,
    /// Height of each pixel, m (positive out of the disc, towards the ball).
    pub heights_m: Vec<f64>,
    /// Whether the map is one period of a periodic surface (a synthetic one), so its
    /// slopes and spectrum wrap around its edges.
    pub periodic: bool,
}

impl HeightMap {
    /// A map of `heights_m` (`nx * ny`, row-major), refusing sizes, pixels and heights the
    /// simulation cannot use, single-pixel spikes included (see [`SPIKE_RMS`]).
    pub fn new(
        nx: usize,
        ny: usize,
        dx_m: f64,
        dy_m: f64,
        heights_m: Vec<f64>,
    ) -> Result<Self, SurfaceError> {
        if nx > MAX_MAP_SIDE || ny > MAX_MAP_SIDE {
            return Err(SurfaceError::TooLarge { nx, ny });
        }
        if nx < 2 || ny < 2 {
            return Err(SurfaceError::TooSmall { nx, ny });
        }
        if !(dx_m > 0.0 && dx_m.is_finite() && dy_m > 0.0 && dy_m.is_finite()) {
            return Err(SurfaceError::Invalid(format!(
                "pixel size {dx_m} x {dy_m} m: must be finite and > 0"
            )));
        }
        if heights_m.len() != nx * ny {
            return Err(SurfaceError::Invalid(format!(
                "{} heights for {nx} x {ny} pixels",
                heights_m.len()
            )));
        }
        if let Some(i) = heights_m.iter().position(|h| !h.is_finite()) {
            return Err(SurfaceError::NonFinite {
                column: i % nx,
                row: i / nx,
                value: heights_m[i].to_string(),
            });
        }
        let map = Self {
            nx,
            ny,
            dx_m,
            dy_m,
            heights_m,
            periodic: false,
        };
        spikes::refuse_spikes(&map)?;
        Ok(map)
    }

    /// Side along x, m.
    pub fn width_m(&self) -> f64 {
        self.nx as f64 * self.dx_m
    }

    /// Side along y, m.
    pub fn height_side_m(&self) -> f64 {
        self.ny as f64 * self.dy_m
    }

    /// The map less its least-squares plane `a + b x + c y` (tilt removal): a measured map
    /// carries the tilt of the sample on the stage, which no contact should see.
    pub fn without_tilt(&self) -> Self {
        // Over pixel indices centred on the map the three normal equations decouple:
        // sum x = sum y = sum x y = 0.
        let cx = (self.nx as f64 - 1.0) / 2.0;
        let cy = (self.ny as f64 - 1.0) / 2.0;
        let (mut sum, mut sum_x, mut sum_y, mut xx, mut yy) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (i, &h) in self.heights_m.iter().enumerate() {
            let x = (i % self.nx) as f64 - cx;
            let y = (i / self.nx) as f64 - cy;
            sum += h;
            sum_x += h * x;
            sum_y += h * y;
            xx += x * x;
            yy += y * y;
        }
        let a = sum / self.heights_m.len() as f64;
        let (b, c) = (sum_x / xx, sum_y / yy);
        let heights_m = self
            .heights_m
            .iter()
            .enumerate()
            .map(|(i, &h)| {
                h - a - b * ((i % self.nx) as f64 - cx) - c * ((i / self.nx) as f64 - cy)
            })
            .collect();
        Self {
            heights_m,
            ..self.clone()
        }
    }

    /// The height at `(x_m, y_m)`, the map centred on the origin and repeated periodically:
    /// bilinear between the four nearest pixel centres. Sampling at cells coarser than the
    /// pixels keeps one value per cell and drops the wavelengths shorter than two cells
    /// (the simulation reports when its grid is that coarse).
    pub fn height_at(&self, x_m: f64, y_m: f64) -> f64 {
        // Pixel centre i sits at (i + 0.5 - n / 2) d, as the contact grid's cells do.
        let fx = x_m / self.dx_m + self.nx as f64 / 2.0 - 0.5;
        let fy = y_m / self.dy_m + self.ny as f64 / 2.0 - 0.5;
        let (x0, tx) = (fx.floor(), fx - fx.floor());
        let (y0, ty) = (fy.floor(), fy - fy.floor());
        let at = |ix: f64, iy: f64| {
            let ix = (ix as i64).rem_euclid(self.nx as i64) as usize;
            let iy = (iy as i64).rem_euclid(self.ny as i64) as usize;
            self.heights_m[iy * self.nx + ix]
        };
        let bottom = at(x0, y0) * (1.0 - tx) + at(x0 + 1.0, y0) * tx;
        let top = at(x0, y0 + 1.0) * (1.0 - tx) + at(x0 + 1.0, y0 + 1.0) * tx;
        bottom * (1.0 - ty) + top * ty
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(nx: usize, ny: usize, f: impl Fn(usize, usize) -> f64) -> HeightMap {
        let heights = (0..nx * ny).map(|i| f(i % nx, i / nx)).collect();
        HeightMap::new(nx, ny, 1e-6, 2e-6, heights).expect("valid map")
    }

    #[test]
    fn refuses_what_the_simulation_cannot_use() {
        let nan = HeightMap::new(2, 2, 1e-6, 1e-6, vec![0.0, 1.0, f64::NAN, 0.0]);
        assert_eq!(
            nan,
            Err(SurfaceError::NonFinite {
                column: 0,
                row: 1,
                value: "NaN".to_owned()
            })
        );
        let big = HeightMap::new(MAX_MAP_SIDE + 1, 2, 1e-6, 1e-6, Vec::new());
        assert!(matches!(big, Err(SurfaceError::TooLarge { .. })));
        assert!(matches!(
            HeightMap::new(2, 2, 0.0, 1e-6, vec![0.0; 4]),
            Err(SurfaceError::Invalid(_))
        ));
    }

    #[test]
    fn tilt_removal_leaves_what_a_plane_cannot_explain() {
        let bump = |ix: usize, iy: usize| if (ix, iy) == (3, 2) { 1e-6 } else { 0.0 };
        let tilted = map(8, 6, |ix, iy| 5e-6 + 2e-7 * ix as f64 - 3e-7 * iy as f64);
        let flat = tilted.without_tilt();
        // The plane is exact: only round-off of sums of 48 terms of 1e-6 remains.
        assert!(flat.heights_m.iter().all(|h| h.abs() < 1e-20), "{flat:?}");
        let plane_and_bump = map(8, 6, |ix, iy| 2e-7 * ix as f64 + bump(ix, iy));
        let kept = plane_and_bump.without_tilt();
        let (max, min) = kept
            .heights_m
            .iter()
            .fold((f64::MIN, f64::MAX), |(a, b), &h| (a.max(h), b.min(h)));
        // The bump stays the highest point, less its own share of the fitted plane.
        assert!(max - min > 0.9e-6 && max - min < 1.1e-6, "{max} {min}");
    }

    #[test]
    fn bilinear_sampling_hits_pixel_centres_and_wraps() {
        let m = map(4, 4, |ix, iy| (ix + 10 * iy) as f64);
        // Pixel (1, 2)'s centre: x = (1 + 0.5 - 2) 1 um, y = (2 + 0.5 - 2) 2 um.
        assert!((m.height_at(-0.5e-6, 1e-6) - 21.0).abs() < 1e-9);
        // Half way between pixels (1, 2) and (2, 2).
        assert!((m.height_at(0.0, 1e-6) - 21.5).abs() < 1e-9);
        // One period further along x is the same point.
        assert!((m.height_at(-0.5e-6 + 4e-6, 1e-6) - 21.0).abs() < 1e-9);
    }
}
