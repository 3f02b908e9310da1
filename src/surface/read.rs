//! The height-map formats labs export, each refused with a typed error when it is not what
//! it claims to be:
//!
//! - Gwyddion Simple Field (`.gsf`, <https://gwyddion.net/documentation/user-guide-en/gsf.html>):
//!   the magic line `Gwyddion Simple Field 1.0`, `name = value` header lines (`XRes`,
//!   `YRes` required; `XReal`, `YReal` the sides in m, required here since a map without a
//!   size cannot be put under a ball; `XYUnits`, `ZUnits` must be `m` when given), one to
//!   four NUL bytes aligning the data to a multiple of 4, then `XRes * YRes` little-endian
//!   f32 heights row by row;
//! - a plain-text matrix of heights in m, one row of the map per line (separated by
//!   spaces, tabs, commas or semicolons; `#` starts a comment line), with the pixel size
//!   given by the caller;
//! - three columns `x y z` in m, one point per line, which must fill a uniform grid exactly
//!   once.
//!
//! Anything else (another binary format, a matrix without its pixel size) is refused.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{HeightMap, MAX_MAP_SIDE, SurfaceError};

const GSF_MAGIC: &[u8] = b"Gwyddion Simple Field 1.0\n";

/// The largest file read: a full-size text matrix (4096^2 heights at about 15 characters
/// each is 250 MB) fits.
const MAX_FILE_BYTES: u64 = 256 << 20;

/// The smallest pixel side read, m: below an atom's size no instrument measures.
pub const MIN_PIXEL_M: f64 = 1e-12;

/// The largest pixel side read, m: a centimetre, beyond which a map's pixel is wider than
/// any ball-on-disc contact, and whose statistics in um (the pixel squared, the spectrum's
/// wavevectors) stay finite numbers JSON can hold.
pub const MAX_PIXEL_M: f64 = 1e-2;

/// Relative tolerance on the spacing of XYZ points: coordinates printed with 7 significant
/// digits (Gwyddion's default) err by up to 5e-7 of their value.
const SPACING_TOLERANCE: f64 = 1e-5;

/// The format a map was read from, named in JSON as `gsf`, `matrix`, `xyz`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Format {
    /// Gwyddion Simple Field.
    Gsf,
    /// A plain-text matrix with the pixel size given.
    Matrix,
    /// Three columns x y z.
    Xyz,
}

/// Reads the file at `path` (see [`read`]).
pub fn read_file(path: &Path, pixel_m: Option<f64>) -> Result<(HeightMap, Format), SurfaceError> {
    let io = |e: std::io::Error| SurfaceError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    let size = std::fs::metadata(path).map_err(io)?.len();
    if size > MAX_FILE_BYTES {
        return Err(SurfaceError::Invalid(format!(
            "{} is {size} bytes; at most {MAX_FILE_BYTES}",
            path.display()
        )));
    }
    read(&std::fs::read(path).map_err(io)?, pixel_m)
}

/// A map from the bytes of a file: `.gsf` by its magic line; otherwise text, a matrix when
/// `pixel_m` (the square pixel's side, m) is given, else three columns x y z.
pub fn read(bytes: &[u8], pixel_m: Option<f64>) -> Result<(HeightMap, Format), SurfaceError> {
    if let Some(rest) = bytes.strip_prefix(GSF_MAGIC) {
        return read_gsf(rest).map(|m| (m, Format::Gsf));
    }
    let text = std::str::from_utf8(bytes).map_err(|_| {
        SurfaceError::UnknownFormat(
            "binary data without the Gwyddion Simple Field magic line".into(),
        )
    })?;
    match pixel_m {
        Some(pixel) => read_matrix(text, pixel).map(|m| (m, Format::Matrix)),
        None => read_xyz(text).map(|m| (m, Format::Xyz)),
    }
}

/// A map from the bytes of a file said to be in `format` (the caller knows it, so the
/// content does not have to tell): a matrix needs `pixel_m`, the others ignore it.
pub fn read_as(
    bytes: &[u8],
    format: Format,
    pixel_m: Option<f64>,
) -> Result<HeightMap, SurfaceError> {
    if format == Format::Gsf {
        let rest = bytes
            .strip_prefix(GSF_MAGIC)
            .ok_or_else(|| SurfaceError::Malformed {
                line: 1,
                message: "a .gsf file starts with the line `Gwyddion Simple Field 1.0`".to_owned(),
            })?;
        return read_gsf(rest);
    }
    let text = std::str::from_utf8(bytes).map_err(|e| SurfaceError::Malformed {
        line: 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count(),
        message: "not UTF-8 text".to_owned(),
    })?;
    match (format, pixel_m) {
        (Format::Matrix, Some(pixel)) => read_matrix(text, pixel),
        (Format::Matrix, None) => Err(SurfaceError::Invalid(
            "a plain-text matrix needs its pixel size".to_owned(),
        )),
        _ => read_xyz(text),
    }
}

