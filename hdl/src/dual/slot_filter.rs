//! A slot's filter lane as a [`super::slot::FilterSlot`] holds it: a [`BfpFilter`] or a
//! [`PluckerFilter`] behind ports without arrays (`query` as the register map's 16 fp32
//! words, a Plücker lane's `operands` as [`super::plucker_operands`] packs them), so that a
//! slot can keep either in a list (rust-hdl's Verilog takes no port array of a block in a
//! list). Wires only.

use hw_model::dual::FilterKind;
use rust_hdl::prelude::*;

use super::align_add::EXP_BITS;
use super::filter::{self, BfpFilter};
use super::plucker::{OFFSET_BITS, W, WT};
use super::plucker_filter::{self, PluckerFilter};
use super::plucker_operands::{CUT_WORD, OFFSET_WORD, OPERAND_BITS, OPERAND_WORDS, STORED_WORD};
use super::s_bound::CUT_BITS;
use crate::regmap::OPERAND_COUNT;
use crate::top::stream::QUERY_BITS;

// The kernels spell the words' places as literals.
const _: () = assert!(QUERY_BITS == 512 && OPERAND_COUNT == 16);
const _: () = assert!(
    OPERAND_WORDS == 48
        && OFFSET_WORD == 40
        && CUT_WORD == 43
        && STORED_WORD == 47
        && EXP_BITS <= 32
);

/// The filter lane of a slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlotFilter {
    /// The bfp filter on the query's fp32 words (`--dual-filter bfp`).
    Bfp,
    /// The Plücker filter on the query's stored vectors (`--dual-filter plucker-signs`).
    Plucker,
}

impl SlotFilter {
    /// Clock edges from a query to its decision.
    pub const fn latency(self) -> usize {
        match self {
            SlotFilter::Bfp => filter::LATENCY,
            SlotFilter::Plucker => plucker_filter::LATENCY,
        }
    }

    /// The model's filter, which the lane equals bit for bit.
    pub fn model_kind(self) -> FilterKind {
        match self {
            SlotFilter::Bfp => FilterKind::Bfp,
            SlotFilter::Plucker => FilterKind::Plucker,
        }
    }
}

/// A [`BfpFilter`] on a query's words.
#[derive(LogicBlock, Default)]
pub struct BfpWords {
    pub clock: Signal<In, Clock>,
    pub valid: Signal<In, Bit>,
    pub query: Signal<In, Bits<QUERY_BITS>>,
    pub valid_out: Signal<Out, Bit>,
    pub miss: Signal<Out, Bit>,
    pub forward: Signal<Out, Bit>,
    filter: BfpFilter,
}

impl Logic for BfpWords {
    #[hdl_gen]
    fn update(&mut self) {
        self.filter.clock.next = self.clock.val();
        self.filter.valid.next = self.valid.val();
        self.filter.orig[0].next = self.query.val().get_bits::<32>(0);
        self.filter.orig[1].next = self.query.val().get_bits::<32>(32);
        self.filter.orig[2].next = self.query.val().get_bits::<32>(64);
        self.filter.dir[0].next = self.query.val().get_bits::<32>(96);
        self.filter.dir[1].next = self.query.val().get_bits::<32>(128);
        self.filter.dir[2].next = self.query.val().get_bits::<32>(160);
        self.filter.v0[0].next = self.query.val().get_bits::<32>(192);
        self.filter.v0[1].next = self.query.val().get_bits::<32>(224);
        self.filter.v0[2].next = self.query.val().get_bits::<32>(256);
        self.filter.v1[0].next = self.query.val().get_bits::<32>(288);
        self.filter.v1[1].next = self.query.val().get_bits::<32>(320);
        self.filter.v1[2].next = self.query.val().get_bits::<32>(352);
        self.filter.v2[0].next = self.query.val().get_bits::<32>(384);
        self.filter.v2[1].next = self.query.val().get_bits::<32>(416);
        self.filter.v2[2].next = self.query.val().get_bits::<32>(448);
        self.filter.t_min.next = self.query.val().get_bits::<32>(480);
        self.valid_out.next = self.filter.valid_out.val();
        self.miss.next = self.filter.miss.val();
        self.forward.next = self.filter.forward.val();
    }
}

/// A [`PluckerFilter`] on a query's words (its t_min) and its operands' words.
#[derive(LogicBlock, Default)]
pub struct PluckerWords {
    pub clock: Signal<In, Clock>,
    pub valid: Signal<In, Bit>,
    pub query: Signal<In, Bits<QUERY_BITS>>,
    pub operands: Signal<In, Bits<OPERAND_BITS>>,
    pub valid_out: Signal<Out, Bit>,
    pub miss: Signal<Out, Bit>,
    pub forward: Signal<Out, Bit>,
    filter: PluckerFilter,
}

