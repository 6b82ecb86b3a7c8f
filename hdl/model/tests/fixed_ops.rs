//! Fixed-point operators against exact i128 / rational arithmetic written here from the SPEC,
//! for every quantisation × overflow combination.

mod common;

use common::rng;
use hw_model::{catalogue, Format, Overflow, Quant};
use rand::Rng;

/// (width, int) pairs: the catalogue's, plus the extremes of the allowed range.
fn layouts() -> Vec<(u32, u32)> {
    let mut v: Vec<(u32, u32)> = catalogue()
        .iter()
        .filter_map(|n| match n.format {
            Format::Fixed { int, frac, .. } => Some((int + frac, int)),
            Format::Float { .. } => None,
        })
        .collect();
    v.extend([(2, 1), (2, 2), (8, 8), (33, 1), (53, 20), (64, 2), (64, 40)]);
    v.sort();
    v.dedup();
    v
}

fn all_modes(width: u32, int: u32) -> impl Iterator<Item = Format> {
    [Quant::Trn, Quant::Rnd].into_iter().flat_map(move |quant| {
        [Overflow::Wrap, Overflow::Sat]
            .into_iter()
            .map(move |overflow| Format::Fixed {
                int,
                frac: width - int,
                quant,
                overflow,
            })
    })
}

/// The oracle's view of one format.
struct Spec {
    w: u32,
    f: u32,
    quant: Quant,
    overflow: Overflow,
}

impl Spec {
    fn of(format: &Format) -> Spec {
        match *format {
            Format::Fixed {
                int,
                frac,
                quant,
                overflow,
            } => Spec {
                w: int + frac,
                f: frac,
                quant,
                overflow,
            },
            Format::Float { .. } => unreachable!(),
        }
    }
    fn min(&self) -> i128 {
        -(1i128 << (self.w - 1))
    }
    fn max(&self) -> i128 {
        (1i128 << (self.w - 1)) - 1
    }
    fn value(&self, bits: u64) -> i128 {
        let b = bits as i128;
        if b >= 1i128 << (self.w - 1) {
            b - (1i128 << self.w)
        } else {
            b
        }
    }
    fn encode(&self, v: i128) -> u64 {
        assert!((self.min()..=self.max()).contains(&v));
        v.rem_euclid(1i128 << self.w) as u64
    }
    /// Brings an exact integer into range.
    fn fit(&self, v: i128) -> u64 {
        let v = match self.overflow {
            Overflow::Sat => v.clamp(self.min(), self.max()),
            Overflow::Wrap => {
                let m = v.rem_euclid(1i128 << self.w);
                if m > self.max() {
                    m - (1i128 << self.w)
                } else {
                    m
                }
            }
        };
        self.encode(v)
    }
    /// num/den (den > 0) to an integer: floor, or floor(num/den + 1/2).
    fn quantise(&self, num: i128, den: i128) -> i128 {
        match self.quant {
            Quant::Trn => num.div_euclid(den),
            Quant::Rnd if den % 2 == 0 => (num + den / 2).div_euclid(den),
            Quant::Rnd => (2 * num + den).div_euclid(2 * den),
        }
    }
    fn edges(&self) -> Vec<u64> {
        let mut v = vec![
            0,
            1,
            self.max(),
            self.min(),
            self.min() + 1,
            -1,
            self.max() - 1,
        ];
        if self.f >= 1 {
            v.push(1i128 << (self.f - 1)); // 1/2
            v.push(-(1i128 << (self.f - 1)));
        }
        v.extend([
            1i128 << self.f,
            -(1i128 << self.f),
            3i128 << self.f.saturating_sub(1),
        ]); // 1, −1, 1.5
        v.into_iter()
            .filter(|x| (self.min()..=self.max()).contains(x))
            .map(|x| self.encode(x))
            .collect()
    }
    fn random(&self, r: &mut impl Rng) -> u64 {
        let bits = r.gen::<u64>() & (u64::MAX >> (64 - self.w));
        match r.gen_range(0..4) {
            0 => bits >> r.gen_range(0..self.w), // small magnitudes
            1 => self.fit(-(self.value(bits >> r.gen_range(0..self.w)))),
            _ => bits,
        }
    }
}

