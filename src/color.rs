//! Colours: Delphi's `clXxx` names (the paper's program was written in
//! Delphi) and `#rrggbb`.

use std::fmt;

/// An opaque RGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Rgb {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

impl Rgb {
    /// White: the layout's empty canvas.
    pub const WHITE: Rgb = Rgb::new(255, 255, 255);
    /// Black.
    pub const BLACK: Rgb = Rgb::new(0, 0, 0);

    /// A colour from its channels.
    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Rgb { r, g, b }
    }

    /// True for pure white, the colour that erases layout.
    pub fn is_white(&self) -> bool {
        *self == Rgb::WHITE
    }

    /// Parses `#rrggbb`, `#rgb` or a Delphi name (`clGreen`, case-insensitive).
    pub fn parse(text: &str) -> Option<Rgb> {
        if let Some(hex) = text.strip_prefix('#') {
            return parse_hex(hex);
        }
        let lower = text.to_ascii_lowercase();
        DELPHI
            .iter()
            .find(|(name, _)| name.eq_ignore_ascii_case(&lower))
            .map(|&(_, c)| c)
    }

    /// The Delphi name of this colour, if it has one.
    pub fn delphi_name(&self) -> Option<&'static str> {
        DELPHI.iter().find(|(_, c)| c == self).map(|&(n, _)| n)
    }

    /// The known colour name closest to `text` (for "did you mean").
    pub fn suggest(text: &str) -> Option<&'static str> {
        DELPHI
            .iter()
            .map(|(n, _)| {
                (
                    strsim::levenshtein(&n.to_ascii_lowercase(), &text.to_ascii_lowercase()),
                    *n,
                )
            })
            .filter(|(d, _)| *d <= 3)
            .min()
            .map(|(_, n)| n)
    }
}

impl fmt::Display for Rgb {
    /// `#rrggbb`, always lower case.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

fn parse_hex(hex: &str) -> Option<Rgb> {
    if !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let v = |s: &str| u8::from_str_radix(s, 16).ok();
    match hex.len() {
        6 => Some(Rgb::new(v(&hex[0..2])?, v(&hex[2..4])?, v(&hex[4..6])?)),
        3 => {
            let d = |i: usize| v(&hex[i..i + 1]).map(|x| x * 17);
            Some(Rgb::new(d(0)?, d(1)?, d(2)?))
        }
        _ => None,
    }
}

/// Delphi's standard `TColor` constants (VCL `Graphics.pas`).
const DELPHI: &[(&str, Rgb)] = &[
    ("clBlack", Rgb::new(0x00, 0x00, 0x00)),
    ("clMaroon", Rgb::new(0x80, 0x00, 0x00)),
    ("clGreen", Rgb::new(0x00, 0x80, 0x00)),
    ("clOlive", Rgb::new(0x80, 0x80, 0x00)),
    ("clNavy", Rgb::new(0x00, 0x00, 0x80)),
    ("clPurple", Rgb::new(0x80, 0x00, 0x80)),
    ("clTeal", Rgb::new(0x00, 0x80, 0x80)),
    ("clGray", Rgb::new(0x80, 0x80, 0x80)),
    ("clSilver", Rgb::new(0xC0, 0xC0, 0xC0)),
    ("clRed", Rgb::new(0xFF, 0x00, 0x00)),
    ("clLime", Rgb::new(0x00, 0xFF, 0x00)),
    ("clYellow", Rgb::new(0xFF, 0xFF, 0x00)),
    ("clBlue", Rgb::new(0x00, 0x00, 0xFF)),
    ("clFuchsia", Rgb::new(0xFF, 0x00, 0xFF)),
    ("clAqua", Rgb::new(0x00, 0xFF, 0xFF)),
    ("clWhite", Rgb::new(0xFF, 0xFF, 0xFF)),
    ("clMoneyGreen", Rgb::new(0xC0, 0xDC, 0xC0)),
    ("clSkyBlue", Rgb::new(0xA6, 0xCA, 0xF0)),
    ("clCream", Rgb::new(0xFF, 0xFB, 0xF0)),
    ("clMedGray", Rgb::new(0xA4, 0xA0, 0xA0)),
    ("clDkGray", Rgb::new(0x80, 0x80, 0x80)),
    ("clLtGray", Rgb::new(0xC0, 0xC0, 0xC0)),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delphi_names_and_hex() {
        assert_eq!(Rgb::parse("clGreen"), Some(Rgb::new(0, 128, 0)));
        assert_eq!(Rgb::parse("CLWHITE"), Some(Rgb::WHITE));
        assert_eq!(Rgb::parse("#ff8000"), Some(Rgb::new(255, 128, 0)));
        assert_eq!(Rgb::parse("#f80"), Some(Rgb::new(255, 136, 0)));
        assert_eq!(Rgb::parse("clGren"), None);
        assert_eq!(Rgb::suggest("clGren"), Some("clGreen"));
        assert_eq!(Rgb::new(0, 128, 0).to_string(), "#008000");
    }
}