/// How many pixels the bytes of a file declare, read without parsing a height: a `.gsf`'s
/// `XRes * YRes`, a matrix's data lines times the fields of its first, XYZ's data lines. The
/// format is told as [`read`] and [`read_as`] tell it. A caller bounds its memory by this
/// before reading the map (a map costs tens of bytes per pixel while it is read and its
/// statistics are taken); the count is an upper bound for a map that then reads.
pub fn declared_pixels(
    bytes: &[u8],
    format: Option<Format>,
    pixel_m: Option<f64>,
) -> Result<u64, SurfaceError> {
    if let Some(rest) = bytes.strip_prefix(GSF_MAGIC) {
        let (header, _) = gsf_header(rest)?;
        let res = |name: &str| {
            header
                .get(name)
                .and_then(|value| value.parse::<u64>().ok())
                .unwrap_or(0)
        };
        return Ok(res("XRes").saturating_mul(res("YRes")));
    }
    let matrix = format == Some(Format::Matrix) || (format.is_none() && pixel_m.is_some());
    let mut lines = bytes
        .split(|&b| b == b'\n')
        .map(<[u8]>::trim_ascii)
        .filter(|line| !line.is_empty() && !line.starts_with(b"#"));
    if !matrix {
        return Ok(lines.count() as u64);
    }
    let Some(first) = lines.next() else {
        return Ok(0);
    };
    let fields = first
        .split(|&b| b.is_ascii_whitespace() || b == b',' || b == b';')
        .filter(|field| !field.is_empty())
        .count() as u64;
    Ok(fields.saturating_mul(1 + lines.count() as u64))
}

/// Refuses a pixel outside [[`MIN_PIXEL_M`], [`MAX_PIXEL_M`]] (or not a number).
fn check_pixel(dx_m: f64, dy_m: f64) -> Result<(), SurfaceError> {
    let within = |side: f64| (MIN_PIXEL_M..=MAX_PIXEL_M).contains(&side);
    if within(dx_m) && within(dy_m) {
        return Ok(());
    }
    Err(SurfaceError::Invalid(format!(
        "the pixel is {dx_m:e} x {dy_m:e} m; a pixel's side must be between \
         {MIN_PIXEL_M:e} and {MAX_PIXEL_M:e} m"
    )))
}

/// The numbered data lines of `text` as fields, without blank and `#` comment lines.
fn data_lines(text: &str) -> impl Iterator<Item = (usize, Vec<&str>)> {
    text.lines().enumerate().filter_map(|(i, line)| {
        let line = line.trim();
        (!line.is_empty() && !line.starts_with('#')).then(|| {
            let fields = line
                .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
                .filter(|f| !f.is_empty())
                .collect();
            (i + 1, fields)
        })
    })
}

/// A number of a text file; a word where a number should be is malformed.
fn number(field: &str, line: usize) -> Result<f64, SurfaceError> {
    field.parse::<f64>().map_err(|_| SurfaceError::Malformed {
        line,
        message: format!("`{field}` is not a number"),
    })
}

fn read_matrix(text: &str, pixel_m: f64) -> Result<HeightMap, SurfaceError> {
    check_pixel(pixel_m, pixel_m)?;
    let mut heights = Vec::new();
    let (mut nx, mut ny) = (0, 0);
    for (line, fields) in data_lines(text) {
        if ny == 0 {
            nx = fields.len();
        } else if fields.len() != nx {
            return Err(SurfaceError::Malformed {
                line,
                message: format!(
                    "{} heights where the first row has {nx}: a missing height must be \
                     filled (or the map cropped) before it is read",
                    fields.len()
                ),
            });
        }
        if nx > MAX_MAP_SIDE || ny >= MAX_MAP_SIDE {
            return Err(SurfaceError::TooLarge { nx, ny: ny + 1 });
        }
        for field in fields {
            heights.push(number(field, line)?);
        }
        ny += 1;
    }
    HeightMap::new(nx, ny, pixel_m, pixel_m, heights)
}

