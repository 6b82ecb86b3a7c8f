//! The margin of one Plücker value at `Decide`'s input, in units of its last bit L, bit for
//! bit the margin of `hw_model::dual::plucker::decide_inputs`: the wired fixed part
//! (`plucker::MarginConstants`: the coarser dot's bound and the units), the finer dot's
//! bound C shifted right by its grid's distance below L and rounded up, and the fallback's
//! term m_F·2^y (`plucker::fallback_term`, y = its shift + ΣE − L) rounded up; `over` when
//! that term would reach 2^(MB − 1) (the model forwards). N_w, which the fallback does
//! not compute, has no fallback term ([`PluckerMargin::dots_only`]). One register stage.

use hw_model::dual::plucker::{fallback_term, MarginConstants};
use rust_hdl::prelude::*;

use super::align_add::EXP_BITS;

/// Bits of a dot's distance below the value's last bit.
pub const BELOW_BITS: usize = EXP_BITS + 2;
/// Bits of y's field and its bias: y + [`Y_BIAS`].
pub const Y_BITS: usize = EXP_BITS + 2;
pub const Y_BIAS: i64 = 1 << (Y_BITS - 1);

/// Cycles from the inputs to `margin` and `over`.
pub const LATENCY: usize = 1;

/// The margin (MB bits) of a value with up to two dots.
#[derive(LogicBlock)]
pub struct PluckerMargin<const MB: usize> {
    pub clock: Signal<In, Clock>,
    /// The finer dot's distance below the value's last bit.
    pub below: Signal<In, Bits<BELOW_BITS>>,
    /// y + [`Y_BIAS`].
    pub y: Signal<In, Bits<Y_BITS>>,
    pub margin: Signal<Out, Bits<MB>>,
    pub over: Signal<Out, Bit>,
    margin_reg: DFF<Bits<MB>>,
    over_reg: DFF<Bit>,
    /// The finer dot's C − 1: ceil(C·2^-d) = ((C − 1) >> d) + 1 for C ≥ 1; a value of one
    /// dot has none.
    less: Constant<Bits<MB>>,
    present: Constant<Bit>,
    /// The fallback's term is charged.
    charged: Constant<Bit>,
    fixed: Constant<Bits<MB>>,
    one: Constant<Bits<MB>>,
    /// m_F and m_F − 1; y = 0 and the first y whose term reaches 2^(MB − 1).
    f_m: Constant<Bits<MB>>,
    f_less: Constant<Bits<MB>>,
    y_zero: Constant<Bits<Y_BITS>>,
    y_over: Constant<Bits<Y_BITS>>,
    term: Signal<Local, Bits<MB>>,
    fallback: Signal<Local, Bits<MB>>,
}

impl<const MB: usize> PluckerMargin<MB> {
    /// The margin of a value with the wired constants `c`.
    pub fn new(c: MarginConstants) -> Self {
        Self::of(c, true)
    }

    /// The margin of a value with the wired constants `c` and no fallback term (`y` unread,
    /// `over` low).
    pub fn dots_only(c: MarginConstants) -> Self {
        Self::of(c, false)
    }

    fn of(c: MarginConstants, charged: bool) -> Self {
        let wire = |v: i128| -> Constant<Bits<MB>> {
            assert!((0..1i128 << MB).contains(&v), "{v} does not fit {MB} bits");
            Constant::new((v as u64).to_bits())
        };
        let f = fallback_term();
        let f_bits = (128 - f.m.leading_zeros()) as i64;
        let y_field = |y: i64| Constant::new(((y + Y_BIAS) as u64).to_bits());
        Self {
            clock: Default::default(),
            below: Default::default(),
            y: Default::default(),
            margin: Default::default(),
            over: Default::default(),
            margin_reg: Default::default(),
            over_reg: Default::default(),
            less: wire((c.fine - 1).max(0)),
            present: Constant::new(c.fine > 0),
            charged: Constant::new(charged),
            fixed: wire(c.fixed),
            one: wire(1),
            f_m: wire(f.m),
            f_less: wire(f.m - 1),
            y_zero: y_field(0),
            y_over: y_field(MB as i64 - f_bits),
            term: Default::default(),
            fallback: Default::default(),
        }
    }
}

impl<const MB: usize> Logic for PluckerMargin<MB> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, margin_reg, over_reg);
        self.term.next = 0.into();
        if self.present.val() {
            self.term.next = (self.less.val() >> self.below.val()) + self.one.val();
        }
        // m_F·2^y rounded up, while below 2^(MB − 1).
        self.over_reg.d.next = self.charged.val() && self.y.val() >= self.y_over.val();
        self.fallback.next = 0.into();
        if self.charged.val() && self.y.val() < self.y_over.val() {
            if self.y.val() >= self.y_zero.val() {
                self.fallback.next = self.f_m.val() << (self.y.val() - self.y_zero.val());
            } else {
                self.fallback.next =
                    (self.f_less.val() >> (self.y_zero.val() - self.y.val())) + self.one.val();
            }
        }
        self.margin_reg.d.next = self.fixed.val() + self.term.val() + self.fallback.val();
        self.margin.next = self.margin_reg.q.val();
        self.over.next = self.over_reg.q.val();
    }
}
