//! What a figure shows, read off its SVG ([`super::svg`]): its legend entries and what
//! each entry's sample looks like, what lies under the legend, its error bars and its
//! colour bar.

// Each test crate compiles this module on its own and uses a part of it.
#![allow(dead_code)]

use super::svg::{Bounds, Element};

/// How a legend entry's sample is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sample {
    /// One horizontal stroke.
    Line,
    /// Two or more horizontal strokes in a row.
    Dashed,
    /// A filled shape (a triangle or a dot), with or without an error bar.
    Marker,
}

/// A legend entry: its words, where they are, its sample and the sample's colour.
#[derive(Debug, Clone)]
pub struct Entry {
    pub label: String,
    pub sample: Sample,
    pub colour: String,
    /// The indices (into the figure's elements) of the label and of its sample.
    pub parts: Vec<usize>,
}

/// A figure's legend: the frame around it and its entries.
#[derive(Debug, Clone)]
pub struct Legend {
    pub frame: Bounds,
    pub entries: Vec<Entry>,
}

/// How far from a label's anchor a sample may sit: the row's half height and the sample's
/// room before the label, px (the legend draws a 30 px sample 8 px before the label).
const ROW_HALF_PX: f64 = 9.0;
const SAMPLE_ROOM_PX: f64 = 45.0;

/// The legend of `elements` whose entries are `labels`: each label found as a text, the
/// frame the smallest unfilled rectangle holding them all, each sample what lies in the
/// frame on the label's row just before it. Panics when a label or the frame is missing.
pub fn legend(elements: &[Element], labels: &[&str]) -> Legend {
    let anchors: Vec<usize> = labels
        .iter()
        .map(|label| {
            let found: Vec<usize> = (0..elements.len())
                .filter(|&i| elements[i].tag == "text" && elements[i].text == *label)
                .collect();
            assert_eq!(found.len(), 1, "the legend label {label:?} is drawn once");
            found[0]
        })
        .collect();
    let label_box = Bounds::of(
        &anchors
            .iter()
            .flat_map(|&i| elements[i].points())
            .collect::<Vec<_>>(),
    );
    let frame = elements
        .iter()
        .filter(|e| e.tag == "rect" && !e.is_filled() && e.bounds().holds(&label_box))
        .map(Element::bounds)
        .min_by(|a, b| ((a.x1 - a.x0) * (a.y1 - a.y0)).total_cmp(&((b.x1 - b.x0) * (b.y1 - b.y0))))
        .expect("a frame around the legend");
    let entries = anchors
        .iter()
        .zip(labels)
        .map(|(&anchor, label)| entry(elements, &frame, anchor, label))
        .collect();
    Legend { frame, entries }
}

fn entry(elements: &[Element], frame: &Bounds, anchor: usize, label: &str) -> Entry {
    let (x, y) = elements[anchor].points()[0];
    let row = Bounds {
        x0: x - SAMPLE_ROOM_PX,
        y0: y - ROW_HALF_PX,
        x1: x - 1.0,
        y1: y + ROW_HALF_PX,
    };
    let parts: Vec<usize> = (0..elements.len())
        .filter(|&i| elements[i].tag != "text" && elements[i].tag != "rect")
        .filter(|&i| frame.holds(&elements[i].bounds()) && row.holds(&elements[i].bounds()))
        .collect();
    let shapes: Vec<&Element> = parts
        .iter()
        .map(|&i| &elements[i])
        .filter(|e| e.is_filled() && matches!(e.tag.as_str(), "polygon" | "circle"))
        .collect();
    let strokes: Vec<&Element> = parts
        .iter()
        .map(|&i| &elements[i])
        .filter(|e| e.is_horizontal_stroke())
        .collect();
    let (sample, colour) = match (shapes.as_slice(), strokes.len()) {
        ([shape], 0) => (Sample::Marker, shape.colour()),
        ([], 1) => (Sample::Line, strokes[0].colour()),
        ([], n) if n >= 2 => (Sample::Dashed, strokes[0].colour()),
        _ => {
            panic!("the legend entry {label:?} has no sample of one kind: {shapes:?}, {strokes:?}")
        }
    };
    let mut all = parts.clone();
    all.push(anchor);
    Entry {
        label: label.to_owned(),
        sample,
        colour: colour.to_owned(),
        parts: all,
    }
}

