//! Physical pages: named paper sizes (A3 to A6, letter, W×H mm), margins, and the one mapping
//! of a framed screen rectangle onto a page in millimetres, fitted and centred.
//!
//! Page coordinates are millimetres from the page's top-left corner, y growing down (SVG's
//! and a plotter's convention); screen y grows up, so the mapping flips y.

use crate::error::{Error, Result};
use crate::geom::poly2::Pt2;
use crate::geom::Rect;
use crate::view::Frame;

/// Millimetres per CSS pixel (1/96 inch): the unit of `--size` when no page is given.
pub(crate) const MM_PER_PX: f64 = 25.4 / 96.0;

/// Margin around the drawing on a named page when none is asked for, in mm.
pub(crate) const DEFAULT_PAGE_MARGIN_MM: f64 = 10.0;

/// A sheet of paper, in millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PageSize {
    /// Width in mm.
    pub width: f64,
    /// Height in mm.
    pub height: f64,
}

impl PageSize {
    /// ISO A4, portrait.
    pub const A4: PageSize = PageSize {
        width: 210.0,
        height: 297.0,
    };
    /// ISO A3, portrait.
    pub const A3: PageSize = PageSize {
        width: 297.0,
        height: 420.0,
    };
    /// ISO A5, portrait.
    pub const A5: PageSize = PageSize {
        width: 148.0,
        height: 210.0,
    };
    /// ISO A6, portrait.
    pub const A6: PageSize = PageSize {
        width: 105.0,
        height: 148.0,
    };
    /// US letter (8.5 × 11 in), portrait.
    pub const LETTER: PageSize = PageSize {
        width: 215.9,
        height: 279.4,
    };

    /// A page from `--page`: `a3`, `a4`, `a5`, `a6`, `letter` (any case) or `WxHmm` (`W` and `H`
    /// positive millimetres, the `mm` optional).
    pub fn parse(s: &str) -> Result<PageSize> {
        let t = s.trim().to_ascii_lowercase();
        match t.as_str() {
            "a4" => return Ok(PageSize::A4),
            "a3" => return Ok(PageSize::A3),
            "a5" => return Ok(PageSize::A5),
            "a6" => return Ok(PageSize::A6),
            "letter" => return Ok(PageSize::LETTER),
            _ => {}
        }
        let bad = || {
            Error::Usage(format!(
                "--page {s}: expected a3, a4, a5, a6, letter or WIDTHxHEIGHTmm (e.g. 200x150mm)"
            ))
        };
        let dims = t.strip_suffix("mm").unwrap_or(&t);
        let (w, h) = dims.split_once('x').ok_or_else(bad)?;
        let mm = |v: &str| -> Result<f64> {
            let x: f64 = v.trim().parse().map_err(|_| bad())?;
            if x.is_finite() && x > 0.0 && x <= 100_000.0 {
                Ok(x)
            } else {
                Err(Error::Usage(format!(
                    "--page {s}: sides must be positive millimetres up to 100000"
                )))
            }
        };
        Ok(PageSize {
            width: mm(w)?,
            height: mm(h)?,
        })
    }

    /// The same sheet turned so that its longer side is horizontal.
    pub fn landscape(self) -> PageSize {
        PageSize {
            width: self.width.max(self.height),
            height: self.width.min(self.height),
        }
    }

    /// The longer side in mm.
    pub fn longer_side(&self) -> f64 {
        self.width.max(self.height)
    }
}

/// Where a framed drawing lands on the page: page size, scale, and the drawing's area.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Layout {
    /// The page.
    pub page: PageSize,
    /// Millimetres per screen unit.
    pub scale: f64,
    /// The framed screen rectangle the area shows.
    pub content: Rect,
    /// The drawing's area on the page (mm, y down): `content` mapped. Every line is clipped
    /// to it.
    pub area: Rect,
}

