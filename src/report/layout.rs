//! Where the report's SVG text goes, and the check that it fits.
//!
//! Text extents are estimated from per-character widths a little wider than DejaVu Sans
//! (the usual `sans-serif` on Linux, wider than Helvetica or Arial), so a label laid out
//! here does not grow past its box in a browser. A [`Canvas`] collects the elements of one
//! chart, remembers every label's box and sizes its `viewBox` to everything drawn, so nothing
//! is clipped; [`layout_problems`] reads an SVG back and names any text that leaves the
//! `viewBox` or overlaps another (the tests run it over every chart of a report, and
//! measure the same in Chromium with the real font).

use std::fmt::Write;

/// Escapes text for HTML.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The report's font size, px.
pub const FONT: f64 = 11.0;
/// Height above the baseline and depth below it of a line of text, in ems (DejaVu Sans:
/// 0.928 and 0.236).
const ASCENT: f64 = 0.95;
const DESCENT: f64 = 0.25;
/// Baseline-to-baseline distance of stacked lines at [`FONT`].
pub const LINE: f64 = 14.0;

/// Estimated advance width of `s` in px at font size `size`.
pub fn text_width(s: &str, size: f64, bold: bool) -> f64 {
    let ems: f64 = s
        .chars()
        .map(|c| match c {
            'i' | 'l' | 'j' | '.' | ',' | ':' | ';' | '\'' | '|' | '!' | ' ' => 0.34,
            'f' | 't' | 'r' | 'I' | '(' | ')' | '[' | ']' | '-' | '/' => 0.46,
            'm' | 'w' | 'M' | 'W' | '%' => 1.0,
            '_' => 0.52,
            '0'..='9' | 'a'..='z' => 0.65,
            'A'..='Z' => 0.8,
            '=' | '+' | '<' | '>' | '~' | '→' | '−' | '×' | '÷' | '≤' | '≥' | '±' => {
                0.86
            }
            c if c.is_ascii() => 0.66,
            _ => 0.82,
        })
        .sum();
    ems * size * if bold { 1.1 } else { 1.0 }
}