fn check_all(format: &Format, s: &Spec, a: u64, b: u64) {
    let (x, y) = (s.value(a), s.value(b));
    let ctx = || format!("{format}: a={a:#x} ({x}) b={b:#x} ({y})");
    assert_eq!(format.add(a, b), s.fit(x + y), "add {}", ctx());
    assert_eq!(format.sub(a, b), s.fit(x - y), "sub {}", ctx());
    assert_eq!(format.neg(a), s.fit(-x), "neg {}", ctx());
    assert_eq!(
        format.mul(a, b),
        s.fit(s.quantise(x * y, 1i128 << s.f)),
        "mul {}",
        ctx()
    );
    let recip = if x == 0 {
        s.encode(s.max())
    } else {
        // 1/x in units of 2^-f is 2^(2f)/x; make the denominator positive
        let num = 1i128 << (2 * s.f);
        s.fit(if x > 0 {
            s.quantise(num, x)
        } else {
            s.quantise(-num, -x)
        })
    };
    assert_eq!(format.recip(a), recip, "recip {}", ctx());
    assert_eq!(format.lt(a, b), x < y, "lt {}", ctx());
    assert!(!format.is_nan(a));
    // to_f32: `as f32` from an integer rounds once (RNE); the power-of-two scale is exact.
    let want = (x as f32) * 2f32.powi(-(s.f as i32));
    assert_eq!(
        format.to_f32(a).to_bits(),
        want.to_bits(),
        "to_f32 {}",
        ctx()
    );
    assert_eq!(
        format.to_f64(a),
        x as f64 * 2f64.powi(-(s.f as i32)),
        "to_f64 {}",
        ctx()
    );
}

#[test]
fn operators_match_exact_arithmetic_in_every_mode() {
    let mut r = rng(11);
    for (w, i) in layouts() {
        for format in all_modes(w, i) {
            format.validate().unwrap();
            let s = Spec::of(&format);
            let edges = s.edges();
            for &a in &edges {
                for &b in &edges {
                    check_all(&format, &s, a, b);
                }
            }
            for _ in 0..2_000 {
                let (a, b) = (s.random(&mut r), s.random(&mut r));
                check_all(&format, &s, a, b);
            }
        }
    }
}

/// from_f32 against the exact value x·2^f (exact in f64), quantised and fitted by the oracle.
fn from_f32_oracle(s: &Spec, x: f32) -> u64 {
    if x.is_nan() || x.is_subnormal() || x == 0.0 {
        return 0;
    }
    if x.is_infinite() {
        return s.encode(if x > 0.0 { s.max() } else { s.min() });
    }
    let scaled = x as f64 * 2f64.powi(s.f as i32);
    if scaled.abs() >= 2f64.powi(100) {
        // a multiple of 2^76 (24-bit significand): 0 modulo 2^w, or clamped
        return match s.overflow {
            Overflow::Wrap => 0,
            Overflow::Sat => s.encode(if x > 0.0 { s.max() } else { s.min() }),
        };
    }
    let q = match s.quant {
        Quant::Trn => scaled.floor(),
        Quant::Rnd => (scaled + 0.5).floor(), // exact: scaled < 2^100 has ≤ 24 significant bits
    };
    s.fit(q as i128)
}

#[test]
fn from_f32_quantises_and_fits_in_every_mode() {
    let mut r = rng(12);
    let specials = [
        0.0f32,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -0.5,
        1.5,
        -1.5,
        2.5,
        -2.5,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        1e-45,
        -1e-45,
        1e-8,
        -1e-8,
    ];
    for (w, i) in layouts() {
        for format in all_modes(w, i) {
            let s = Spec::of(&format);
            let lsb = 2f32.powi(-(s.f as i32));
            let extra = [
                lsb / 2.0,
                -lsb / 2.0,
                lsb * 1.5,
                -lsb * 1.5,
                lsb * 0.75,
                -lsb * 0.25,
            ];
            let randoms = (0..4_000).map(|k| {
                if k % 2 == 0 {
                    f32::from_bits(r.gen())
                } else {
                    // magnitudes around the format's range
                    let mag = 2f32.powi(r.gen_range(-(s.f as i32) - 3..=(w - s.f) as i32 + 3));
                    mag * r.gen_range(-2.0f32..2.0)
                }
            });
            for x in specials.into_iter().chain(extra).chain(randoms) {
                let want = from_f32_oracle(&s, x);
                assert_eq!(
                    format.from_f32(x),
                    want,
                    "{format} from_f32({x:e} = {:#x})",
                    x.to_bits()
                );
                // values of the format survive a round trip through fp32 when fp32 holds them
                if w <= 24 {
                    assert_eq!(
                        format.from_f32(format.to_f32(want)),
                        want,
                        "{format} round trip {want:#x}"
                    );
                }
            }
        }
    }
}

/// The soak: 1M random operand pairs per operator and catalogue fixed format (all operators
/// per pair) and 1M from_f32 conversions each. Run with
/// `cargo test --release -p hw-model --test fixed_ops -- --ignored soak`.
#[test]
#[ignore]
fn soak_catalogue_fixed_1m_per_op() {
    let mut r = rng(13);
    for named in catalogue() {
        if let Format::Float { .. } = named.format {
            continue;
        }
        let s = Spec::of(&named.format);
        for _ in 0..1_000_000 {
            let (a, b) = (s.random(&mut r), s.random(&mut r));
            check_all(&named.format, &s, a, b);
            let x = f32::from_bits(r.gen());
            assert_eq!(
                named.format.from_f32(x),
                from_f32_oracle(&s, x),
                "{} from_f32({x:e})",
                named.name
            );
        }
    }
}
