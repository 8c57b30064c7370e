//! Heatmaps of a table's texels: one chart per channel, every texel one pixel of an
//! embedded PNG (8-bit viridis), drawn crisp (`image-rendering: pixelated`) so zooming in
//! shows each texel; a 3D table as one panel per slice; a colour bar whose ends are the
//! channel's true minimum and maximum over the whole table, printed.
//!
//! A table too large to embed texel for texel (over [`MAX_DRAWN`] texels, or over
//! [`MAX_SLICES`] slices) is drawn from every k-th texel or slice, and the chart says which;
//! its colour bar still spans the whole table's range.

use super::layout::{wrap, Anchor, Canvas, Label, FONT, LINE};
use super::svg::{colour_rgb, esc, fmt_num, linear_ticks};
use crate::lut::Lut;
use crate::numfmt::sig4;

/// Most texels one heatmap embeds (a 1024² table is drawn whole).
pub const MAX_DRAWN: usize = 1 << 20;
/// Most slices of a 3D table one heatmap shows.
pub const MAX_SLICES: usize = 64;
/// The colour of a texel that is not a finite number.
const NOT_FINITE: [u8; 3] = [255, 0, 255];

/// Which texels are drawn: every `s`-th along axes 0 and 1, every `sz`-th slice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampling {
    pub s: usize,
    pub sz: usize,
}

impl Sampling {
    /// The drawing of an `nx × ny × nz` table.
    pub fn of(nx: usize, ny: usize, nz: usize) -> Sampling {
        let sz = nz.div_ceil(MAX_SLICES).max(1);
        let dz = nz.div_ceil(sz);
        let mut s = 1;
        while nx.div_ceil(s) * ny.div_ceil(s) * dz > MAX_DRAWN {
            s += 1;
        }
        Sampling { s, sz }
    }
}

/// `data:` URI of an 8-bit RGB PNG (`rgb`: rows top first); `None` if it cannot be encoded.
fn png_uri(w: usize, h: usize, rgb: &[u8]) -> Option<String> {
    let bytes = crate::encode::png::write_png(
        (u32::try_from(w).ok()?, u32::try_from(h).ok()?),
        ::png::ColorType::Rgb,
        ::png::BitDepth::Eight,
        &[],
        rgb,
        &|e| crate::encode::EncodeError::Shape {
            table: "report".into(),
            reason: e.to_string(),
        },
    )
    .ok()?;
    Some(format!("data:image/png;base64,{}", base64(&bytes)))
}

/// Standard base64 with padding (RFC 4648 §4).
fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Displayed size, px, of an axis of `n` drawn texels: whole pixels per texel up to about
/// `target`, one pixel per texel up to `2·target`, scaled down beyond.
fn display(n: usize, target: usize) -> f64 {
    if n <= target {
        (n * (target as f64 / n as f64).round().max(1.0) as usize) as f64
    } else {
        n.min(2 * target) as f64
    }
}

/// The `<image>` element of `uri` at (x, y), w × h px.
fn image(uri: &str, x: f64, y: f64, w: f64, h: f64, crisp: bool) -> String {
    format!(
        "<image x=\"{x:.1}\" y=\"{y:.1}\" width=\"{w:.1}\" height=\"{h:.1}\" \
         preserveAspectRatio=\"none\"{} href=\"{uri}\"/>",
        if crisp {
            " style=\"image-rendering:pixelated\""
        } else {
            ""
        }
    )
}