impl Legend {
    /// The elements other than the legend's own (its frame, labels and samples) that reach
    /// into its frame: what it hides. The background, the first element, is left out.
    pub fn hidden<'a>(&self, elements: &'a [Element]) -> Vec<&'a Element> {
        let own: Vec<usize> = self
            .entries
            .iter()
            .flat_map(|e| e.parts.iter().copied())
            .collect();
        (1..elements.len())
            .filter(|i| !own.contains(i))
            .map(|i| &elements[i])
            .filter(|e| !(e.tag == "rect" && e.bounds() == self.frame))
            .filter(|e| e.bounds().meets(&self.frame))
            .collect()
    }

    /// The entry labelled `label`.
    pub fn entry(&self, label: &str) -> &Entry {
        self.entries
            .iter()
            .find(|e| e.label == label)
            .unwrap_or_else(|| panic!("no legend entry {label:?}"))
    }

    /// The elements drawn in `entry`'s colour outside the legend: its data.
    pub fn data_of<'a>(&self, elements: &'a [Element], label: &str) -> Vec<&'a Element> {
        let colour = &self.entry(label).colour;
        elements
            .iter()
            .filter(|e| e.tag != "text" && e.colour() == colour)
            .filter(|e| !self.frame.meets(&e.bounds()))
            .collect()
    }
}

/// The plot's area: the extent of its grid lines.
pub fn plot_area(elements: &[Element]) -> Bounds {
    let grid: Vec<(f64, f64)> = elements
        .iter()
        .filter(|e| e.tag == "line")
        .flat_map(Element::points)
        .collect();
    Bounds::of(&grid)
}

/// A colour bar: its bands (bottom first) and its tick labels as (value, y px).
#[derive(Debug, Clone)]
pub struct ColourBar {
    pub bands: Vec<Bounds>,
    pub fills: Vec<String>,
    pub ticks: Vec<(f64, f64)>,
}

/// The colour bar of a map: the tallest column of at least `min_bands` filled rectangles of
/// one x and width, each of its own colour, stacked without gaps (1 px of rounding), and
/// the numbers written just right of it.
pub fn colour_bar(elements: &[Element], min_bands: usize) -> ColourBar {
    let mut columns: std::collections::BTreeMap<(i64, i64), Vec<&Element>> = Default::default();
    for e in elements.iter().filter(|e| e.tag == "rect" && e.is_filled()) {
        let b = e.bounds();
        columns
            .entry((b.x0 as i64, (b.x1 - b.x0) as i64))
            .or_default()
            .push(e);
    }
    let mut column: Vec<&Element> = columns
        .into_values()
        .filter(|c| c.len() >= min_bands)
        .filter(|c| {
            let mut fills: Vec<&str> = c.iter().map(|e| e.colour()).collect();
            fills.sort_unstable();
            fills.dedup();
            fills.len() == c.len()
        })
        .max_by_key(Vec::len)
        .expect("a colour bar: a column of bands of distinct colours");
    column.sort_by(|a, b| b.bounds().y0.total_cmp(&a.bounds().y0));
    let bands: Vec<Bounds> = column.iter().map(|e| e.bounds()).collect();
    for pair in bands.windows(2) {
        assert!(
            (pair[0].y0 - pair[1].y1).abs() <= 1.0,
            "the colour bar has a gap: {pair:?}"
        );
    }
    let whole = Bounds::of(&[
        (bands[0].x0, bands[0].y1),
        (bands[0].x1, bands[bands.len() - 1].y0),
    ]);
    let ticks = elements
        .iter()
        .filter(|e| e.tag == "text")
        .filter_map(|e| Some((e.text.parse::<f64>().ok()?, e.points()[0])))
        .filter(|&(_, (x, y))| {
            x > whole.x1 && x < whole.x1 + 30.0 && y >= whole.y0 - 1.0 && y <= whole.y1 + 1.0
        })
        .map(|(v, (_, y))| (v, y))
        .collect();
    ColourBar {
        fills: column.iter().map(|e| e.colour().to_owned()).collect(),
        bands,
        ticks,
    }
}