impl Layout {
    /// The layout of `frame`'s content: on `page` (fitted inside `margin` mm, default
    /// [`DEFAULT_PAGE_MARGIN_MM`], and centred), or, without a page, on a page of the frame's
    /// shape whose longer side is `size_px` CSS pixels (the frame's own 5% margin, or
    /// `margin` mm when given).
    pub(crate) fn new(
        frame: &Frame,
        page: Option<PageSize>,
        margin: Option<f64>,
        size_px: u32,
    ) -> Result<Layout> {
        if let Some(m) = margin {
            if !(m.is_finite() && m >= 0.0) {
                return Err(Error::Usage(format!(
                    "--margin {m}: expected millimetres >= 0"
                )));
            }
        }
        let c = frame.content;
        // A drawing with no extent on an axis still needs a scale: use the frame's unit.
        let (cw, ch) = (c.width().max(0.0), c.height().max(0.0));
        let longer = if cw.max(ch) > 0.0 {
            cw.max(ch)
        } else {
            frame.unit
        };
        match page {
            Some(page) => {
                let m = margin.unwrap_or(DEFAULT_PAGE_MARGIN_MM);
                let (bw, bh) = (page.width - 2.0 * m, page.height - 2.0 * m);
                if !(bw > 0.0 && bh > 0.0) {
                    return Err(Error::Usage(format!(
                        "--margin {m} mm leaves no room on a {} x {} mm page",
                        page.width, page.height
                    )));
                }
                let fit = |box_side: f64, side: f64| {
                    if side > 0.0 {
                        box_side / side
                    } else {
                        f64::INFINITY
                    }
                };
                let mut scale = fit(bw, cw).min(fit(bh, ch));
                if !scale.is_finite() {
                    scale = bw.min(bh) / longer;
                }
                let (x0, y0) = (
                    0.5 * (page.width - scale * cw),
                    0.5 * (page.height - scale * ch),
                );
                Ok(Layout::placed(page, scale, c, [x0, y0]))
            }
            None => {
                let long_mm = f64::from(size_px.max(1)) * MM_PER_PX;
                let (scale, m) = match margin {
                    Some(m) => {
                        if long_mm - 2.0 * m <= 0.0 {
                            return Err(Error::Usage(format!(
                                "--margin {m} mm leaves no room on a {long_mm:.1} mm drawing \
                                 (--size {size_px})"
                            )));
                        }
                        ((long_mm - 2.0 * m) / longer, m)
                    }
                    None => {
                        let scale = long_mm / frame.rect.longer_side().max(f64::MIN_POSITIVE);
                        (scale, (c.xmin - frame.rect.xmin) * scale)
                    }
                };
                let page = PageSize {
                    width: scale * cw + 2.0 * m,
                    height: scale * ch + 2.0 * m,
                };
                Ok(Layout::placed(page, scale, c, [m, m]))
            }
        }
    }

    /// The layout with the content's top-left corner at `origin` on the page.
    fn placed(page: PageSize, scale: f64, content: Rect, origin: Pt2) -> Layout {
        let area = Rect::new(
            origin[0],
            origin[1],
            origin[0] + scale * content.width().max(0.0),
            origin[1] + scale * content.height().max(0.0),
        );
        Layout {
            page,
            scale,
            content,
            area,
        }
    }

    /// The page point (mm, y down) of a screen point.
    #[inline]
    pub(crate) fn to_page(self, p: Pt2) -> Pt2 {
        [
            self.area.xmin + self.scale * (p[0] - self.content.xmin),
            self.area.ymin + self.scale * (self.content.ymax - p[1]),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(content: Rect) -> Frame {
        let unit = content.longer_side();
        Frame {
            rect: content.padded(0.05 * unit),
            unit,
            content,
        }
    }

    #[test]
    fn named_and_custom_pages() {
        assert_eq!(PageSize::parse("A4").unwrap(), PageSize::A4);
        assert_eq!(PageSize::parse("letter").unwrap().width, 215.9);
        let p = PageSize::parse("200x150mm").unwrap();
        assert_eq!((p.width, p.height), (200.0, 150.0));
        assert_eq!(PageSize::parse("90X60").unwrap().height, 60.0);
        assert_eq!(PageSize::A4.landscape().width, 297.0);
        assert_eq!(PageSize::parse("a5").unwrap(), PageSize::A5);
        assert_eq!(PageSize::parse(" A6 ").unwrap().height, 148.0);
        assert_eq!(PageSize::A6.landscape().width, 148.0);
        for bad in ["a5x", "0x10mm", "10x-1", "nanxnan", "x", "b4"] {
            assert!(PageSize::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn drawing_is_fitted_and_centred_on_a_page() {
        // A 2:1 drawing on A4 portrait with 10 mm margins: width-limited, 190 mm wide.
        let l = Layout::new(
            &frame(Rect::new(-1., 0., 3., 2.)),
            Some(PageSize::A4),
            None,
            1024,
        )
        .unwrap();
        assert_eq!(l.scale, 190.0 / 4.0);
        assert_eq!(l.area, Rect::new(10.0, 101.0, 200.0, 196.0));
        assert_eq!(l.to_page([-1., 2.]), [10.0, 101.0], "top-left");
        assert_eq!(l.to_page([3., 0.]), [200.0, 196.0], "bottom-right");
        assert!(Layout::new(
            &frame(Rect::new(0., 0., 1., 1.)),
            Some(PageSize::A4),
            Some(105.0),
            9
        )
        .is_err());
    }

    #[test]
    fn without_a_page_the_longer_side_is_size_css_pixels() {
        let f = frame(Rect::new(0., 0., 10., 5.));
        let l = Layout::new(&f, None, None, 1100).unwrap();
        let long = 1100.0 * MM_PER_PX;
        assert!((l.page.width - long).abs() < 1e-9 * long);
        assert!((l.page.height - long * 6.0 / 11.0).abs() < 1e-9 * long);
        // An explicit margin in mm.
        let l = Layout::new(&f, None, Some(5.0), 1100).unwrap();
        assert!((l.page.width - long).abs() < 1e-9 * long);
        assert_eq!(l.area.xmin, 5.0);
    }
}
