//! Normalisation in fp32, one vector a cycle: `hw_model::fp32::Vec3::normalized` in its
//! operation order,
//!
//! ```text
//! t_square = mul                      x·x, y·y, z·z
//! t_partial = t_square + add          x·x + y·y
//! t_norm  = t_partial + add           n = (x·x + y·y) + z·z
//! t_root  = t_norm + sqrt             sqrt(n)             (and lt(0, n) at t_norm + lt)
//! t_inv   = t_root + recip            recip(sqrt(n))
//! t_out   = t_inv + mul               each component × it, or v unchanged unless 0 < n
//! ```
//!
//! with every other path padded by a delay line to the cycle its value is used, so the block
//! takes a vector every cycle (II = 1) and gives its normalisation exactly
//! [`latency`]`(depth)` cycles later. `depth` is the pipeline registers per operator, each
//! saturating at its own `max_stages()` (as in the MT lane and the traversal unit).

use rust_hdl::prelude::*;

use crate::formats::fp32::{self, Add, Lt, Mul, Recip, Sqrt};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;

type Word = Bits<32>;

/// When each value of the normalisation is ready, from the operators' latencies at a depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NormaliseSchedule {
    pub ops: OpLatencies,
    /// x·x, y·y, z·z.
    pub t_square: usize,
    /// x·x + y·y.
    pub t_partial: usize,
    /// n.
    pub t_norm: usize,
    /// lt(0, n).
    pub t_positive: usize,
    /// recip(sqrt(n)).
    pub t_inv: usize,
    /// The result (input to output).
    pub latency: usize,
}

impl NormaliseSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        let t_square = ops.mul;
        let t_partial = t_square + ops.add;
        let t_norm = t_partial + ops.add;
        let t_positive = t_norm + ops.lt;
        let t_inv = t_norm + ops.sqrt + ops.recip;
        let latency = t_inv + ops.mul;
        assert!(
            t_positive <= latency,
            "lt is never slower than sqrt, recip and mul"
        );
        NormaliseSchedule {
            ops,
            t_square,
            t_partial,
            t_norm,
            t_positive,
            t_inv,
            latency,
        }
    }
}

/// Cycles from a vector at the inputs to its normalisation at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    NormaliseSchedule::new(depth).latency
}

/// `v` (fp32 words) in, its normalisation out [`latency`]`(depth)` cycles later. The caller
/// carries its own valid and side data beside it, delayed by the same latency.
#[derive(LogicBlock)]
pub struct Normalise {
    pub clock: Signal<In, Clock>,
    pub v: [Signal<In, Word>; 3],
    pub y: [Signal<Out, Word>; 3],
    square: [Mul; 3],
    partial: Add,
    z_square_at_norm: Delay<Word>,
    norm: Add,
    positive: Lt,
    norm_root: Sqrt,
    inv: Recip,
    positive_at_out: Delay<Bit>,
    v_at_scale: [Delay<Word>; 3],
    scaled: [Mul; 3],
    v_at_out: [Delay<Word>; 3],
    zero: Constant<Word>,
}

impl Normalise {
    pub fn new(depth: usize) -> Self {
        let s = NormaliseSchedule::new(depth);
        Self {
            clock: Default::default(),
            v: Default::default(),
            y: Default::default(),
            square: std::array::from_fn(|_| Mul::new(s.ops.mul)),
            partial: Add::new(s.ops.add),
            z_square_at_norm: Delay::new(s.t_partial - s.t_square),
            norm: Add::new(s.ops.add),
            positive: Lt::new(s.ops.lt),
            norm_root: Sqrt::new(s.ops.sqrt),
            inv: Recip::new(s.ops.recip),
            positive_at_out: Delay::new(s.latency - s.t_positive),
            v_at_scale: Delay::lines(s.t_inv),
            scaled: std::array::from_fn(|_| Mul::new(s.ops.mul)),
            v_at_out: Delay::lines(s.latency - s.t_inv),
            zero: Constant::new(Word::default()),
        }
    }
}

impl Logic for Normalise {
    #[hdl_gen]
    fn update(&mut self) {
        for a in 0..3 {
            clock!(self, clock, square[a]);
            self.square[a].a.next = self.v[a].val();
            self.square[a].b.next = self.v[a].val();
        }
        clock!(
            self,
            clock,
            partial,
            z_square_at_norm,
            norm,
            positive,
            norm_root,
            inv
        );
        self.partial.a.next = self.square[0].y.val();
        self.partial.b.next = self.square[1].y.val();
        self.z_square_at_norm.d.next = self.square[2].y.val();
        self.norm.a.next = self.partial.y.val();
        self.norm.b.next = self.z_square_at_norm.q.val();
        self.positive.a.next = self.zero.val();
        self.positive.b.next = self.norm.y.val();
        self.norm_root.a.next = self.norm.y.val();
        self.inv.a.next = self.norm_root.y.val();
        clock!(self, clock, positive_at_out);
        self.positive_at_out.d.next = self.positive.y.val();
        for a in 0..3 {
            clock!(self, clock, v_at_scale[a], scaled[a], v_at_out[a]);
            self.v_at_scale[a].d.next = self.v[a].val();
            self.scaled[a].a.next = self.v_at_scale[a].q.val();
            self.scaled[a].b.next = self.inv.y.val();
            self.v_at_out[a].d.next = self.v_at_scale[a].q.val();
            if self.positive_at_out.q.val() {
                self.y[a].next = self.scaled[a].y.val();
            } else {
                self.y[a].next = self.v_at_out[a].q.val();
            }
        }
    }
}

impl Stepped for Normalise {
    /// A vector's fp32 words.
    type Input = [u32; 3];
    type Output = [u32; 3];

    fn idle() -> [u32; 3] {
        [0; 3]
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, v: &[u32; 3]) {
        for (port, &word) in self.v.iter_mut().zip(v) {
            port.next = Word::from(u64::from(word));
        }
    }

    fn observe(&self) -> [u32; 3] {
        std::array::from_fn(|a| self.y[a].val().to_u64() as u32)
    }
}

/// Runs a freshly built block at `depth` in rust-hdl's simulator, one vector a cycle, and
/// returns the outputs of every cycle (`inputs.len() + flush` of them).
pub fn simulate_normalise(depth: usize, inputs: &[[u32; 3]], flush: usize) -> Vec<[u32; 3]> {
    simulate_cycles(move || Normalise::new(depth), inputs, flush)
}

/// Verilog of the block at `depth`, top module `top`.
pub fn normalise_verilog(depth: usize) -> String {
    built_verilog(move || Normalise::new(depth))
}
