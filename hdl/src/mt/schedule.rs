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

#[cfg(test)]
mod tests {
    use super::*;

    fn uniform(n: usize) -> OpLatencies {
        OpLatencies {
            add: n,
            sub: n,
            mul: n,
            recip: n,
            lt: n,
            from_f32: n,
            to_f32: n,
        }
    }

    #[test]
    fn combinational_lane_has_no_latency_and_no_delays() {
        let s = Schedule::new(uniform(0));
        assert_eq!(s.latency, 0);
        assert_eq!(
            [
                s.dir_to_cross(),
                s.edge_to_dot(),
                s.third_product(),
                s.numerator_to_scale()
            ],
            [0; 4]
        );
        assert_eq!(
            [
                s.parallel_to_out(),
                s.range_to_out(),
                s.sum_to_out(),
                s.result_to_out()
            ],
            [0; 4]
        );
    }

    #[test]
    fn one_register_per_operator_counts_the_operators_on_the_critical_path() {
        // from, sub, mul, sub, mul, add, add, recip, mul, add, lt.
        let s = Schedule::new(uniform(1));
        assert_eq!(s.latency, 11);
        assert_eq!(s.parallel_to_out(), 3); // recip, mul, add after the comparison
        assert_eq!(s.range_to_out(), 1);
        assert_eq!(s.sum_to_out(), 0);
        assert_eq!(s.result_to_out(), 1);
    }

    #[test]
    fn every_path_reaches_the_output_at_the_latency() {
        let ops = OpLatencies {
            add: 4,
            sub: 3,
            mul: 2,
            recip: 27,
            lt: 1,
            from_f32: 1,
            to_f32: 5,
        };
        let s = Schedule::new(ops);
        // A slow conversion out makes t, u, v the critical path.
        assert_eq!(s.latency, s.t_scale + 5);
        assert_eq!(s.t_dot + ops.lt + s.parallel_to_out(), s.latency);
        assert_eq!(s.t_sum + ops.lt + s.sum_to_out(), s.latency);
        assert_eq!(s.t_load + s.dir_to_cross() + s.edge_to_dot(), s.t_cross);
        assert_eq!(s.t_dot + s.numerator_to_scale() + ops.mul, s.t_scale);
        assert_eq!(s.t_load + s.t_min_to_test(), s.t_scale);
    }

    #[test]
    fn depth_saturates_at_each_operators_maximum() {
        let max = |op| match op {
            Op::Recip => 27,
            Op::Add | Op::Sub => 4,
            Op::Mul => 3,
            _ => 1,
        };
        let ops = OpLatencies::for_depth(2, max);
        assert_eq!(
            ops,
            OpLatencies {
                add: 2,
                sub: 2,
                mul: 2,
                recip: 2,
                lt: 1,
                from_f32: 1,
                to_f32: 1
            }
        );
        assert_eq!(OpLatencies::for_depth(100, max).recip, 27);
    }

    #[test]
    fn a_raw_fp32_lane_drops_only_the_conversion_stages() {
        let ops = uniform(2);
        assert_eq!(ops.unconverted(false), ops);
        let raw = ops.unconverted(true);
        assert_eq!(
            raw,
            OpLatencies {
                from_f32: 0,
                to_f32: 0,
                ..ops
            }
        );
        // The load is on the critical path, the store is not (u + v and its test follow).
        assert_eq!(Schedule::new(raw).latency + 2, Schedule::new(ops).latency);
        assert_eq!(Schedule::new(raw).result_to_out(), 4);
    }

    #[test]
    fn fp32_lane_is_40_cycles_at_max_depth_and_other_floats_keep_their_conversions() {
        use hw_model::HwFormat;
        let (fp32, fp16) = (HwFormat::FP32, HwFormat::named("fp16"));
        assert!(crate::formats::raw_fp32(fp32));
        assert!(!crate::formats::raw_fp32(fp16));
        assert!(!crate::formats::raw_fp32(HwFormat::named("fx16_10")));
        assert_eq!(crate::mt::max_depth(fp32), 5);
        assert_eq!(crate::mt::latency(fp32, 5), 40);
        assert_eq!(crate::mt::latency(fp16, 5), 42);
    }
}