/// The distinct values of `values` (sorted) and their uniform spacing, or why not uniform.
fn uniform_axis(values: &mut Vec<f64>, axis: &str) -> Result<f64, SurfaceError> {
    values.sort_by(f64::total_cmp);
    let span = values.last().copied().unwrap_or(0.0) - values.first().copied().unwrap_or(0.0);
    // Coordinates closer than the tolerance are one grid line.
    values.dedup_by(|a, b| (*a - *b).abs() <= SPACING_TOLERANCE * span);
    if values.len() < 2 {
        return Err(SurfaceError::NonUniform(format!("a single {axis} value")));
    }
    let step = span / (values.len() - 1) as f64;
    for (i, &v) in values.iter().enumerate() {
        let want = values[0] + i as f64 * step;
        if (v - want).abs() > SPACING_TOLERANCE * span {
            return Err(SurfaceError::NonUniform(format!(
                "{axis} = {v:e} m where a spacing of {step:e} m puts {want:e} m"
            )));
        }
    }
    Ok(step)
}

fn read_xyz(text: &str) -> Result<HeightMap, SurfaceError> {
    let mut points = Vec::new();
    for (line, fields) in data_lines(text) {
        if fields.len() != 3 {
            return Err(SurfaceError::UnknownFormat(format!(
                "line {line} has {} columns; three columns are x y z, and a matrix needs \
                 its pixel size",
                fields.len()
            )));
        }
        let xyz = [
            number(fields[0], line)?,
            number(fields[1], line)?,
            number(fields[2], line)?,
        ];
        if !(xyz[0].is_finite() && xyz[1].is_finite()) {
            return Err(SurfaceError::Malformed {
                line,
                message: "x and y must be finite".to_owned(),
            });
        }
        points.push((line, xyz));
        if points.len() > MAX_MAP_SIDE * MAX_MAP_SIDE {
            return Err(SurfaceError::TooLarge {
                nx: MAX_MAP_SIDE + 1,
                ny: MAX_MAP_SIDE,
            });
        }
    }
    let mut xs: Vec<f64> = points.iter().map(|p| p.1[0]).collect();
    let mut ys: Vec<f64> = points.iter().map(|p| p.1[1]).collect();
    let dx = uniform_axis(&mut xs, "x")?;
    let dy = uniform_axis(&mut ys, "y")?;
    let (nx, ny) = (xs.len(), ys.len());
    if nx > MAX_MAP_SIDE || ny > MAX_MAP_SIDE {
        return Err(SurfaceError::TooLarge { nx, ny });
    }
    let mut cells: BTreeMap<usize, f64> = BTreeMap::new();
    for &(line, [x, y, z]) in &points {
        let ix = ((x - xs[0]) / dx).round() as usize;
        let iy = ((y - ys[0]) / dy).round() as usize;
        if cells.insert(iy * nx + ix, z).is_some() {
            return Err(SurfaceError::NonUniform(format!(
                "line {line} gives the point ({x:e}, {y:e}) m a second time"
            )));
        }
    }
    if cells.len() != nx * ny {
        let missing = (0..nx * ny).find(|i| !cells.contains_key(i)).unwrap_or(0);
        return Err(SurfaceError::NonFinite {
            column: missing % nx,
            row: missing / nx,
            value: "missing".to_owned(),
        });
    }
    check_pixel(dx, dy)?;
    HeightMap::new(nx, ny, dx, dy, cells.into_values().collect())
}

/// The header values of a `.gsf` file after the magic line, and the data's offset in
/// `rest`.
fn gsf_header(rest: &[u8]) -> Result<(BTreeMap<String, String>, usize), SurfaceError> {
    let end = rest
        .iter()
        .position(|&b| b == 0)
        .ok_or(SurfaceError::Malformed {
            line: 0,
            message: "the header has no NUL terminator".to_owned(),
        })?;
    let text = std::str::from_utf8(&rest[..end]).map_err(|_| SurfaceError::Malformed {
        line: 0,
        message: "the header is not UTF-8 text".to_owned(),
    })?;
    let mut header = BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let (name, value) = line
            .split_once('=')
            .ok_or_else(|| SurfaceError::Malformed {
                line: i + 2,
                message: format!("`{line}` is not `name = value`"),
            })?;
        header.insert(name.trim().to_owned(), value.trim().to_owned());
    }
    // The data starts at the next multiple of 4 after at least one NUL, counted from the
    // start of the file.
    let header_len = GSF_MAGIC.len() + end;
    let data_start = (header_len / 4 + 1) * 4 - GSF_MAGIC.len();
    Ok((header, data_start))
}

