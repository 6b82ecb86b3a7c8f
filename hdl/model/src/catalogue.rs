//! The named formats: the ones the hardware has rust-hdl operators for, which the CLI lists.
//!
//! [`hw_formats!`] is the one list: this crate builds the catalogue from it, `hdl` builds one
//! operator module per entry from it, and [`HwFormat`] is an index into it.

use std::fmt;
use std::str::FromStr;

use crate::format::{Format, FormatError, Overflow, Quant};

/// Every hardware format, written once: `name: float(E, M), "description";` (E exponent bits,
/// M fraction bits) or `name: fixed(W, I, quantisation, overflow), "description";` (W bits in
/// all, I integer bits including the sign, as `ap_fixed<W, I>`). Calls `$callback!` with the
/// list; adding a format to the hardware is one line here.
#[macro_export]
macro_rules! hw_formats {
    ($callback:ident) => {
        $callback! {
            fp32: float(8, 23), "IEEE binary32 (E8M23), the thesis' software format";
            fp24: float(8, 15), "E8M15, fp32's range with 16-bit significands";
            bf16: float(8, 7), "bfloat16 (E8M7)";
            fp16: float(5, 10), "IEEE binary16 (E5M10)";
            fx16_10: fixed(16, 10, Trn, Wrap), "ap_fixed<16,10> (AP_TRN, AP_WRAP), thesis trial";
            fx16_10_rnd_sat: fixed(16, 10, Rnd, Sat), "ap_fixed<16,10,AP_RND,AP_SAT>, thesis trial";
            fx16_13: fixed(16, 13, Trn, Wrap), "ap_fixed<16,13> (AP_TRN, AP_WRAP), thesis trial";
            fx16_13_rnd_sat: fixed(16, 13, Rnd, Sat), "ap_fixed<16,13,AP_RND,AP_SAT>, thesis trial";
            fx21_12: fixed(21, 12, Trn, Wrap), "ap_fixed<21,12> (AP_TRN, AP_WRAP), thesis trial";
            fx21_12_rnd_sat: fixed(21, 12, Rnd, Sat), "ap_fixed<21,12,AP_RND,AP_SAT>, thesis trial";
            fx25_10: fixed(25, 10, Trn, Wrap), "ap_fixed<25,10> (AP_TRN, AP_WRAP), thesis trial";
            fx25_10_rnd_sat: fixed(25, 10, Rnd, Sat), "ap_fixed<25,10,AP_RND,AP_SAT>, thesis trial";
            fx32_16: fixed(32, 16, Trn, Wrap), "ap_fixed<32,16> (AP_TRN, AP_WRAP), thesis trial";
            fx32_16_rnd_sat: fixed(32, 16, Rnd, Sat), "ap_fixed<32,16,AP_RND,AP_SAT>, thesis trial";
            fx32_20: fixed(32, 20, Trn, Wrap), "ap_fixed<32,20> (AP_TRN, AP_WRAP), thesis trial";
            fx32_20_rnd_sat: fixed(32, 20, Rnd, Sat), "ap_fixed<32,20,AP_RND,AP_SAT>, thesis trial";
            e5m14: float(5, 14), "E5M14 (20 bits): fp16's range, 15-bit significands; >= 40 dB with the format-aware spawn and the leaf advance";
        }
    };
}

/// A catalogue entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NamedFormat {
    pub name: &'static str,
    pub format: Format,
    pub description: &'static str,
}

const fn float(name: &'static str, exp: u32, man: u32, description: &'static str) -> NamedFormat {
    NamedFormat {
        name,
        format: Format::Float { exp, man },
        description,
    }
}

/// `width` total bits, `int` integer bits including the sign, like ap_fixed<width, int>.
const fn fixed(
    name: &'static str,
    width: u32,
    int: u32,
    quant: Quant,
    overflow: Overflow,
    description: &'static str,
) -> NamedFormat {
    NamedFormat {
        name,
        format: Format::Fixed {
            int,
            frac: width - int,
            quant,
            overflow,
        },
        description,
    }
}

macro_rules! catalogue_table {
    ($($name:ident: $kind:ident($($arg:tt),*), $description:literal;)*) => {
        const CATALOGUE: &[NamedFormat] = {
            use Overflow::{Sat, Wrap};
            use Quant::{Rnd, Trn};
            &[$($kind(stringify!($name), $($arg),*, $description)),*]
        };
    };
}

hw_formats!(catalogue_table);

/// A format the hardware has operators for: an entry of the catalogue. Parse one with
/// `str::parse` (a catalogue name, or any spelling [`lookup`] takes that names an entry's
/// format); it prints and serialises as its catalogue name.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct HwFormat(u8);

impl HwFormat {
    /// IEEE fp32, the format of the accelerator's ports.
    pub const FP32: HwFormat = HwFormat::named("fp32");

    /// The entry called `name`; an unknown name fails to compile where used in a constant.
    pub const fn named(name: &str) -> HwFormat {
        let mut i = 0;
        while i < CATALOGUE.len() {
            if str_eq(CATALOGUE[i].name, name) {
                return HwFormat(i as u8);
            }
            i += 1;
        }
        panic!("no such hardware format")
    }