impl Logic for PluckerWords {
    #[hdl_gen]
    fn update(&mut self) {
        self.filter.clock.next = self.clock.val();
        self.filter.valid.next = self.valid.val();
        // Each block's three words and field (`plucker_operands`).
        self.filter.stored.next = self.operands.val().get_bit(1504);
        self.filter.dir[0].next = self.operands.val().get_bits::<W>(0);
        self.filter.dir[1].next = self.operands.val().get_bits::<W>(32);
        self.filter.dir[2].next = self.operands.val().get_bits::<W>(64);
        self.filter.moment[0].next = self.operands.val().get_bits::<W>(128);
        self.filter.moment[1].next = self.operands.val().get_bits::<W>(160);
        self.filter.moment[2].next = self.operands.val().get_bits::<W>(192);
        self.filter.orig[0].next = self.operands.val().get_bits::<WT>(256);
        self.filter.orig[1].next = self.operands.val().get_bits::<WT>(288);
        self.filter.orig[2].next = self.operands.val().get_bits::<WT>(320);
        self.filter.n[0].next = self.operands.val().get_bits::<WT>(384);
        self.filter.n[1].next = self.operands.val().get_bits::<WT>(416);
        self.filter.n[2].next = self.operands.val().get_bits::<WT>(448);
        self.filter.e1[0].next = self.operands.val().get_bits::<W>(512);
        self.filter.e1[1].next = self.operands.val().get_bits::<W>(544);
        self.filter.e1[2].next = self.operands.val().get_bits::<W>(576);
        self.filter.e2[0].next = self.operands.val().get_bits::<W>(640);
        self.filter.e2[1].next = self.operands.val().get_bits::<W>(672);
        self.filter.e2[2].next = self.operands.val().get_bits::<W>(704);
        self.filter.e3[0].next = self.operands.val().get_bits::<W>(768);
        self.filter.e3[1].next = self.operands.val().get_bits::<W>(800);
        self.filter.e3[2].next = self.operands.val().get_bits::<W>(832);
        self.filter.m1[0].next = self.operands.val().get_bits::<W>(896);
        self.filter.m1[1].next = self.operands.val().get_bits::<W>(928);
        self.filter.m1[2].next = self.operands.val().get_bits::<W>(960);
        self.filter.m2[0].next = self.operands.val().get_bits::<W>(1024);
        self.filter.m2[1].next = self.operands.val().get_bits::<W>(1056);
        self.filter.m2[2].next = self.operands.val().get_bits::<W>(1088);
        self.filter.m3[0].next = self.operands.val().get_bits::<W>(1152);
        self.filter.m3[1].next = self.operands.val().get_bits::<W>(1184);
        self.filter.m3[2].next = self.operands.val().get_bits::<W>(1216);
        self.filter.cut[0].next = self.operands.val().get_bits::<CUT_BITS>(1376);
        self.filter.cut[1].next = self.operands.val().get_bits::<CUT_BITS>(1408);
        self.filter.cut[2].next = self.operands.val().get_bits::<CUT_BITS>(1440);
        self.filter.dir_e.next = self.operands.val().get_bits::<EXP_BITS>(96);
        self.filter.moment_e.next = self.operands.val().get_bits::<EXP_BITS>(224);
        self.filter.orig_e.next = self.operands.val().get_bits::<EXP_BITS>(352);
        self.filter.n_e.next = self.operands.val().get_bits::<EXP_BITS>(480);
        self.filter.e1_e.next = self.operands.val().get_bits::<EXP_BITS>(608);
        self.filter.e2_e.next = self.operands.val().get_bits::<EXP_BITS>(736);
        self.filter.e3_e.next = self.operands.val().get_bits::<EXP_BITS>(864);
        self.filter.m1_e.next = self.operands.val().get_bits::<EXP_BITS>(992);
        self.filter.m2_e.next = self.operands.val().get_bits::<EXP_BITS>(1120);
        self.filter.m3_e.next = self.operands.val().get_bits::<EXP_BITS>(1248);
        self.filter.offset.next = self.operands.val().get_bits::<OFFSET_BITS>(1280);
        self.filter.offset_e.next = self.operands.val().get_bits::<EXP_BITS>(1344);
        self.filter.cut_e.next = self.operands.val().get_bits::<EXP_BITS>(1472);
        self.filter.t_min.next = self.query.val().get_bits::<32>(480);
        self.valid_out.next = self.filter.valid_out.val();
        self.miss.next = self.filter.miss.val();
        self.forward.next = self.filter.forward.val();
    }
}
