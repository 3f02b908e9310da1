//! The descriptors of `disc.surface`, the disc's initial roughness (see [`super::FIELDS`]).

use crate::scene::field::{Field, Range};
use crate::scene::{MAX_RMS_HEIGHT_UM, MAX_RMS_SLOPE};

/// `disc.surface`.
pub(in crate::scene) const SURFACE: Field = Field {
    path: "disc.surface",
    unit: "",
    range: Range::OptionalObject,
    why: "",
    meaning: "The disc's initial roughness, superposed on its flat (the ball stays smooth); \
              absent or null: smooth, as in the paper. The grid resolves the short cut-off \
              (the result's `surface` model says how, or by how much it falls short).",
    feeds: "the separation h of eqs. 2-3; the real contact area (`contact_area_mm2`)",
};

/// `disc.surface.kind`.
pub(in crate::scene) const SURFACE_KIND: Field = Field {
    path: "disc.surface.kind",
    unit: "",
    range: Range::OneOf(&["synthetic", "measured"]),
    why: "",
    meaning: "`synthetic`: a self-affine surface by Fourier filtering (Jacobs et al., Surf. \
              Topogr. 2017), from the fields below; `measured`: a height map supplied with \
              the scene (`tribosim run --surface FILE`, or uploaded to the service), named \
              by `id`.",
    feeds: "",
};

/// `disc.surface.rms_height_um`.
pub(in crate::scene) const SURFACE_RMS_HEIGHT: Field = Field {
    path: "disc.surface.rms_height_um",
    unit: "um",
    range: Range::Closed(1e-4, MAX_RMS_HEIGHT_UM),
    why: "0.1 nm is below any measured roughness; 100 um is beyond a ball-on-disc contact",
    meaning: "Synthetic: root mean square height about the mean (give it or `rms_slope`).",
    feeds: "the amplitude of the generated surface",
};

/// `disc.surface.rms_slope`.
pub(in crate::scene) const SURFACE_RMS_SLOPE: Field = Field {
    path: "disc.surface.rms_slope",
    unit: "",
    range: Range::Closed(1e-4, MAX_RMS_SLOPE),
    why: "above 1 the small-slope half-space theory of eqs. 5-10 does not hold",
    meaning: "Synthetic: root mean square gradient, by forward differences over the cells \
              (give it or `rms_height_um`).",
    feeds: "the amplitude of the generated surface",
};

/// `disc.surface.hurst`.
pub(in crate::scene) const SURFACE_HURST: Field = Field {
    path: "disc.surface.hurst",
    unit: "",
    range: Range::Closed(0.1, 1.0),
    why: "a self-affine surface has 0 < H <= 1; below 0.1 nearly all of its slope sits at \
          the short cut-off",
    meaning: "Synthetic: Hurst exponent H, the power spectrum C(q) proportional to \
              q^(-2(1+H)) between the cut-offs; 0.8 when absent.",
    feeds: "the spectrum of the generated surface",
};

/// `disc.surface.short_cutoff_um`.
pub(in crate::scene) const SURFACE_SHORT_CUTOFF: Field = Field {
    path: "disc.surface.short_cutoff_um",
    unit: "um",
    range: Range::Closed(1e-3, 10_000.0),
    why: "1 nm is atomic; 10 mm is beyond a ball-on-disc contact",
    meaning: "Synthetic: the shortest wavelength, below `long_cutoff_um`. The grid puts a \
              fixed number of cells across it (the result's `surface` model gives the \
              number, or by how much the grid limit falls short).",
    feeds: "the spectrum of the generated surface; the cell size",
};

/// `disc.surface.long_cutoff_um`.
pub(in crate::scene) const SURFACE_LONG_CUTOFF: Field = Field {
    path: "disc.surface.long_cutoff_um",
    unit: "um",
    range: Range::Closed(1e-3, 10_000.0),
    why: "1 nm is atomic; 10 mm is beyond a ball-on-disc contact",
    meaning: "Synthetic: the longest wavelength. Wavelengths longer than the first grid's \
              side cannot be represented and are left out (the `surface` model says so).",
    feeds: "the spectrum of the generated surface",
};

/// `disc.surface.seed`.
pub(in crate::scene) const SURFACE_SEED: Field = Field {
    path: "disc.surface.seed",
    unit: "",
    range: Range::Whole(0, 1 << 53),
    why: "JSON numbers are exact up to 2^53",
    meaning: "Synthetic: the seed of the random phases, so a run is reproducible; 0 when \
              absent.",
    feeds: "the generated surface",
};

/// `disc.surface.id`.
pub(in crate::scene) const SURFACE_ID: Field = Field {
    path: "disc.surface.id",
    unit: "",
    range: Range::Text(crate::text::NAME_MAX_CHARS),
    why: "a file's name or a stored surface's id",
    meaning: "Measured: the map's name; `tribosim run --surface FILE` sets it to the file's \
              name and supplies the map; on the service, the id `POST /api/v1/surfaces` \
              answered.",
    feeds: "",
};

/// `disc.surface.remove_tilt`.
pub(in crate::scene) const SURFACE_REMOVE_TILT: Field = Field {
    path: "disc.surface.remove_tilt",
    unit: "",
    range: Range::Bool,
    why: "",
    meaning: "Measured: subtract the map's least-squares plane (the sample's tilt on the \
              stage) before use.",
    feeds: "",
};
