//! Normalisation in fp32, one vector every two cycles: `hw_model::fp32::Vec3::normalized` in
//! its operation order, on three multipliers and one adder, each used twice a vector,
//!
//! ```text
//! t_square     = mul                       x·x, y·y, z·z          (multiplier a, a vector's
//!                                                                   cycle)
//! t_partial    = t_square + add            x·x + y·y              (the adder)
//! t_norm       = t_norm_issue + add        n = (x·x + y·y) + z·z  (the adder, the other
//!                                                                   parity)
//! t_inv        = t_norm + sqrt + recip     recip(sqrt(n))         (and lt(0, n) at t_norm + lt)
//! latency      = t_scale + mul             each component × it    (multiplier a, the other
//!                                                                   parity), or v unchanged
//!                                                                   unless 0 < n
//! ```
//!
//! A vector comes in a cycle whose `phase` input is low, and `phase` alternates every
//! cycle, so the first use of a shared operator always falls on one parity of the cycle
//! count and its second use on the other: the second use is issued one register later
//! where the operator's latency is even (`t_norm_issue` = t_square + add rounded up to odd,
//! `t_scale` = t_inv rounded up to odd). Every other path is padded by a delay line to the
//! cycle its value is used; the vector is answered exactly [`latency`]`(depth)` cycles
//! later. `depth` is the pipeline registers per operator, each saturating at its own
//! `max_stages()` (as in the MT lane and the traversal unit).

use rust_hdl::prelude::*;

use crate::formats::fp32::{self, Add, Lt, Mul, Recip, Sqrt};
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;

type Word = Bits<32>;

/// Cycles between two uses of a shared operator's parities: `t` rounded up to odd.
pub(crate) const fn odd(t: usize) -> usize {
    t | 1
}

/// When each value of the normalisation is ready, from the operators' latencies at a depth,
/// counted from the vector's cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NormaliseSchedule {
    pub ops: OpLatencies,
    /// x·x, y·y, z·z; x·x + y·y issued.
    pub t_square: usize,
    /// x·x + y·y.
    pub t_partial: usize,
    /// n issued on the adder (the other parity than x·x + y·y).
    pub t_norm_issue: usize,
    /// n.
    pub t_norm: usize,
    /// lt(0, n).
    pub t_positive: usize,
    /// recip(sqrt(n)).
    pub t_inv: usize,
    /// The components × recip(sqrt(n)) issued on the multipliers (the other parity than the
    /// squares).
    pub t_scale: usize,
    /// The result (input to output).
    pub latency: usize,
}

impl NormaliseSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        let t_square = ops.mul;
        let t_partial = t_square + ops.add;
        let t_norm_issue = t_square + odd(ops.add);
        let t_norm = t_norm_issue + ops.add;
        let t_positive = t_norm + ops.lt;
        let t_inv = t_norm + ops.sqrt + ops.recip;
        let t_scale = odd(t_inv);
        let latency = t_scale + ops.mul;
        assert!(
            t_positive <= latency,
            "lt is never slower than sqrt, recip and mul"
        );
        NormaliseSchedule {
            ops,
            t_square,
            t_partial,
            t_norm_issue,
            t_norm,
            t_positive,
            t_inv,
            t_scale,
            latency,
        }
    }
}

/// Cycles from a vector at the inputs to its normalisation at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    NormaliseSchedule::new(depth).latency
}

/// `v` (fp32 words) in when `phase` is low, its normalisation out [`latency`]`(depth)` cycles
/// later; `phase` must alternate every cycle (so a vector at most every two cycles). The
/// caller carries its own valid and side data beside it, delayed by the same latency.
#[derive(LogicBlock)]
pub struct Normalise {
    pub clock: Signal<In, Clock>,
    pub phase: Signal<In, Bit>,
    pub v: [Signal<In, Word>; 3],
    pub y: [Signal<Out, Word>; 3],
    /// The squares, then the components × recip(sqrt(n)).
    mul: [Mul; 3],
    /// x·x + y·y, then n.
    add: Add,
    partial_at_norm: Delay<Word>,
    z_square_at_norm: Delay<Word>,
    positive: Lt,
    norm_root: Sqrt,
    inv: Recip,
    inv_at_scale: Delay<Word>,
    positive_at_out: Delay<Bit>,
    v_at_scale: [Delay<Word>; 3],
    v_at_out: [Delay<Word>; 3],
    /// The parity of `t_square` (the adder's first use).
    square_odd: Constant<Bit>,
    zero: Constant<Word>,
}

