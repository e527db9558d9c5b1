//! Colours of the pictures: `#rrggbb`, `#rgb` or a few names, for `--background`.

use crate::error::{Error, Result};

/// An opaque sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub [u8; 3]);

impl Rgb {
    /// White.
    pub const WHITE: Rgb = Rgb([255, 255, 255]);

    /// A grey level (0 black).
    pub fn grey(g: u8) -> Rgb {
        Rgb([g, g, g])
    }

    /// Parses `#rrggbb`, `#rgb` (the `#` optional) or one of white, black, grey/gray,
    /// ivory, cream.
    pub fn parse(s: &str) -> Result<Rgb> {
        let t = s.trim().to_ascii_lowercase();
        let named = match t.as_str() {
            "white" => Some([255, 255, 255]),
            "black" => Some([0, 0, 0]),
            "grey" | "gray" => Some([128, 128, 128]),
            "ivory" => Some([255, 255, 240]),
            "cream" => Some([255, 253, 208]),
            _ => None,
        };
        if let Some(c) = named {
            return Ok(Rgb(c));
        }
        let hex = t.strip_prefix('#').unwrap_or(&t);
        let bad = || {
            Error::Usage(format!(
                "colour {s}: expected #rrggbb, #rgb or white, black, grey, ivory, cream"
            ))
        };
        if !hex.chars().all(|c| c.is_ascii_hexdigit()) {
            return Err(bad());
        }
        let digit = |i: usize| u8::from_str_radix(&hex[i..=i], 16).map_err(|_| bad());
        match hex.len() {
            6 => {
                let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).map_err(|_| bad());
                Ok(Rgb([byte(0)?, byte(2)?, byte(4)?]))
            }
            3 => Ok(Rgb([digit(0)? * 17, digit(1)? * 17, digit(2)? * 17])),
            _ => Err(bad()),
        }
    }

    /// `#rrggbb`.
    pub fn hex(&self) -> String {
        let [r, g, b] = self.0;
        format!("#{r:02x}{g:02x}{b:02x}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_hex_short_hex_and_names() {
        assert_eq!(Rgb::parse("#fffff0").unwrap(), Rgb([255, 255, 240]));
        assert_eq!(Rgb::parse("abc").unwrap(), Rgb([0xaa, 0xbb, 0xcc]));
        assert_eq!(Rgb::parse("White").unwrap(), Rgb::WHITE);
        assert_eq!(Rgb::grey(200).hex(), "#c8c8c8");
        for bad in ["#12345", "zzzzzz", "", "#ééé"] {
            assert!(Rgb::parse(bad).is_err(), "{bad}");
        }
    }
}