fn read_gsf(rest: &[u8]) -> Result<HeightMap, SurfaceError> {
    let (header, start) = gsf_header(rest)?;
    let malformed = |message: String| SurfaceError::Malformed { line: 0, message };
    let get = |name: &str| {
        header
            .get(name)
            .ok_or_else(|| malformed(format!("the header has no `{name}`")))
    };
    let res = |name: &str| {
        get(name)?
            .parse::<usize>()
            .map_err(|_| malformed(format!("`{name}` must be a whole number")))
    };
    let real = |name: &str| {
        get(name)?
            .parse::<f64>()
            .map_err(|_| malformed(format!("`{name}` must be a number (m)")))
    };
    for units in ["XYUnits", "ZUnits"] {
        if let Some(u) = header.get(units).filter(|u| u.as_str() != "m") {
            return Err(malformed(format!(
                "`{units} = {u}`: heights and sides must be in m"
            )));
        }
    }
    let (nx, ny) = (res("XRes")?, res("YRes")?);
    if nx > MAX_MAP_SIDE || ny > MAX_MAP_SIDE {
        return Err(SurfaceError::TooLarge { nx, ny });
    }
    let (width, height) = (real("XReal")?, real("YReal")?);
    check_pixel(width / nx as f64, height / ny as f64)?;
    let data = rest.get(start..).unwrap_or_default();
    if data.len() != 4 * nx * ny {
        return Err(malformed(format!(
            "{} bytes of data for {nx} x {ny} f32 heights ({} bytes)",
            data.len(),
            4 * nx * ny
        )));
    }
    let heights = data
        .chunks_exact(4)
        .map(|b| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])))
        .collect();
    HeightMap::new(nx, ny, width / nx as f64, height / ny as f64, heights)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `.gsf` file of `map` as the format's specification lays it out.
    pub(crate) fn gsf_bytes(map: &HeightMap) -> Vec<u8> {
        let mut bytes = GSF_MAGIC.to_vec();
        let header = format!(
            "XRes = {}\nYRes = {}\nXReal = {:e}\nYReal = {:e}\nXYUnits = m\nZUnits = m\n",
            map.nx,
            map.ny,
            map.width_m(),
            map.height_side_m()
        );
        bytes.extend_from_slice(header.as_bytes());
        let padding = 4 - bytes.len() % 4;
        bytes.extend(std::iter::repeat_n(0u8, padding));
        for &h in &map.heights_m {
            bytes.extend_from_slice(&(h as f32).to_le_bytes());
        }
        bytes
    }

    fn sample() -> HeightMap {
        let heights = (0..12).map(|i| (i as f64 * 0.37).sin() * 1e-7).collect();
        HeightMap::new(4, 3, 2e-7, 2e-7, heights).expect("valid")
    }

    #[test]
    fn each_format_round_trips() {
        let map = sample();
        let (gsf, format) = read(&gsf_bytes(&map), None).expect("a .gsf");
        assert_eq!(format, Format::Gsf);
        assert_eq!((gsf.nx, gsf.ny), (4, 3));
        // f32 keeps 24 bits: a relative 6e-8 of each height, and of the pixel's size.
        for (a, b) in gsf.heights_m.iter().zip(&map.heights_m) {
            assert!((a - b).abs() <= 6e-8 * b.abs(), "{a} {b}");
        }
        assert!((gsf.dx_m / map.dx_m - 1.0).abs() < 1e-12);

        let rows: Vec<String> = map
            .heights_m
            .chunks(4)
            .map(|r| {
                r.iter()
                    .map(|h| format!("{h:e}"))
                    .collect::<Vec<_>>()
                    .join("\t")
            })
            .collect();
        let text = format!("# heights in m\n{}\n", rows.join("\n"));
        let (matrix, format) = read(text.as_bytes(), Some(2e-7)).expect("a matrix");
        assert_eq!(format, Format::Matrix);
        assert_eq!(matrix, map);

        let mut xyz = String::new();
        for (i, h) in map.heights_m.iter().enumerate() {
            let (x, y) = ((i % 4) as f64 * 2e-7, (i / 4) as f64 * 2e-7);
            xyz.push_str(&format!("{x:.7e} {y:.7e} {h:e}\n"));
        }
        let (points, format) = read(xyz.as_bytes(), None).expect("x y z");
        assert_eq!(format, Format::Xyz);
        assert_eq!(points.heights_m, map.heights_m);
        assert!((points.dy_m / 2e-7 - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_format_given_is_held_to() {
        let map = sample();
        let gsf = gsf_bytes(&map);
        assert_eq!(
            read_as(&gsf, Format::Gsf, None),
            read(&gsf, None).map(|r| r.0)
        );
        assert!(matches!(
            read_as(b"0 0\n0 0\n", Format::Gsf, None),
            Err(SurfaceError::Malformed { line: 1, .. })
        ));
        assert!(matches!(
            read_as(b"0 0\n0 0\n", Format::Matrix, None),
            Err(SurfaceError::Invalid(_))
        ));
        // Three columns read as a matrix when it is said to be one.
        let matrix = read_as(
            b"1e-7 2e-7 3e-7\n4e-7 5e-7 6e-7\n",
            Format::Matrix,
            Some(1e-6),
        );
        assert_eq!(matrix.map(|m| (m.nx, m.ny)), Ok((3, 2)));
        assert!(matches!(
            read_as(b"0 0\n\xff\n", Format::Xyz, None),
            Err(SurfaceError::Malformed { line: 2, .. })
        ));
    }

    #[test]
    fn the_declared_pixels_are_counted_without_reading_a_height() {
        let map = sample();
        assert_eq!(declared_pixels(&gsf_bytes(&map), None, None), Ok(12));
        let matrix = b"# heights\n1 2 3\n\n4;5;6\n7,8\n";
        // An upper bound: the ragged last row is the reader's to refuse.
        assert_eq!(declared_pixels(matrix, None, Some(1e-6)), Ok(9));
        assert_eq!(
            declared_pixels(matrix, Some(Format::Matrix), Some(1e-6)),
            Ok(9)
        );
        assert_eq!(declared_pixels(b"0 0 1\n1 0 1\n# c\n", None, None), Ok(2));
        let mut header = GSF_MAGIC.to_vec();
        header.extend_from_slice(b"XRes = 100000\nYRes = 100000\n\0\0\0");
        assert_eq!(declared_pixels(&header, None, None), Ok(10_000_000_000));
    }

    #[test]
    fn refusals_name_the_problem() {
        let err = |bytes: &[u8], pixel| read(bytes, pixel).expect_err("refused");
        assert!(matches!(
            err(b"\x89PNG\r\n\x1a\n\xff", None),
            SurfaceError::UnknownFormat(_)
        ));
        assert!(matches!(
            err(b"1 2 3 4\n5 6 7 8\n", None),
            SurfaceError::UnknownFormat(_)
        ));
        assert_eq!(
            err(b"1 2\n3 NaN\n", Some(1e-6)),
            SurfaceError::NonFinite {
                column: 1,
                row: 1,
                value: "NaN".to_owned()
            }
        );
        assert!(matches!(
            err(b"1 2 3\n4 5\n", Some(1e-6)),
            SurfaceError::Malformed { line: 2, .. }
        ));
        assert!(matches!(
            err(b"1 x\n", Some(1e-6)),
            SurfaceError::Malformed { line: 1, .. }
        ));
        let uneven = b"0 0 1\n1 0 1\n3 0 1\n0 1 1\n1 1 1\n3 1 1\n";
        assert!(matches!(err(uneven, None), SurfaceError::NonUniform(_)));
        let hole = b"0 0 1\n1 0 1\n0 1 1\n";
        assert!(matches!(
            err(hole, None),
            SurfaceError::NonFinite {
                column: 1,
                row: 1,
                ..
            }
        ));
        let mut short = gsf_bytes(&sample());
        short.truncate(short.len() - 4);
        assert!(matches!(err(&short, None), SurfaceError::Malformed { .. }));
        for pixel in [1e308, 0.02, 1e-13, f64::NAN] {
            let refused = err(b"1 2\n3 4\n", Some(pixel));
            assert!(refused.to_string().contains("pixel's side"), "{refused}");
        }
        let mut absurd = sample();
        absurd.dx_m = 1e300;
        absurd.dy_m = 1e300;
        let refused = err(&gsf_bytes(&absurd), None);
        assert!(refused.to_string().contains("pixel's side"), "{refused}");
        let wide = format!("{}\n", vec!["0"; MAX_MAP_SIDE + 1].join(" "));
        assert!(matches!(
            err(wide.as_bytes(), Some(1e-6)),
            SurfaceError::TooLarge { .. }
        ));
    }
}
