//! The named formats: the ones the rust-hdl operators are instantiated for and the CLI lists.

use crate::format::{Format, FormatError, Overflow, Quant};

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

use Overflow::{Sat, Wrap};
use Quant::{Rnd, Trn};

static CATALOGUE: &[NamedFormat] = &[
    float(
        "fp32",
        8,
        23,
        "IEEE binary32 (E8M23), the thesis' software format",
    ),
    float(
        "fp24",
        8,
        15,
        "E8M15, fp32's range with 16-bit significands",
    ),
    float("bf16", 8, 7, "bfloat16 (E8M7)"),
    float("fp16", 5, 10, "IEEE binary16 (E5M10)"),
    fixed(
        "fx16_10",
        16,
        10,
        Trn,
        Wrap,
        "ap_fixed<16,10> (AP_TRN, AP_WRAP), thesis trial",
    ),
    fixed(
        "fx16_10_rnd_sat",
        16,
        10,
        Rnd,
        Sat,
        "ap_fixed<16,10,AP_RND,AP_SAT>, thesis trial",
    ),
    fixed(
        "fx16_13",
        16,
        13,
        Trn,
        Wrap,
        "ap_fixed<16,13> (AP_TRN, AP_WRAP), thesis trial",
    ),
    fixed(
        "fx16_13_rnd_sat",
        16,
        13,
        Rnd,
        Sat,
        "ap_fixed<16,13,AP_RND,AP_SAT>, thesis trial",
    ),
    fixed(
        "fx21_12",
        21,
        12,
        Trn,
        Wrap,
        "ap_fixed<21,12> (AP_TRN, AP_WRAP), thesis trial",
    ),
    fixed(
        "fx21_12_rnd_sat",
        21,
        12,
        Rnd,
        Sat,
        "ap_fixed<21,12,AP_RND,AP_SAT>, thesis trial",
    ),
    fixed(
        "fx25_10",
        25,
        10,
        Trn,
        Wrap,
        "ap_fixed<25,10> (AP_TRN, AP_WRAP), thesis trial",
    ),
    fixed(
        "fx25_10_rnd_sat",
        25,
        10,
        Rnd,
        Sat,
        "ap_fixed<25,10,AP_RND,AP_SAT>, thesis trial",
    ),
    fixed(
        "fx32_16",
        32,
        16,
        Trn,
        Wrap,
        "ap_fixed<32,16> (AP_TRN, AP_WRAP), thesis trial",
    ),
    fixed(
        "fx32_16_rnd_sat",
        32,
        16,
        Rnd,
        Sat,
        "ap_fixed<32,16,AP_RND,AP_SAT>, thesis trial",
    ),
    fixed(
        "fx32_20",
        32,
        20,
        Trn,
        Wrap,
        "ap_fixed<32,20> (AP_TRN, AP_WRAP), thesis trial",
    ),
    fixed(
        "fx32_20_rnd_sat",
        32,
        20,
        Rnd,
        Sat,
        "ap_fixed<32,20,AP_RND,AP_SAT>, thesis trial",
    ),
];

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
