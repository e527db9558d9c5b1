//! `--sheet COLSxROWS`: several views on one page, in reading order (left to right, then top
//! to bottom), each in a cell of its own with its own margin, composed into one SVG (each
//! layer holds every cell's lines, moved into place) and one PNG (the cells' pictures pasted).

use anyhow::{anyhow, bail, Result};
use kepler_hsr::plot::{PageSize, Rgb};

/// Millimetres per CSS pixel (1/96 in): the unit of `--size` without a page.
const MM_PER_PX: f64 = 25.4 / 96.0;

/// A grid of cells on one page.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Sheet {
    /// Columns.
    pub cols: u32,
    /// Rows.
    pub rows: u32,
    /// The whole page, mm.
    pub page: PageSize,
}

impl Sheet {
    /// The sheet `COLSxROWS` on `page`, or, without one, on a page of square cells whose
    /// longer side is `size_px` CSS pixels.
    pub(crate) fn new(spec: &str, page: Option<PageSize>, size_px: u32) -> Result<Sheet> {
        let bad = || anyhow!("--sheet {spec}: expected COLSxROWS, e.g. 3x2 (each 1 to 100)");
        let (c, r) = spec
            .trim()
            .to_ascii_lowercase()
            .split_once('x')
            .map(|(c, r)| (c.trim().parse::<u32>(), r.trim().parse::<u32>()))
            .ok_or_else(bad)?;
        let (cols, rows) = (c.map_err(|_| bad())?, r.map_err(|_| bad())?);
        if !(1..=100).contains(&cols) || !(1..=100).contains(&rows) {
            return Err(bad());
        }
        let page = page.unwrap_or_else(|| {
            let cell = f64::from(size_px.max(1)) * MM_PER_PX / f64::from(cols.max(rows));
            PageSize {
                width: cell * f64::from(cols),
                height: cell * f64::from(rows),
            }
        });
        Ok(Sheet { cols, rows, page })
    }

    /// Cells on the sheet.
    pub(crate) fn cells(&self) -> usize {
        (self.cols * self.rows) as usize
    }

    /// Refuses more views than cells.
    pub(crate) fn check_views(&self, n: usize) -> Result<()> {
        if n > self.cells() {
            bail!(
                "--sheet {}x{} has {} cells for {n} views: give a larger sheet or fewer views",
                self.cols,
                self.rows,
                self.cells()
            );
        }
        Ok(())
    }

    /// The page of one cell.
    pub(crate) fn cell_page(&self) -> PageSize {
        PageSize {
            width: self.page.width / f64::from(self.cols),
            height: self.page.height / f64::from(self.rows),
        }
    }

    /// The top-left corner of cell `k` (reading order), mm.
    fn origin(&self, k: usize) -> [f64; 2] {
        let cell = self.cell_page();
        let (col, row) = (k as u32 % self.cols, k as u32 / self.cols);
        [f64::from(col) * cell.width, f64::from(row) * cell.height]
    }

    /// Pixels per mm of the sheet's PNG: `dpi`, or `size_px` along the page's longer side.
    fn px_per_mm(&self, dpi: Option<f64>, size_px: u32) -> f64 {
        match dpi {
            Some(d) => d / 25.4,
            None => f64::from(size_px.max(1)) / self.page.longer_side(),
        }
    }

    /// The `--size` of one cell's PNG, so that the cells tile the sheet's.
    pub(crate) fn cell_size(&self, size_px: u32) -> u32 {
        let s =
            f64::from(size_px.max(1)) * self.cell_page().longer_side() / self.page.longer_side();
        (s.round() as u32).max(1)
    }

    /// One SVG of the cells' SVGs (each a page of [`Sheet::cell_page`]), in reading order.
    pub(crate) fn svg(&self, cells: &[String]) -> String {
        let (w, h) = (self.page.width, self.page.height);
        let mut head = None;
        let mut background = None;
        // Top-level groups by their opening line, in first-seen order, each with the cells'
        // contents moved into place.
        let mut groups: Vec<(String, Vec<String>)> = Vec::new();
        for (k, svg) in cells.iter().enumerate() {
            let [x, y] = self.origin(k);
            let mut lines = svg.lines();
            if let Some(first) = lines.next() {
                head.get_or_insert_with(|| first.to_string());
            }
            let mut depth = 0usize;
            let mut current: Option<usize> = None;
            let mut loose = Vec::new();
            for line in lines {
                let t = line.trim_start();
                if depth == 0 {
                    if t.starts_with("</svg") {
                        continue;
                    }
                    if t.starts_with("<rect") && t.contains("id=\"background\"") {
                        background.get_or_insert_with(|| attr(t, "fill"));
                        continue;
                    }
                    if t.starts_with("<g") && !t.ends_with("/>") {
                        let i = match groups.iter().position(|(g, _)| g == line) {
                            Some(i) => i,
                            None => {
                                groups.push((line.to_string(), Vec::new()));
                                groups.len() - 1
                            }
                        };
                        groups[i]
                            .1
                            .push(format!("<g transform=\"translate({x} {y})\">"));
                        current = Some(i);
                        depth = 1;
                        continue;
                    }
                    loose.push(line.to_string());
                    continue;
                }
                depth += t.matches("<g").filter(|_| !t.ends_with("/>")).count();
                depth -= t.matches("</g>").count().min(depth);
                if depth == 0 {
                    if let Some(i) = current.take() {
                        groups[i].1.push("</g>".into());
                    }
                    continue;
                }
                if let Some(i) = current {
                    groups[i].1.push(line.to_string());
                }
            }
            if !loose.is_empty() {
                let mut g = vec![format!("<g transform=\"translate({x} {y})\">")];
                g.extend(loose);
                g.push("</g>".into());
                groups.push((String::new(), g));
            }
        }
        let head = head.unwrap_or_default();
        let mut out = vec![sized(&head, w, h)];
        if let Some(Some(fill)) = background {
            out.push(format!(
                "<rect fill=\"{fill}\" height=\"{h}\" id=\"background\" width=\"{w}\"/>"
            ));
        }
        for (open, body) in groups {
            let wrap = !open.is_empty();
            if wrap {
                out.push(open);
            }
            out.extend(body);
            if wrap {
                out.push("</g>".into());
            }
        }
        out.push("</svg>".into());
        let mut text = out.join("\n");
        text.push('\n');
        text
    }