impl Normalise {
    pub fn new(depth: usize) -> Self {
        let s = NormaliseSchedule::new(depth);
        Self {
            clock: Default::default(),
            phase: Default::default(),
            v: Default::default(),
            y: Default::default(),
            mul: std::array::from_fn(|_| Mul::new(s.ops.mul)),
            add: Add::new(s.ops.add),
            partial_at_norm: Delay::new(s.t_norm_issue - s.t_partial),
            z_square_at_norm: Delay::new(s.t_norm_issue - s.t_square),
            positive: Lt::new(s.ops.lt),
            norm_root: Sqrt::new(s.ops.sqrt),
            inv: Recip::new(s.ops.recip),
            inv_at_scale: Delay::new(s.t_scale - s.t_inv),
            positive_at_out: Delay::new(s.latency - s.t_positive),
            v_at_scale: Delay::lines(s.t_scale),
            v_at_out: Delay::lines(s.latency - s.t_scale),
            square_odd: Constant::new(s.t_square % 2 == 1),
            zero: Constant::new(Word::default()),
        }
    }
}

impl Logic for Normalise {
    #[hdl_gen]
    fn update(&mut self) {
        // The adder: x·x + y·y in the squares' cycle, n in the other.
        clock!(
            self,
            clock,
            add,
            partial_at_norm,
            z_square_at_norm,
            positive,
            norm_root,
            inv,
            inv_at_scale
        );
        self.partial_at_norm.d.next = self.add.y.val();
        self.z_square_at_norm.d.next = self.mul[2].y.val();
        if self.phase.val() ^ self.square_odd.val() {
            self.add.a.next = self.partial_at_norm.q.val();
            self.add.b.next = self.z_square_at_norm.q.val();
        } else {
            self.add.a.next = self.mul[0].y.val();
            self.add.b.next = self.mul[1].y.val();
        }
        self.positive.a.next = self.zero.val();
        self.positive.b.next = self.add.y.val();
        self.norm_root.a.next = self.add.y.val();
        self.inv.a.next = self.norm_root.y.val();
        self.inv_at_scale.d.next = self.inv.y.val();
        clock!(self, clock, positive_at_out);
        self.positive_at_out.d.next = self.positive.y.val();
        // The multipliers: a vector's squares in its cycle, the scaling in the other.
        for a in 0..3 {
            clock!(self, clock, mul[a], v_at_scale[a], v_at_out[a]);
            self.v_at_scale[a].d.next = self.v[a].val();
            self.v_at_out[a].d.next = self.v_at_scale[a].q.val();
            if self.phase.val() {
                self.mul[a].a.next = self.v_at_scale[a].q.val();
                self.mul[a].b.next = self.inv_at_scale.q.val();
            } else {
                self.mul[a].a.next = self.v[a].val();
                self.mul[a].b.next = self.v[a].val();
            }
            if self.positive_at_out.q.val() {
                self.y[a].next = self.mul[a].y.val();
            } else {
                self.y[a].next = self.v_at_out[a].q.val();
            }
        }
    }
}

impl Stepped for Normalise {
    /// `phase` and a vector's fp32 words.
    type Input = (bool, [u32; 3]);
    type Output = [u32; 3];

    fn idle() -> (bool, [u32; 3]) {
        (false, [0; 3])
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, &(phase, v): &(bool, [u32; 3])) {
        self.phase.next = phase;
        for (port, &word) in self.v.iter_mut().zip(&v) {
            port.next = Word::from(u64::from(word));
        }
    }

    fn observe(&self) -> [u32; 3] {
        std::array::from_fn(|a| self.y[a].val().to_u64() as u32)
    }
}

/// Runs a freshly built block at `depth` in rust-hdl's simulator for `inputs.len() + flush`
/// cycles, `phase` low in the even ones (a vector taken: `inputs`' even entries) and high in
/// the odd ones (the block must ignore those entries), and returns every cycle's outputs.
pub fn simulate_normalise(depth: usize, inputs: &[[u32; 3]], flush: usize) -> Vec<[u32; 3]> {
    let inputs = inputs.to_vec();
    let cycles = inputs.len() + flush;
    let mut cycle = 0;
    simulate_driven(
        move || Normalise::new(depth),
        move |_| {
            let c = cycle;
            cycle += 1;
            (c < cycles).then(|| (c % 2 == 1, inputs.get(c).copied().unwrap_or_default()))
        },
    )
    .into_iter()
    .map(|(_, out)| out)
    .collect()
}

/// Verilog of the block at `depth`, top module `top`.
pub fn normalise_verilog(depth: usize) -> String {
    built_verilog(move || Normalise::new(depth))
}
