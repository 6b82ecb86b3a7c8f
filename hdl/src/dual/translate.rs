//! Step 1 of the bfp filter: a − b of two fp32 numbers as an integer, bit for bit
//! `hw_model::dual::bfp::translate`. Both significands are signed and moved up by the
//! guard bits; the one with the smaller exponent is shifted right arithmetically by the
//! exponent difference (floor: its lost bits are dropped); then one 29-bit subtraction. No
//! rounding and no normalisation. One register stage: the result the cycle after its inputs.

use hw_model::dual::bfp::GUARD_BITS;
use rust_hdl::prelude::*;

/// Width of the difference: a 24-bit significand, the guard bits, a sign and a carry.
pub const DIFF_BITS: usize = 24 + GUARD_BITS as usize + 2;

/// `d`·2^(`e` − 150 − GUARD_BITS) = a − b (subnormals read as 0); `d` is two's complement,
/// `e` the larger exponent field.
#[derive(LogicBlock)]
pub struct Translate {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<32>>,
    pub b: Signal<In, Bits<32>>,
    pub d: Signal<Out, Bits<DIFF_BITS>>,
    pub e: Signal<Out, Bits<8>>,
    d_reg: DFF<Bits<DIFF_BITS>>,
    e_reg: DFF<Bits<8>>,
    hidden: Constant<Bits<DIFF_BITS>>,
    one: Constant<Bits<DIFF_BITS>>,
    /// The difference's sign bit (a Rust constant as a bit index would reach the Verilog as
    /// an undefined name).
    sign: Constant<Bits<DIFF_BITS>>,
    guard: Constant<Bits<8>>,
    /// The largest shift that still matters: beyond it only the sign is left.
    max_shift: Constant<Bits<8>>,
    ea: Signal<Local, Bits<8>>,
    eb: Signal<Local, Bits<8>>,
    /// The signed significands, moved up by the guard bits.
    sa: Signal<Local, Bits<DIFF_BITS>>,
    sb: Signal<Local, Bits<DIFF_BITS>>,
    shift: Signal<Local, Bits<8>>,
    /// The operand with the smaller exponent, before and after its arithmetic shift.
    lesser: Signal<Local, Bits<DIFF_BITS>>,
    shifted: Signal<Local, Bits<DIFF_BITS>>,
}

impl Default for Translate {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            d: Default::default(),
            e: Default::default(),
            d_reg: Default::default(),
            e_reg: Default::default(),
            hidden: Constant::new((1u64 << 23).to_bits()),
            one: Constant::new(1u64.to_bits()),
            sign: Constant::new((1u64 << (DIFF_BITS - 1)).to_bits()),
            guard: Constant::new((GUARD_BITS as u64).to_bits()),
            max_shift: Constant::new(((DIFF_BITS - 1) as u64).to_bits()),
            ea: Default::default(),
            eb: Default::default(),
            sa: Default::default(),
            sb: Default::default(),
            shift: Default::default(),
            lesser: Default::default(),
            shifted: Default::default(),
        }
    }
}

impl Logic for Translate {
    #[hdl_gen]
    fn update(&mut self) {
        self.d_reg.clock.next = self.clock.val();
        self.e_reg.clock.next = self.clock.val();
        self.ea.next = self.a.val().get_bits::<8>(23);
        self.eb.next = self.b.val().get_bits::<8>(23);
        // Significand with its hidden bit (0 for a zero or a flushed subnormal), signed.
        self.sa.next = 0.into();
        if self.ea.val().any() {
            self.sa.next = (self.hidden.val()
                | bit_cast::<DIFF_BITS, 23>(self.a.val().get_bits::<23>(0)))
                << self.guard.val();
        }
        if self.a.val().get_bit(31) {
            self.sa.next = !self.sa.val() + self.one.val();
        }
        self.sb.next = 0.into();
        if self.eb.val().any() {
            self.sb.next = (self.hidden.val()
                | bit_cast::<DIFF_BITS, 23>(self.b.val().get_bits::<23>(0)))
                << self.guard.val();
        }
        if self.b.val().get_bit(31) {
            self.sb.next = !self.sb.val() + self.one.val();
        }
        if self.ea.val() >= self.eb.val() {
            self.shift.next = self.ea.val() - self.eb.val();
            self.lesser.next = self.sb.val();
            self.e_reg.d.next = self.ea.val();
        } else {
            self.shift.next = self.eb.val() - self.ea.val();
            self.lesser.next = self.sa.val();
            self.e_reg.d.next = self.eb.val();
        }
        if self.shift.val() > self.max_shift.val() {
            self.shift.next = self.max_shift.val();
        }
        // Arithmetic shift right: a negative value's complement shifts in zeros.
        self.shifted.next = self.lesser.val() >> self.shift.val();
        if (self.lesser.val() & self.sign.val()).any() {
            self.shifted.next = !(!self.lesser.val() >> self.shift.val());
        }
        if self.ea.val() >= self.eb.val() {
            self.d_reg.d.next = self.sa.val() - self.shifted.val();
        } else {
            self.d_reg.d.next = self.shifted.val() - self.sb.val();
        }
        self.d.next = self.d_reg.q.val();
        self.e.next = self.e_reg.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hw_model::dual::bfp::{translate, Fx};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// The block's answer for (a, b), as the model's value.
    fn run(uut: &mut Translate, a: f32, b: f32) -> Fx {
        uut.a.next = a.to_bits().to_bits();
        uut.b.next = b.to_bits().to_bits();
        uut.clock.next = Clock { clk: false };
        assert!(simulate(uut, 100));
        uut.clock.next = Clock { clk: true };
        assert!(simulate(uut, 100));
        let raw = uut.d.val().to_u64() as i64;
        // Sign-extend the two's-complement difference.
        let shift = 64 - DIFF_BITS;
        Fx {
            m: i128::from((raw << shift) >> shift),
            e: uut.e.val().to_u64() as i32 - 150 - GUARD_BITS,
        }
    }

    /// Random fp32 bit patterns (any exponent, subnormals, zeros of both signs) and pairs of
    /// nearby exponents, where the guard bits matter.
    #[test]
    fn translation_equals_the_model_bit_for_bit() {
        let mut uut = Translate::default();
        uut.connect_all();
        let mut rng = StdRng::seed_from_u64(17);
        let finite = |rng: &mut StdRng| loop {
            let x = f32::from_bits(rng.gen());
            if x.is_finite() {
                return x;
            }
        };
        let special = [
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            f32::MIN_POSITIVE,
            1e-40,
            -1e-40,
            f32::MAX,
        ];
        for k in 0..20_000 {
            let a = if k % 7 == 0 {
                special[k % special.len()]
            } else {
                finite(&mut rng)
            };
            let near = a * rng.gen_range(-40.0f32..40.0);
            let b = match k % 3 {
                0 => finite(&mut rng),
                // Within a few binades of a, either sign.
                1 if near.is_finite() => near,
                _ => special[(k / 3) % special.len()],
            };
            let want = translate(a, b).unwrap();
            assert_eq!(run(&mut uut, a, b), want, "{a:e} - {b:e}");
        }
    }

    /// Its Verilog is what Vivado would read: Verilator lints it clean (reserved words and
    /// widths included).
    #[test]
    fn verilog_passes_verilator_lint() {
        let mut uut = Translate::default();
        uut.connect_all();
        if let Err(e) = crate::verilog::verilator_lint(&generate_verilog(&uut)) {
            panic!("verilator lint failed:\n{e}");
        }
    }
}