/// `text` broken at spaces into lines no wider than `max_width` (a word wider than that
/// gets a line of its own).
pub fn wrap(text: &str, max_width: f64, size: f64, bold: bool) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        match lines.last_mut() {
            Some(l) if text_width(&format!("{l} {word}"), size, bold) <= max_width => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Where a label's `x` is along its text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

impl Anchor {
    fn name(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// A line of text: baseline point, anchor, size, weight, and whether it reads upwards
/// (rotated −90° about its point, as a y-axis label).
#[derive(Clone, Debug)]
pub struct Label {
    pub x: f64,
    pub y: f64,
    pub text: String,
    pub anchor: Anchor,
    pub size: f64,
    pub bold: bool,
    pub vertical: bool,
}

impl Label {
    /// A plain horizontal label at [`FONT`].
    pub fn new(x: f64, y: f64, anchor: Anchor, text: impl Into<String>) -> Label {
        Label {
            x,
            y,
            text: text.into(),
            anchor,
            size: FONT,
            bold: false,
            vertical: false,
        }
    }

    pub fn bold(mut self) -> Label {
        self.bold = true;
        self
    }

    pub fn vertical(mut self) -> Label {
        self.vertical = true;
        self
    }

    /// The box the label's glyphs occupy.
    pub fn bounds(&self) -> Rect {
        let w = text_width(&self.text, self.size, self.bold);
        let (a0, a1) = match self.anchor {
            Anchor::Start => (0.0, w),
            Anchor::Middle => (-w / 2.0, w / 2.0),
            Anchor::End => (-w, 0.0),
        };
        let (up, down) = (ASCENT * self.size, DESCENT * self.size);
        if self.vertical {
            // rotate(−90) about (x, y): along the baseline u goes up, below it v goes right
            Rect {
                x0: self.x - up,
                x1: self.x + down,
                y0: self.y - a1,
                y1: self.y - a0,
            }
        } else {
            Rect {
                x0: self.x + a0,
                x1: self.x + a1,
                y0: self.y - up,
                y1: self.y + down,
            }
        }
    }

    fn svg(&self) -> String {
        let mut attrs = if self.vertical {
            format!(
                "transform=\"translate({:.1} {:.1}) rotate(-90)\"",
                self.x, self.y
            )
        } else {
            format!("x=\"{:.1}\" y=\"{:.1}\"", self.x, self.y)
        };
        let _ = write!(attrs, " font-size=\"{}\"", self.size);
        if self.bold {
            attrs.push_str(" font-weight=\"bold\"");
        }
        if self.anchor != Anchor::Start {
            let _ = write!(attrs, " text-anchor=\"{}\"", self.anchor.name());
        }
        format!("<text {attrs}>{}</text>", esc(&self.text))
    }
}

/// An axis-aligned box, px.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Rect {
    /// Whether the boxes share more than `slack` px in both directions.
    pub fn overlaps(&self, o: &Rect, slack: f64) -> bool {
        self.x0.max(o.x0) + slack < self.x1.min(o.x1)
            && self.y0.max(o.y0) + slack < self.y1.min(o.y1)
    }
}

/// One chart being drawn: its elements, the boxes of its labels, and how far it reaches.
#[derive(Default)]
pub struct Canvas {
    body: String,
    labels: Vec<Rect>,
    right: f64,
    bottom: f64,
}

/// Space left around everything drawn, px.
const PAD: f64 = 4.0;

impl Canvas {
    pub fn new() -> Canvas {
        Canvas::default()
    }

    fn reach(&mut self, r: &Rect) {
        self.right = self.right.max(r.x1);
        self.bottom = self.bottom.max(r.y1);
    }

    /// Draws `l`.
    pub fn label(&mut self, l: &Label) {
        let b = l.bounds();
        self.reach(&b);
        self.labels.push(b);
        self.body.push_str(&l.svg());
    }

    /// Draws `l` unless it would overlap a label already drawn; whether it was drawn.
    pub fn optional_label(&mut self, l: &Label) -> bool {
        let b = l.bounds();
        if self.labels.iter().any(|o| o.overlaps(&b, -0.5)) {
            return false;
        }
        self.label(l);
        true
    }

    /// Draws `element` (SVG markup, not text), which reaches `right` and `bottom`.
    pub fn shape(&mut self, element: &str, right: f64, bottom: f64) {
        self.right = self.right.max(right);
        self.bottom = self.bottom.max(bottom);
        self.body.push_str(element);
    }

    /// The SVG: sized to everything drawn (nothing is drawn left of or above 0), with
    /// `title` as its accessible name and `attrs` on the `<svg>` element.
    pub fn finish(self, title: &str, attrs: &str) -> String {
        let (w, h) = ((self.right + PAD).ceil(), (self.bottom + PAD).ceil());
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\" role=\"img\"{attrs}><title>{}</title>{}</svg>\n",
            esc(title),
            self.body
        )
    }
}

/// The value of attribute `name` in the start tag `tag`.
fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = tag.find(&key)? + key.len();
    Some(&tag[i..i + tag[i..].find('"')?])
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&amp;", "&")
}

/// The labels of one `<svg>…</svg>` as [`Canvas`] writes them.
fn labels_of(svg: &str) -> Result<Vec<Label>, String> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find("<text ") {
        rest = &rest[i..];
        let close = rest.find('>').ok_or("an unterminated <text> tag")?;
        let tag = &rest[..close];
        let end = rest.find("</text>").ok_or("a <text> without </text>")?;
        let text = unescape(&rest[close + 1..end]);
        rest = &rest[end..];
        let num = |s: &str| {
            s.parse::<f64>()
                .map_err(|_| format!("a <text> position {s:?}"))
        };
        let (x, y, vertical) = match attr(tag, "transform") {
            Some(t) => {
                let inner = t
                    .strip_prefix("translate(")
                    .and_then(|t| t.strip_suffix(") rotate(-90)"))
                    .ok_or_else(|| format!("a <text> transform {t:?}"))?;
                let (a, b) = inner.split_once(' ').ok_or("a translate without y")?;
                (num(a)?, num(b)?, true)
            }
            None => (
                num(attr(tag, "x").ok_or("a <text> without x")?)?,
                num(attr(tag, "y").ok_or("a <text> without y")?)?,
                false,
            ),
        };
        let anchor = match attr(tag, "text-anchor") {
            None | Some("start") => Anchor::Start,
            Some("middle") => Anchor::Middle,
            Some("end") => Anchor::End,
            Some(a) => return Err(format!("text-anchor {a:?}")),
        };
        let size = num(attr(tag, "font-size").ok_or("a <text> without font-size")?)?;
        let bold = attr(tag, "font-weight") == Some("bold");
        out.push(Label {
            x,
            y,
            text,
            anchor,
            size,
            bold,
            vertical,
        });
    }
    Ok(out)
}