    /// Every hardware format, in catalogue order.
    pub fn all() -> impl ExactSizeIterator<Item = HwFormat> + Clone {
        (0..CATALOGUE.len() as u8).map(HwFormat)
    }

    /// The catalogue index: the format code of the CONFIG register and the C header.
    pub fn code(self) -> u8 {
        self.0
    }

    /// The format of a CONFIG register's format code.
    pub fn from_code(code: u8) -> Option<HwFormat> {
        (usize::from(code) < CATALOGUE.len()).then_some(HwFormat(code))
    }

    /// The hardware format whose arithmetic is `format`, if the hardware has one.
    pub fn of(format: Format) -> Option<HwFormat> {
        HwFormat::all().find(|h| h.format() == format)
    }

    pub fn entry(self) -> &'static NamedFormat {
        &CATALOGUE[usize::from(self.0)]
    }

    pub fn name(self) -> &'static str {
        self.entry().name
    }

    pub fn format(self) -> Format {
        self.entry().format
    }
}

const fn str_eq(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

impl fmt::Display for HwFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Debug for HwFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for HwFormat {
    type Err = FormatError;

    fn from_str(s: &str) -> Result<Self, FormatError> {
        HwFormat::of(lookup(s)?).ok_or_else(|| no_hardware(s.trim()))
    }
}

impl TryFrom<Format> for HwFormat {
    type Error = FormatError;

    fn try_from(format: Format) -> Result<Self, FormatError> {
        HwFormat::of(format).ok_or_else(|| no_hardware(&format.to_string()))
    }
}

fn no_hardware(name: &str) -> FormatError {
    FormatError::NoHardware {
        name: name.to_string(),
    }
}

/// The catalogue's names, comma-separated (for messages).
pub(crate) fn names() -> String {
    CATALOGUE
        .iter()
        .map(|e| e.name)
        .collect::<Vec<_>>()
        .join(", ")
}

impl serde::Serialize for HwFormat {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for HwFormat {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

/// Every named format, in listing order.
pub fn catalogue() -> &'static [NamedFormat] {
    CATALOGUE
}

/// A catalogue name (case-insensitive) or a generic spelling: `e5m10`, `fx<16,10>` or
/// `fx16_10`, each fixed spelling optionally followed by `_rnd` and/or `_sat`.
pub fn lookup(name: &str) -> Result<Format, FormatError> {
    let lower = name.trim().to_ascii_lowercase();
    if let Some(entry) = CATALOGUE.iter().find(|e| e.name == lower) {
        return Ok(entry.format);
    }
    let format = match (parse_float(&lower), parse_fixed(&lower)) {
        (Some(format), _) => format,
        (None, Some((width, int, quant, overflow))) => {
            let frac = width
                .checked_sub(int)
                .ok_or_else(|| FormatError::Impossible {
                    name: name.to_string(),
                    why: format!("{int} integer bits exceed the total width {width}"),
                })?;
            Format::Fixed {
                int,
                frac,
                quant,
                overflow,
            }
        }
        (None, None) => return Err(FormatError::Unknown(name.to_string())),
    };
    format.validate()?;
    Ok(format)
}

/// `e<exp>m<man>`.
fn parse_float(s: &str) -> Option<Format> {
    let (exp, man) = s.strip_prefix('e')?.split_once('m')?;
    Some(Format::Float {
        exp: parse_u32(exp)?,
        man: parse_u32(man)?,
    })
}

/// `fx<W,I>` or `fxW_I`, then `_rnd`, `_sat` in any order (each at most once):
/// (width, integer bits, quantisation, overflow).
fn parse_fixed(s: &str) -> Option<(u32, u32, Quant, Overflow)> {
    let rest = s.strip_prefix("fx")?;
    let (width, int, mut rest) = if let Some(inner) = rest.strip_prefix('<') {
        let (args, tail) = inner.split_once('>')?;
        let (w, i) = args.split_once(',')?;
        (parse_u32(w.trim())?, parse_u32(i.trim())?, tail)
    } else {
        let (w, tail) = rest.split_once('_')?;
        let int_len = tail
            .find(|c: char| !c.is_ascii_digit())
            .unwrap_or(tail.len());
        (
            parse_u32(w)?,
            parse_u32(&tail[..int_len])?,
            &tail[int_len..],
        )
    };
    let (mut quant, mut overflow) = (Quant::Trn, Overflow::Wrap);
    while !rest.is_empty() {
        if let (Some(r), Quant::Trn) = (rest.strip_prefix("_rnd"), quant) {
            quant = Quant::Rnd;
            rest = r;
        } else if let (Some(r), Overflow::Wrap) = (rest.strip_prefix("_sat"), overflow) {
            overflow = Overflow::Sat;
            rest = r;
        } else {
            return None;
        }
    }
    Some((width, int, quant, overflow))
}

fn parse_u32(s: &str) -> Option<u32> {
    if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}
