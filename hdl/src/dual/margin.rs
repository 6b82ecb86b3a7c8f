//! Step 4 of the bfp filter: the margin of one value a·trunc(b × c) (det, N_u, N_v or N_t)
//! in units of the value's last bit, bit for bit `hw_model::dual::bfp::margin_units`.
//!
//! The value's last bit is 2^(ΣE − K) with K fixed per kind (`value_shift`), so no term needs
//! an absolute exponent: the fixed term is a wired constant, and each of a, b, c and the cut
//! cross product x that dropped something adds its wired constant m·2^shift
//! (`margin_terms`) shifted right by its dropped distance `below` (`ToBlock::below`), rounded
//! up. Five constants, four 7-bit shifters and an adder tree; one register stage.

use hw_model::dual::bfp::{self, margin_terms, Vector, DET, N_T, N_U, N_V};
use rust_hdl::prelude::*;

use super::to_block::BELOW_BITS;
use super::WIDTH;

/// Cycles from `below` to `margin`.
pub const LATENCY: usize = 1;

/// Bits of the margin of `value` at [`WIDTH`], in units of the value's last bit
/// (`hw_model::dual::bfp::margin_bits`).
pub const fn margin_bits(value: [Vector; 4]) -> usize {
    bfp::margin_bits(WIDTH, value) as usize
}

/// det = e1·trunc(dir × e2).
pub type DetMargin = Margin<{ margin_bits(DET) }>;
/// N_u = s·trunc(dir × e2).
pub type UMargin = Margin<{ margin_bits(N_U) }>;
/// N_v = dir·trunc(s × e1).
pub type VMargin = Margin<{ margin_bits(N_V) }>;
/// N_t = e2·trunc(s × e1).
pub type TMargin = Margin<{ margin_bits(N_T) }>;

impl DetMargin {
    pub fn det() -> Self {
        Self::new(DET)
    }
}

impl UMargin {
    pub fn n_u() -> Self {
        Self::new(N_U)
    }
}

impl VMargin {
    pub fn n_v() -> Self {
        Self::new(N_V)
    }
}

impl TMargin {
    pub fn n_t() -> Self {
        Self::new(N_T)
    }
}

/// The margin (`MB` bits, [`margin_bits`]) of the value whose vectors a, b, c and x dropped
/// parts `below[k]` under their own block exponents (0: nothing dropped; else in
/// W_k − 1..=`DROP_WINDOW`, as `ToBlock` gives them).
#[derive(LogicBlock)]
pub struct Margin<const MB: usize> {
    pub clock: Signal<In, Clock>,
    pub below: [Signal<In, Bits<BELOW_BITS>>; 4],
    pub margin: Signal<Out, Bits<MB>>,
    margin_reg: DFF<Bits<MB>>,
    /// C_F·2^K rounded up to the last bit: always charged.
    fixed: Constant<Bits<MB>>,
    /// m·2^shift − 1 of each dropped term: ceil(y·2^-below) = ((y − 1) >> below) + 1 for
    /// y ≥ 1, so rounding up needs no sticky bit.
    less: [Constant<Bits<MB>>; 4],
    one: Constant<Bits<MB>>,
    term: [Signal<Local, Bits<MB>>; 4],
    pair: [Signal<Local, Bits<MB>>; 2],
}

impl<const MB: usize> Margin<MB> {
    /// The margin of `value` ([a, b, c, x]) at [`WIDTH`]; `MB` must be its
    /// [`margin_bits`], and every wired constant must fit it.
    pub fn new(value: [Vector; 4]) -> Self {
        assert_eq!(MB, margin_bits(value), "Margin<{MB}> of {value:?}");
        let terms = margin_terms(WIDTH, value, 1.0);
        let wire = |v: i128| -> Constant<Bits<MB>> {
            assert!((0..1i128 << MB).contains(&v), "{v} does not fit {MB} bits");
            Constant::new((v as u64).to_bits())
        };
        let fixed = terms.fixed.units(0).expect("the fixed term fits i128");
        let less = terms.dropped.map(|t| {
            assert!(
                t.m >= 1 && t.shift >= 0,
                "{t:?}: a wired term is m·2^shift, m ≥ 1"
            );
            wire((t.m << t.shift) - 1)
        });
        Self {
            clock: Default::default(),
            below: Default::default(),
            margin: Default::default(),
            margin_reg: Default::default(),
            fixed: wire(fixed),
            less,
            one: wire(1),
            term: Default::default(),
            pair: Default::default(),
        }
    }
}

impl<const MB: usize> Logic for Margin<MB> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, margin_reg);
        // Each vector that dropped something: its constant at its distance, rounded up.
        for k in 0..4 {
            self.term[k].next = 0.into();
            if self.below[k].val().any() {
                self.term[k].next = (self.less[k].val() >> self.below[k].val()) + self.one.val();
            }
        }
        // The adder tree.
        self.pair[0].next = self.term[0].val() + self.term[1].val();
        self.pair[1].next = self.term[2].val() + self.term[3].val();
        self.margin_reg.d.next = self.fixed.val() + self.pair[0].val() + self.pair[1].val();
        self.margin.next = self.margin_reg.q.val();
    }
}
