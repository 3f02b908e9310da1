//! Reading a figure as a reader sees it: the elements of an SVG that plotters wrote, with
//! where each sits on the picture (px), so that a test can ask what a legend entry looks
//! like, what lies under the legend and what a colour bar says.

// Each test crate compiles this module on its own and uses a part of it.
#![allow(dead_code)]

use std::collections::HashMap;

/// One drawn element: its tag, its attributes and, for a `<text>`, its words.
#[derive(Debug, Clone)]
pub struct Element {
    pub tag: String,
    pub attributes: HashMap<String, String>,
    pub text: String,
}

/// A box on the picture, px (y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Bounds {
    /// The smallest box holding `points`.
    pub fn of(points: &[(f64, f64)]) -> Self {
        points.iter().fold(
            Self {
                x0: f64::INFINITY,
                y0: f64::INFINITY,
                x1: f64::NEG_INFINITY,
                y1: f64::NEG_INFINITY,
            },
            |b, &(x, y)| Self {
                x0: b.x0.min(x),
                y0: b.y0.min(y),
                x1: b.x1.max(x),
                y1: b.y1.max(y),
            },
        )
    }

    /// Whether the two boxes share a point.
    pub fn meets(&self, other: &Self) -> bool {
        self.x0 <= other.x1 && other.x0 <= self.x1 && self.y0 <= other.y1 && other.y0 <= self.y1
    }

    /// Whether `other` lies wholly inside.
    pub fn holds(&self, other: &Self) -> bool {
        self.x0 <= other.x0 && other.x1 <= self.x1 && self.y0 <= other.y0 && other.y1 <= self.y1
    }

    pub fn centre(&self) -> (f64, f64) {
        ((self.x0 + self.x1) / 2.0, (self.y0 + self.y1) / 2.0)
    }
}

/// The drawn elements of `svg`, in order (the root `<svg>` left out).
pub fn parse(svg: &str) -> Vec<Element> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        rest = &rest[start + 1..];
        let end = rest.find('>').expect("every tag closes");
        let tag_text = rest[..end].trim_end_matches('/');
        rest = &rest[end + 1..];
        if tag_text.starts_with('/') || tag_text.starts_with("svg") {
            continue;
        }
        let (tag, attribute_text) = tag_text.split_once(' ').unwrap_or((tag_text, ""));
        let text = if tag == "text" {
            rest[..rest.find("</text>").expect("a text closes")]
                .trim()
                .to_owned()
        } else {
            String::new()
        };
        out.push(Element {
            tag: tag.to_owned(),
            attributes: attributes(attribute_text),
            text,
        });
    }
    out
}

/// `key="value"` pairs.
fn attributes(text: &str) -> HashMap<String, String> {
    let mut out = HashMap::new();
    let mut rest = text;
    while let Some(eq) = rest.find("=\"") {
        let key = rest[..eq].trim().to_owned();
        let value_start = eq + 2;
        let value_end = value_start + rest[value_start..].find('"').expect("a value closes");
        out.insert(key, rest[value_start..value_end].to_owned());
        rest = &rest[value_end + 1..];
    }
    out
}

impl Element {
    /// A numeric attribute.
    pub fn number(&self, key: &str) -> f64 {
        self.attributes
            .get(key)
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("<{}> has no number {key}: {:?}", self.tag, self.attributes))
    }

    /// The colour it is drawn in: its stroke for a line, its fill for a shape or a text.
    pub fn colour(&self) -> &str {
        let key = if matches!(self.tag.as_str(), "polyline" | "line") {
            "stroke"
        } else {
            "fill"
        };
        self.attributes.get(key).map_or("none", String::as_str)
    }

    /// Whether it is drawn filled (a `<rect>`, `<polygon>` or `<circle>` with a fill).
    pub fn is_filled(&self) -> bool {
        self.attributes.get("fill").is_some_and(|f| f != "none")
    }

    /// Its defining points, px: a text's anchor, a shape's corners or vertices.
    pub fn points(&self) -> Vec<(f64, f64)> {
        let n = |k: &str| self.number(k);
        match self.tag.as_str() {
            "polyline" | "polygon" => self.attributes["points"]
                .split_whitespace()
                .map(|pair| {
                    let (x, y) = pair.split_once(',').expect("x,y");
                    (x.parse().expect("x"), y.parse().expect("y"))
                })
                .collect(),
            "line" => vec![(n("x1"), n("y1")), (n("x2"), n("y2"))],
            "rect" => vec![
                (n("x"), n("y")),
                (n("x") + n("width"), n("y") + n("height")),
            ],
            "circle" => vec![
                (n("cx") - n("r"), n("cy") - n("r")),
                (n("cx") + n("r"), n("cy") + n("r")),
            ],
            "text" => vec![(n("x"), n("y"))],
            _ => Vec::new(),
        }
    }

    pub fn bounds(&self) -> Bounds {
        Bounds::of(&self.points())
    }

    /// Whether it is a horizontal stroke (a line sample or a dash). plotters writes whole
    /// pixels, so one of a single height has a height under half a pixel.
    pub fn is_horizontal_stroke(&self) -> bool {
        let b = self.bounds();
        self.tag == "polyline" && b.y1 - b.y0 < 0.5 && b.x1 > b.x0
    }

    /// Whether it is a vertical stroke (an error bar), in whole pixels as above.
    pub fn is_vertical_stroke(&self) -> bool {
        let b = self.bounds();
        self.tag == "polyline" && b.x1 - b.x0 < 0.5
    }
}
