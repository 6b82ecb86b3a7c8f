//! When each value of the MT dataflow is ready, and the delay lines that line parallel
//! branches up, computed from the operators' latencies when a lane is built.
//!
//! The dataflow (the model's order, `hw_model::mt`), with the cycle each value is ready:
//! ```text
//! t_load  = from_f32                       orig, dir, v0, v1, v2
//! t_edge  = t_load + sub                   e1 = v1 − v0, e2 = v2 − v0, s = orig − v0
//! t_cross = t_edge + mul + sub             p = dir × e2, q = s × e1
//! t_dot   = t_cross + mul + add + add      det = e1·p, u' = s·p, v' = dir·q, t' = e2·q
//! t_recip = t_dot + recip                  inv = 1/det
//! t_scale = t_recip + mul                  u = u'·inv, v = v'·inv, t = t'·inv
//! t_sum   = t_scale + add                  u + v
//! ```
//! The tests follow with one comparison each (det against ±eps at t_dot, u, v and t against
//! 0, 1 and the loaded t_min at t_scale, u + v at t_sum) and t, u, v leave through to_f32; the lane's latency is the later of the
//! last comparison and the conversions. Every other path is padded to it.

use crate::operator::Op;

/// Latency (= pipeline stages) of each operator of one lane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OpLatencies {
    pub add: usize,
    pub sub: usize,
    pub mul: usize,
    pub recip: usize,
    pub lt: usize,
    pub from_f32: usize,
    pub to_f32: usize,
    /// The square root (float formats only; not in the MT lane).
    pub sqrt: usize,
}

impl OpLatencies {
    /// Every operator built with `min(depth, its max_stages)` registers.
    pub fn for_depth(depth: usize, max_stages: impl Fn(Op) -> usize) -> Self {
        let at = |op| depth.min(max_stages(op));
        OpLatencies {
            add: at(Op::Add),
            sub: at(Op::Sub),
            mul: at(Op::Mul),
            recip: at(Op::Recip),
            lt: at(Op::Lt),
            from_f32: at(Op::FromF32),
            to_f32: at(Op::ToF32),
            sqrt: at(Op::Sqrt),
        }
    }

    /// No from_f32 and to_f32 stages when the lane takes and gives the fp32 words
    /// unconverted (`raw`: fp32 itself, see `formats`).
    pub fn unconverted(self, raw: bool) -> Self {
        if raw {
            OpLatencies {
                from_f32: 0,
                to_f32: 0,
                ..self
            }
        } else {
            self
        }
    }
}

/// Ready times and padding delays of the dataflow, in clock cycles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Schedule {
    pub ops: OpLatencies,
    /// Inputs converted into the format.
    pub t_load: usize,
    /// e1, e2, s.
    pub t_edge: usize,
    /// p, q.
    pub t_cross: usize,
    /// det, u', v', t'.
    pub t_dot: usize,
    /// 1/det.
    pub t_recip: usize,
    /// u, v, t.
    pub t_scale: usize,
    /// u + v.
    pub t_sum: usize,
    /// valid_in to valid_out (and query to result).
    pub latency: usize,
}

impl Schedule {
    pub fn new(ops: OpLatencies) -> Self {
        let t_load = ops.from_f32;
        let t_edge = t_load + ops.sub;
        let t_cross = t_edge + ops.mul + ops.sub;
        let t_dot = t_cross + ops.mul + 2 * ops.add;
        let t_recip = t_dot + ops.recip;
        let t_scale = t_recip + ops.mul;
        let t_sum = t_scale + ops.add;
        let latency = (t_sum + ops.lt).max(t_scale + ops.to_f32);
        Schedule {
            ops,
            t_load,
            t_edge,
            t_cross,
            t_dot,
            t_recip,
            t_scale,
            t_sum,
            latency,
        }
    }

    /// dir (ready at t_load) to the cross product p = dir × e2 (at t_edge).
    pub fn dir_to_cross(&self) -> usize {
        self.t_edge - self.t_load
    }
    /// e1, e2, s and dir (from the cross-product delay) to the dot products (at t_cross).
    pub fn edge_to_dot(&self) -> usize {
        self.t_cross - self.t_edge
    }
    /// The third product of a dot product, to the second addition.
    pub fn third_product(&self) -> usize {
        self.ops.add
    }
    /// t_min (loaded with the query) to its comparison with t (at t_scale).
    pub fn t_min_to_test(&self) -> usize {
        self.t_scale - self.t_load
    }
    /// u', v', t' to the scaling by 1/det.
    pub fn numerator_to_scale(&self) -> usize {
        self.t_recip - self.t_dot
    }
    /// The det ≈ 0 flag to the output.
    pub fn parallel_to_out(&self) -> usize {
        self.latency - (self.t_dot + self.ops.lt)
    }
    /// The u, v, t range flags to the output.
    pub fn range_to_out(&self) -> usize {
        self.latency - (self.t_scale + self.ops.lt)
    }
    /// The u + v ≤ 1 flag to the output.
    pub fn sum_to_out(&self) -> usize {
        self.latency - (self.t_sum + self.ops.lt)
    }
    /// t, u, v in fp32 to the output.
    pub fn result_to_out(&self) -> usize {
        self.latency - (self.t_scale + self.ops.to_f32)
    }
}