/// The heatmap of channel `c`: axis 0 to the right, axis 1 upwards, a 3D table's slices as
/// panels (slice value above each), a 1D table as a strip.
pub fn heatmap(lut: &Lut, c: usize, title: &str) -> String {
    let nd = lut.axes.len();
    let nc = lut.channels.len().max(1);
    let (nx, ny, nz) = (lut.dim(0), lut.dim(1), lut.dim(2));
    let values = || lut.data.iter().skip(c).step_by(nc).map(|&v| f64::from(v));
    let (lo, hi) = values()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    let not_finite = values().filter(|v| !v.is_finite()).count();
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 0.0) };
    let span = if hi > lo { hi - lo } else { 1.0 };
    let sampling = Sampling::of(nx, ny, nz);
    let Sampling { s, sz } = sampling;
    let (dx, dy, dz) = (nx.div_ceil(s), ny.div_ceil(s), nz.div_ceil(sz));

    // sizes: panels of a 3D table are smaller; a 1D table is a strip
    let target = if nd == 3 { 96 } else { 256 };
    let pw = display(dx, target);
    let ph = if nd == 1 { 32.0 } else { display(dy, target) };
    let cols = if dz > 1 {
        ((dz as f64).sqrt().ceil() as usize).clamp(1, 8)
    } else {
        1
    };
    let rows = dz.div_ceil(cols);
    let head = if dz > 1 { LINE + 8.0 } else { 0.0 };
    let gap_x = 16.0;
    let grid_w = cols as f64 * pw + (cols - 1) as f64 * gap_x;

    let ax = &lut.axes[0];
    let tick_text = |a: &crate::lut::Axis, i: usize| fmt_num(a.coord(i));
    let x_ticks: Vec<(usize, String)> = [0, dx - 1]
        .iter()
        .map(|&i| (i, tick_text(ax, i * s)))
        .collect();
    let y_ticks: Vec<(usize, String)> = if nd >= 2 {
        [0, dy - 1]
            .iter()
            .map(|&j| (j, tick_text(&lut.axes[1], j * s)))
            .collect()
    } else {
        Vec::new()
    };
    let yw = y_ticks
        .iter()
        .map(|(_, l)| super::layout::text_width(l, FONT, false))
        .fold(0.0, f64::max);
    let ylabel_x = 4.0 + 0.95 * FONT;
    let first_x_half = super::layout::text_width(&x_ticks[0].1, FONT, false) / 2.0;
    let ml = if nd >= 2 {
        ylabel_x + 0.25 * FONT + 6.0 + yw + 6.0
    } else {
        8.0
    }
    .max(first_x_half + 6.0);

    // the bar's printed ends
    let max_text = format!("max {}", sig4(hi));
    let min_text = format!("min {}", sig4(lo));
    let bar_x = ml + grid_w + 16.0;
    let bar_w = 14.0;
    let bar_labels_x = bar_x + bar_w + 6.0;
    let right = bar_labels_x
        + [&max_text, &min_text]
            .iter()
            .map(|t| super::layout::text_width(t, FONT, false))
            .fold(0.0, f64::max);

    let mut notes = Vec::new();
    if nd == 3 {
        let az = &lut.axes[2];
        notes.push(format!(
            "one panel per slice of {}, its value above the panel",
            az.name
        ));
        if sz > 1 {
            notes.push(format!(
                "every {sz}th slice drawn (slices 0, {sz}, {}, …: {dz} of {nz})",
                2 * sz
            ));
        }
    }
    if s > 1 {
        notes.push(format!(
            "every {s}th texel drawn along {} and {} (texels 0, {s}, {}, …: {dx} × {dy} of \
             {nx} × {ny}); the bar spans all texels",
            ax.name,
            lut.axes.get(1).map_or("", |a| a.name.as_str()),
            2 * s
        ));
    }
    // crisp texels when enlarged; averaged by the browser when shrunk (crisp, a shrunk
    // image shows moiré)
    let shrunk = pw < dx as f64 || (nd >= 2 && ph < dy as f64);
    if shrunk {
        notes.push("more texels than pixels: zoom in to see each texel".into());
    }
    if hi == lo {
        notes.push(format!("every texel is {}", sig4(hi)));
    }
    if not_finite > 0 {
        notes.push(format!(
            "{not_finite} texel(s) not a finite number, drawn magenta"
        ));
    }

    let mut cv = Canvas::new();
    let width = right.max(260.0);
    let mut y = 16.0;
    for l in wrap(title, width - 4.0, FONT, true) {
        cv.label(&Label::new(4.0, y, Anchor::Start, l).bold());
        y += LINE;
    }
    for n in &notes {
        for l in wrap(n, width - 4.0, FONT, false) {
            cv.label(&Label::new(4.0, y, Anchor::Start, l));
            y += LINE;
        }
    }
    let grid_top = y - LINE + 16.0;
    let panel = |k: usize| {
        (
            ml + (k % cols) as f64 * (pw + gap_x),
            grid_top + (k / cols) as f64 * (ph + head) + head,
        )
    };
    let mut rgb = vec![0u8; dx * dy * 3];
    for k in 0..dz {
        let z = k * sz;
        for j in 0..dy {
            for i in 0..dx {
                let v = f64::from(lut.texel([i * s, j * s, z], c));
                let col = if v.is_finite() {
                    colour_rgb((v - lo) / span)
                } else {
                    NOT_FINITE
                };
                // axis 1 upwards: texel row j is image row dy − 1 − j
                let p = ((dy - 1 - j) * dx + i) * 3;
                rgb[p..p + 3].copy_from_slice(&col);
            }
        }
        let (px, py) = panel(k);
        if let Some(uri) = png_uri(dx, dy, &rgb) {
            cv.shape(&image(&uri, px, py, pw, ph, !shrunk), px + pw, py + ph);
        }
        cv.shape(
            &format!(
                "<rect x=\"{px:.1}\" y=\"{py:.1}\" width=\"{pw:.1}\" height=\"{ph:.1}\" fill=\"none\" stroke=\"#222\"/>"
            ),
            px + pw,
            py + ph,
        );
        if dz > 1 {
            cv.label(&Label::new(
                px + pw / 2.0,
                py - 4.0,
                Anchor::Middle,
                fmt_num(lut.axes[2].coord(z)),
            ));
        }
        // y ticks left of the panels of the first column
        if k % cols == 0 {
            for (n, (j, l)) in y_ticks.iter().enumerate() {
                let ty = py + ph - (*j as f64 + 0.5) * ph / dy as f64;
                cv.shape(
                    &format!(
                        "<line x1=\"{:.1}\" y1=\"{ty:.1}\" x2=\"{px:.1}\" y2=\"{ty:.1}\" stroke=\"#222\"/>",
                        px - 4.0
                    ),
                    px,
                    ty,
                );
                let lab = Label::new(px - 6.0, ty + 4.0, Anchor::End, l.as_str());
                if n == 0 {
                    cv.label(&lab);
                } else {
                    cv.optional_label(&lab);
                }
            }
        }
    }
    let grid_bottom = grid_top + rows as f64 * (ph + head);
    // x ticks under the first panel of the last row
    let (px, py) = panel((rows - 1) * cols);
    for (n, (i, l)) in x_ticks.iter().enumerate() {
        if n == 1 && dx == 1 {
            break;
        }
        let tx = px + (*i as f64 + 0.5) * pw / dx as f64;
        cv.shape(
            &format!(
                "<line x1=\"{tx:.1}\" y1=\"{:.1}\" x2=\"{tx:.1}\" y2=\"{:.1}\" stroke=\"#222\"/>",
                py + ph,
                py + ph + 4.0
            ),
            tx,
            py + ph + 4.0,
        );
        let lab = Label::new(tx, py + ph + 18.0, Anchor::Middle, l.as_str());
        if n == 0 {
            cv.label(&lab);
        } else {
            cv.optional_label(&lab);
        }
    }
    cv.label(&Label::new(
        ml + grid_w / 2.0,
        grid_bottom + 34.0,
        Anchor::Middle,
        format!("{} →", ax.name),
    ));
    if nd >= 2 {
        cv.label(
            &Label::new(
                ylabel_x,
                (grid_top + grid_bottom) / 2.0,
                Anchor::Middle,
                format!("{} →", lut.axes[1].name),
            )
            .vertical(),
        );
    }

    // the colour bar, from the first panel's top to the last row's bottom
    let bar_top = grid_top + head;
    let bar_bottom = grid_bottom;
    let bar: Vec<u8> = (0..256)
        .rev()
        .flat_map(|k| colour_rgb(k as f64 / 255.0))
        .collect();
    if let Some(uri) = png_uri(1, 256, &bar) {
        cv.shape(
            &image(&uri, bar_x, bar_top, bar_w, bar_bottom - bar_top, false),
            bar_x + bar_w,
            bar_bottom,
        );
    }
    cv.shape(
        &format!(
            "<rect x=\"{bar_x:.1}\" y=\"{bar_top:.1}\" width=\"{bar_w}\" height=\"{:.1}\" fill=\"none\" stroke=\"#222\"/>",
            bar_bottom - bar_top
        ),
        bar_x + bar_w,
        bar_bottom,
    );
    let at = |v: f64| bar_bottom - (v - lo) / span * (bar_bottom - bar_top);
    let tick = |cv: &mut Canvas, ty: f64, text: &str, required: bool| {
        let lab = Label::new(bar_labels_x, ty + 4.0, Anchor::Start, text);
        let drawn = if required {
            cv.label(&lab);
            true
        } else {
            cv.optional_label(&lab)
        };
        if drawn {
            cv.shape(
                &format!(
                    "<line x1=\"{:.1}\" y1=\"{ty:.1}\" x2=\"{:.1}\" y2=\"{ty:.1}\" stroke=\"#222\"/>",
                    bar_x + bar_w,
                    bar_x + bar_w + 4.0
                ),
                bar_x + bar_w + 4.0,
                ty,
            );
        }
    };
    tick(&mut cv, bar_top, &max_text, true);
    tick(&mut cv, bar_bottom, &min_text, true);
    if hi > lo {
        for (v, l) in linear_ticks(lo, hi, 4).at {
            if v > lo && v < hi {
                tick(&mut cv, at(v), &l, false);
            }
        }
    }
    let attrs = format!(
        " data-channel=\"{}\" data-min=\"{:?}\" data-max=\"{:?}\"",
        esc(&lut.channels[c].name),
        lo as f32,
        hi as f32
    );
    cv.finish(title, &attrs)
}