/// What is wrong with the text of the SVG charts in `html` (a page or one chart): any label
/// outside its SVG's `viewBox`, any two labels of one SVG that overlap (by more than half a
/// pixel), with the estimated extents of [`text_width`]. Empty when every label fits.
pub fn layout_problems(html: &str) -> Vec<String> {
    let mut problems = Vec::new();
    for (k, part) in html.split("<svg ").skip(1).enumerate() {
        let svg = &part[..part.find("</svg>").unwrap_or(part.len())];
        let name = svg
            .find("<title>")
            .and_then(|i| Some(&svg[i + 7..i + svg[i..].find("</title>")?]))
            .unwrap_or("(untitled)");
        let name = format!("svg {k} ({})", unescape(name));
        let view: Vec<f64> = attr(svg, "viewBox")
            .unwrap_or("")
            .split(' ')
            .filter_map(|v| v.parse().ok())
            .collect();
        let [vx, vy, vw, vh] = view[..] else {
            problems.push(format!("{name}: no viewBox"));
            continue;
        };
        let labels = match labels_of(svg) {
            Ok(l) => l,
            Err(e) => {
                problems.push(format!("{name}: {e}"));
                continue;
            }
        };
        let boxes: Vec<Rect> = labels.iter().map(Label::bounds).collect();
        for (l, b) in labels.iter().zip(&boxes) {
            if b.x0 < vx || b.y0 < vy || b.x1 > vx + vw || b.y1 > vy + vh {
                problems.push(format!(
                    "{name}: {:?} reaches [{:.1}, {:.1}] × [{:.1}, {:.1}], outside the viewBox {vw} × {vh}",
                    l.text, b.x0, b.x1, b.y0, b.y1
                ));
            }
        }
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].overlaps(&boxes[j], 0.5) {
                    problems.push(format!(
                        "{name}: {:?} overlaps {:?}",
                        labels[i].text, labels[j].text
                    ));
                }
            }
        }
    }
    problems
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes_of_anchored_and_rotated_labels() {
        let w = text_width("0.25", FONT, false);
        assert!((w - (3.0 * 0.65 + 0.34) * FONT).abs() < 1e-12);
        let b = Label::new(100.0, 50.0, Anchor::End, "0.25").bounds();
        assert_eq!((b.x0, b.x1), (100.0 - w, 100.0));
        assert!(b.y0 < 50.0 - 10.0 && b.y1 > 50.0 + 2.0);
        let v = Label::new(14.0, 100.0, Anchor::Middle, "0.25")
            .vertical()
            .bounds();
        assert!((v.y1 - v.y0 - w).abs() < 1e-12 && (v.y0 + w / 2.0 - 100.0).abs() < 1e-12);
        assert!(v.x0 < 14.0 - 10.0 && v.x1 > 14.0);
    }

    #[test]
    fn wrap_keeps_lines_within_the_width() {
        let t = "E_avg = 2∫E(μ)μ dμ from a-rather-long-table-name (midpoint rule over the table)";
        let lines = wrap(t, 200.0, FONT, true);
        assert!(lines.len() > 1);
        assert_eq!(lines.join(" "), t);
        for l in &lines {
            assert!(
                text_width(l, FONT, true) <= 200.0 || !l.contains(' '),
                "{l}"
            );
        }
    }

    /// The checker finds what it is for: a label past the right edge, two labels on top of
    /// each other, and accepts a canvas whose labels are apart.
    #[test]
    fn layout_problems_finds_clipped_and_overlapping_text() {
        let mut c = Canvas::new();
        c.label(&Label::new(10.0, 20.0, Anchor::Start, "first"));
        c.label(&Label::new(10.0, 20.0 + LINE, Anchor::Start, "second"));
        c.label(&Label::new(40.0, 80.0, Anchor::Middle, "up").vertical());
        let ok = c.finish("fine", "");
        assert_eq!(layout_problems(&ok), Vec::<String>::new());
        let narrow = ok.replacen(" x=\"10.0\"", " x=\"1000.0\"", 1);
        let p = layout_problems(&narrow);
        assert!(p.len() == 1 && p[0].contains("\"first\"") && p[0].contains("outside"));
        let over = ok.replacen("y=\"34.0\"", "y=\"25.0\"", 1);
        let p = layout_problems(&over);
        assert!(
            p.len() == 1 && p[0].contains("\"first\" overlaps \"second\""),
            "{p:?}"
        );
        // an optional label that would overlap is left out
        let mut c = Canvas::new();
        c.label(&Label::new(10.0, 20.0, Anchor::Start, "first"));
        assert!(!c.optional_label(&Label::new(12.0, 22.0, Anchor::Start, "x")));
        assert!(c.optional_label(&Label::new(10.0, 20.0 + LINE, Anchor::Start, "x")));
    }
}