    /// One PNG of the cells' PNGs, pasted at their places on a ground of `background`.
    pub(crate) fn png(
        &self,
        cells: &[Vec<u8>],
        dpi: Option<f64>,
        size_px: u32,
        background: Option<Rgb>,
    ) -> Result<Vec<u8>> {
        let ppm = self.px_per_mm(dpi, size_px);
        let px = |mm: f64| (mm * ppm).round().max(1.0) as u32;
        let (w, h) = (px(self.page.width), px(self.page.height));
        let ground = background.unwrap_or(Rgb::WHITE).0;
        let mut canvas =
            image::RgbaImage::from_pixel(w, h, image::Rgba([ground[0], ground[1], ground[2], 255]));
        for (k, bytes) in cells.iter().enumerate() {
            let cell = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
                .map_err(|e| anyhow!("sheet cell {}: {e}", k + 1))?
                .to_rgba8();
            let [x, y] = self.origin(k);
            let (x0, y0) = ((x * ppm).round() as i64, (y * ppm).round() as i64);
            image::imageops::overlay(&mut canvas, &cell, x0, y0);
        }
        let mut out = std::io::Cursor::new(Vec::new());
        canvas
            .write_to(&mut out, image::ImageFormat::Png)
            .map_err(|e| anyhow!("sheet PNG: {e}"))?;
        Ok(out.into_inner())
    }
}

/// The value of attribute `name` in one tag's text.
fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!("{name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')? + start;
    Some(tag[start..end].to_string())
}

/// The opening `<svg ...>` line with the sheet's size.
fn sized(head: &str, w: f64, h: f64) -> String {
    let mut s = head.to_string();
    for (name, value) in [
        ("width", format!("{w}mm")),
        ("height", format!("{h}mm")),
        ("viewBox", format!("0 0 {w} {h}")),
    ] {
        if let Some(old) = attr(&s, name) {
            s = s.replacen(
                &format!("{name}=\"{old}\""),
                &format!("{name}=\"{value}\""),
                1,
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_and_cells() {
        let s = Sheet::new("3x2", Some(PageSize::A4.landscape()), 1024).unwrap();
        assert_eq!((s.cols, s.rows, s.cells()), (3, 2, 6));
        assert_eq!(s.cell_page().width, 99.0);
        assert_eq!(s.origin(4), [99.0, 105.0]);
        assert!(s.check_views(6).is_ok());
        assert!(s
            .check_views(7)
            .unwrap_err()
            .to_string()
            .contains("6 cells"));
        for bad in ["3", "0x2", "x", "3x2x1", "ax2", "101x1"] {
            assert!(Sheet::new(bad, None, 100).is_err(), "{bad}");
        }
        // Without a page: square cells, the longer side --size pixels.
        let s = Sheet::new("2x1", None, 960).unwrap();
        assert!((s.page.width - 254.0).abs() < 1e-9 && (s.page.height - 127.0).abs() < 1e-9);
        assert_eq!(s.cell_size(960), 480);
    }

    #[test]
    fn svg_cells_move_into_place_layer_by_layer() {
        let s = Sheet::new(
            "2x1",
            Some(PageSize {
                width: 20.0,
                height: 10.0,
            }),
            100,
        )
        .unwrap();
        let cell = |d: &str| {
            format!(
                "<svg height=\"10mm\" viewBox=\"0 0 10 10\" width=\"10mm\" xmlns=\"x\">\n\
                 <rect fill=\"#fffff0\" height=\"10\" id=\"background\" width=\"10\"/>\n\
                 <g id=\"layer1\">\n<path d=\"{d}\"/>\n</g>\n</svg>\n"
            )
        };
        let out = s.svg(&[cell("M1,1L2,2"), cell("M3,3L4,4")]);
        assert!(out.starts_with(
            "<svg height=\"10mm\" viewBox=\"0 0 20 10\" width=\"20mm\" xmlns=\"x\">\n"
        ));
        assert_eq!(out.matches("<g id=\"layer1\">").count(), 1, "{out}");
        assert!(out.contains("<g transform=\"translate(10 0)\">\n<path d=\"M3,3L4,4\"/>\n</g>"));
        assert!(
            out.contains("<rect fill=\"#fffff0\" height=\"10\" id=\"background\" width=\"20\"/>")
        );
        assert_eq!(out.matches("<g").count(), out.matches("</g>").count());
    }
}