#[cfg(test)]
mod tests {
    use super::super::layout::layout_problems;
    use super::*;
    use crate::lut::{Axis, Channel, Convention, Quantity};

    #[test]
    fn base64_of_rfc_4648_vectors() {
        for (i, o) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(i.as_bytes()), o);
        }
    }

    #[test]
    fn sampling_draws_every_texel_up_to_the_budget() {
        assert_eq!(Sampling::of(1024, 1024, 1), Sampling { s: 1, sz: 1 });
        assert_eq!(Sampling::of(64, 64, 16), Sampling { s: 1, sz: 1 });
        assert_eq!(Sampling::of(1025, 1024, 1), Sampling { s: 2, sz: 1 });
        assert_eq!(Sampling::of(64, 64, 130), Sampling { s: 1, sz: 3 });
        let s = Sampling::of(4096, 4096, 1);
        assert!(4096usize.div_ceil(s.s).pow(2) <= MAX_DRAWN && s.s == 4);
    }

    fn table(sizes: &[usize], f: impl Fn(usize) -> f32) -> Lut {
        let axis = |k: usize, n: usize| Axis {
            name: ["cos_theta_v", "roughness", "fresnel"][k].into(),
            quantity: Quantity::Cosine,
            size: n,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        };
        let n: usize = sizes.iter().product();
        Lut {
            axes: sizes.iter().enumerate().map(|(k, &n)| axis(k, n)).collect(),
            channels: vec![Channel {
                name: "B".into(),
                meaning: "test".into(),
            }],
            data: (0..n).map(f).collect(),
            error_estimate: vec![0.0],
            evaluations: 0,
        }
    }

    /// The PNG embedded in a heatmap, decoded: (width, height, RGB rows top first).
    fn embedded(svg: &str) -> (u32, u32, Vec<u8>) {
        let start = svg.find("base64,").expect("an image") + 7;
        let b64 = &svg[start..start + svg[start..].find('"').unwrap()];
        let val = |c: u8| A.iter().position(|&x| x == c).unwrap() as u32;
        const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut bytes = Vec::new();
        for q in b64.as_bytes().chunks(4) {
            let n = q
                .iter()
                .enumerate()
                .filter(|(_, &c)| c != b'=')
                .fold(0u32, |n, (k, &c)| n | val(c) << (18 - 6 * k));
            let keep = q.iter().filter(|&&c| c != b'=').count() - 1;
            bytes.extend_from_slice(&n.to_be_bytes()[1..1 + keep]);
        }
        let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
            .unwrap()
            .to_rgb8();
        (img.width(), img.height(), img.into_raw())
    }

    /// A 300 × 200 table (over the old 64-cell resampling) is drawn texel for texel: the
    /// embedded image is 300 × 200 and each pixel has its texel's colour; the colour bar's
    /// printed and recorded ends are the table's extremes, including a single spike.
    #[test]
    fn every_texel_is_drawn_and_the_bar_spans_the_true_range() {
        let (nx, ny) = (300, 200);
        let mut lut = table(&[nx, ny], |k| ((k % nx) as f32 / nx as f32) * 0.5);
        lut.data[nx * 150 + 7] = 21.786_14;
        let svg = heatmap(&lut, 0, "spike");
        assert!(svg.contains("data-max=\"21.78614\""), "{}", &svg[..300]);
        assert!(svg.contains(">max 21.79</text>") && svg.contains(">min 0</text>"));
        let (w, h, rgb) = embedded(&svg);
        assert_eq!((w, h), (nx as u32, ny as u32));
        let span = 21.786_14f64;
        for (j, i) in [(0, 0), (150, 7), (199, 299), (37, 123)] {
            let v = f64::from(lut.data[j * nx + i]);
            let p = ((ny - 1 - j) * nx + i) * 3;
            assert_eq!(&rgb[p..p + 3], &colour_rgb(v / span), "texel {i} {j}");
        }
        assert_eq!(layout_problems(&svg), Vec::<String>::new());
    }

    /// 1D, 2D and 3D tables, tiny and large, with negative and tiny values: text inside the
    /// viewBox and apart; a 3D table has a panel (an image) per slice.
    #[test]
    fn heatmaps_keep_their_text_inside_and_apart() {
        let cases = [
            table(&[7], |k| k as f32),
            table(&[2, 2], |k| -4.9e-9 * k as f32),
            table(&[128, 128], |k| (k as f32).sin()),
            table(&[16, 16, 16], |k| k as f32 * 1e-7),
            table(&[64, 64, 32], |k| (k % 97) as f32 - 50.0),
            table(&[3, 5], |_| 0.25),
        ];
        for (n, lut) in cases.iter().enumerate() {
            let svg = heatmap(
                lut,
                0,
                "a title long enough to need wrapping in a small chart",
            );
            assert_eq!(layout_problems(&svg), Vec::<String>::new(), "case {n}");
            let panels = if lut.axes.len() == 3 { lut.dim(2) } else { 1 };
            // + the colour bar
            assert_eq!(svg.matches("<image").count(), panels + 1, "case {n}");
        }
        let svg = heatmap(&cases[5], 0, "flat");
        assert!(svg.contains("every texel is 0.25"));
    }
}
