//! One Möller-Trumbore lane, written once and instantiated in every format module.
//!
//! rust-hdl needs concrete operator types, so the lane is a `macro_rules!` body that every
//! `formats::<name>` module expands (after defining `Add`, `Sub`, `Mul`, `Recip`, `Lt`,
//! `FromF32`, `ToF32`, `WIDTH`, `FORMAT`, `NAME`, `HW` and `RAW_FP32`). It defines
//! `formats::<name>::MtLane` and `formats::<name>::mt_lane_verilog`; the timing comes from
//! [`crate::mt::schedule::Schedule`].

/// Defines `MtLane` (with its `Cross` and `Dot` blocks) and `mt_lane_verilog` in the
/// invoking format module.
macro_rules! mt_lane {
    () => {
        pub use mt_lane_impl::{mt_lane_verilog, MtLane};

        mod mt_lane_impl {
            use $crate::macros::prelude::*;

            use super::{
                Add, FromF32, Lt, Mul, Recip, Sub, ToF32, FORMAT, HW, NAME, RAW_FP32, WIDTH,
            };
            use $crate::mt::delay::{Delay, Ring, RingPosition, WordDelay};
            use $crate::mt::schedule::{OpLatencies, Schedule};
            use $crate::regmap::OPERAND_COUNT;

            fn schedule(depth: usize) -> Schedule {
                $crate::mt::schedule(HW, depth)
            }

            /// a × b, each component as a.j·b.k − a.k·b.j (the model's `cross`).
            #[derive(LogicBlock)]
            pub struct Cross {
                pub clock: Signal<In, Clock>,
                pub a: [Signal<In, Bits<WIDTH>>; 3],
                pub b: [Signal<In, Bits<WIDTH>>; 3],
                pub y: [Signal<Out, Bits<WIDTH>>; 3],
                left: [Mul; 3],
                right: [Mul; 3],
                diff: [Sub; 3],
            }

            impl Cross {
                fn new(ops: &OpLatencies) -> Self {
                    Self {
                        clock: Default::default(),
                        a: Default::default(),
                        b: Default::default(),
                        y: Default::default(),
                        left: std::array::from_fn(|_| Mul::new(ops.mul)),
                        right: std::array::from_fn(|_| Mul::new(ops.mul)),
                        diff: std::array::from_fn(|_| Sub::new(ops.sub)),
                    }
                }
            }

            impl Logic for Cross {
                #[hdl_gen]
                fn update(&mut self) {
                    for i in 0..3 {
                        clock!(self, clock, left[i], right[i], diff[i]);
                        self.diff[i].a.next = self.left[i].y.val();
                        self.diff[i].b.next = self.right[i].y.val();
                        self.y[i].next = self.diff[i].y.val();
                    }
                    self.left[0].a.next = self.a[1].val();
                    self.left[0].b.next = self.b[2].val();
                    self.right[0].a.next = self.a[2].val();
                    self.right[0].b.next = self.b[1].val();
                    self.left[1].a.next = self.a[2].val();
                    self.left[1].b.next = self.b[0].val();
                    self.right[1].a.next = self.a[0].val();
                    self.right[1].b.next = self.b[2].val();
                    self.left[2].a.next = self.a[0].val();
                    self.left[2].b.next = self.b[1].val();
                    self.right[2].a.next = self.a[1].val();
                    self.right[2].b.next = self.b[0].val();
                }
            }

            /// (a.x·b.x + a.y·b.y) + a.z·b.z (the model's `dot`).
            #[derive(LogicBlock)]
            pub struct Dot {
                pub clock: Signal<In, Clock>,
                pub a: [Signal<In, Bits<WIDTH>>; 3],
                pub b: [Signal<In, Bits<WIDTH>>; 3],
                /// The position of the lane's ring for `third_at_sum`.
                pub third_at: Signal<In, RingPosition>,
                pub y: Signal<Out, Bits<WIDTH>>,
                products: [Mul; 3],
                first_sum: Add,
                third_at_sum: WordDelay<Bits<WIDTH>>,
                sum: Add,
            }

            impl Dot {
                fn new(schedule: &Schedule) -> Self {
                    let ops = &schedule.ops;
                    Self {
                        clock: Default::default(),
                        a: Default::default(),
                        b: Default::default(),
                        third_at: Default::default(),
                        y: Default::default(),
                        products: std::array::from_fn(|_| Mul::new(ops.mul)),
                        first_sum: Add::new(ops.add),
                        third_at_sum: WordDelay::new(schedule.third_product()),
                        sum: Add::new(ops.add),
                    }
                }
            }

            impl Logic for Dot {
                #[hdl_gen]
                fn update(&mut self) {
                    for i in 0..3 {
                        clock!(self, clock, products[i]);
                        self.products[i].a.next = self.a[i].val();
                        self.products[i].b.next = self.b[i].val();
                    }
                    clock!(self, clock, first_sum, third_at_sum);
                    self.third_at_sum.at.next = self.third_at.val();
                    clock!(self, clock, sum);
                    self.first_sum.a.next = self.products[0].y.val();
                    self.first_sum.b.next = self.products[1].y.val();
                    self.third_at_sum.d.next = self.products[2].y.val();
                    self.sum.a.next = self.first_sum.y.val();
                    self.sum.b.next = self.third_at_sum.q.val();
                    self.y.next = self.sum.y.val();
                }
            }

            /// One MT lane: a query (16 fp32 words: orig, dir, v0, v1, v2, t_min) every cycle in,
            /// `hit` and t, u, v (fp32) out `latency(depth)` cycles later, with `valid_in`
            /// delayed alongside. `depth` is the pipeline registers per operator, each
            /// operator saturating at its own `max_stages()`. No reset: the valid line holds
            /// the flip-flops' power-on zeros until the first query passes.
            #[derive(LogicBlock)]
            pub struct MtLane {
                pub clock: Signal<In, Clock>,
                pub valid_in: Signal<In, Bit>,
                pub query: [Signal<In, Bits<32>>; OPERAND_COUNT],
                pub valid_out: Signal<Out, Bit>,
                pub hit: Signal<Out, Bit>,
                pub t: Signal<Out, Bits<32>>,
                pub u: Signal<Out, Bits<32>>,
                pub v: Signal<Out, Bits<32>>,
                /// query[i] in the format: orig 0..3, dir 3..6, v0 6..9, v1 9..12, v2 12..15,
                /// t_min 15 (`loaded`; the words themselves when the format is `RAW_FP32`).
                load: [FromF32; OPERAND_COUNT],
                loaded: [Signal<Local, Bits<WIDTH>>; OPERAND_COUNT],
                raw_word: Signal<Local, Bits<32>>,
                raw_fp32: Constant<Bit>,
                /// e1 = v1 − v0, e2 = v2 − v0, s = orig − v0.
                edge1: [Sub; 3],
                edge2: [Sub; 3],
                to_origin: [Sub; 3],
                /// The ring positions of the block RAM delay lines, one counter per length.
                dir_ring: Ring,
                dot_ring: Ring,
                third_ring: Ring,
                numerator_ring: Ring,
                result_ring: Ring,
                t_min_ring: Ring,
                dir_at_cross: [WordDelay<Bits<WIDTH>>; 3],
                dir_at_dot: [WordDelay<Bits<WIDTH>>; 3],
                edge1_at_dot: [WordDelay<Bits<WIDTH>>; 3],
                edge2_at_dot: [WordDelay<Bits<WIDTH>>; 3],
                to_origin_at_dot: [WordDelay<Bits<WIDTH>>; 3],
                /// t_min (in the format) waits for t.
                t_min_at_test: WordDelay<Bits<WIDTH>>,
                /// p = dir × e2, q = s × e1.
                p: Cross,
                q: Cross,
                /// det = e1·p, u' = s·p, v' = dir·q, t' = e2·q.
                det: Dot,
                u_num: Dot,
                v_num: Dot,
                t_num: Dot,
                inv_det: Recip,
                u_num_at_scale: WordDelay<Bits<WIDTH>>,
                v_num_at_scale: WordDelay<Bits<WIDTH>>,
                t_num_at_scale: WordDelay<Bits<WIDTH>>,
                u_scale: Mul,
                v_scale: Mul,
                t_scale: Mul,
                u_plus_v: Add,
                det_below_eps: Lt,
                det_above_neg_eps: Lt,
                u_below_zero: Lt,
                u_above_one: Lt,
                v_below_zero: Lt,
                sum_above_one: Lt,
                t_above_min: Lt,
                parallel_at_out: Delay<Bit>,
                in_range_at_out: Delay<Bit>,
                sum_above_one_at_out: Delay<Bit>,
                /// t, u, v in fp32 (the words themselves when the format is `RAW_FP32`).
                t_out: ToF32,
                u_out: ToF32,
                v_out: ToF32,
                t_at_out: WordDelay<Bits<32>>,
                u_at_out: WordDelay<Bits<32>>,
                v_at_out: WordDelay<Bits<32>>,
                valid_at_out: Delay<Bit>,
                eps: Constant<Bits<WIDTH>>,
                neg_eps: Constant<Bits<WIDTH>>,
                zero: Constant<Bits<WIDTH>>,
                one: Constant<Bits<WIDTH>>,
            }

            impl MtLane {
                pub fn new(depth: usize) -> Self {
                    let s = schedule(depth);
                    let ops = &s.ops;
                    let delays = |cycles: usize| std::array::from_fn(|_| WordDelay::new(cycles));
                    let eps = FORMAT.from_f32(hw_model::mt::DET_EPSILON);
                    let constant = |bits: u64| Constant::new(bits.into());
                    Self {
                        clock: Default::default(),
                        valid_in: Default::default(),
                        query: Default::default(),
                        valid_out: Default::default(),
                        hit: Default::default(),
                        t: Default::default(),
                        u: Default::default(),
                        v: Default::default(),
                        load: std::array::from_fn(|_| FromF32::new(ops.from_f32)),
                        loaded: Default::default(),
                        raw_word: Default::default(),
                        raw_fp32: Constant::new(RAW_FP32),
                        edge1: std::array::from_fn(|_| Sub::new(ops.sub)),
                        edge2: std::array::from_fn(|_| Sub::new(ops.sub)),
                        to_origin: std::array::from_fn(|_| Sub::new(ops.sub)),
                        dir_ring: Ring::new(s.dir_to_cross()),
                        dot_ring: Ring::new(s.edge_to_dot()),
                        third_ring: Ring::new(s.third_product()),
                        numerator_ring: Ring::new(s.numerator_to_scale()),
                        result_ring: Ring::new(s.result_to_out()),
                        t_min_ring: Ring::new(s.t_min_to_test()),
                        dir_at_cross: delays(s.dir_to_cross()),
                        dir_at_dot: delays(s.edge_to_dot()),
                        edge1_at_dot: delays(s.edge_to_dot()),
                        edge2_at_dot: delays(s.edge_to_dot()),
                        to_origin_at_dot: delays(s.edge_to_dot()),
                        t_min_at_test: WordDelay::new(s.t_min_to_test()),
                        p: Cross::new(ops),
                        q: Cross::new(ops),
                        det: Dot::new(&s),
                        u_num: Dot::new(&s),
                        v_num: Dot::new(&s),
                        t_num: Dot::new(&s),
                        inv_det: Recip::new(ops.recip),
                        u_num_at_scale: WordDelay::new(s.numerator_to_scale()),
                        v_num_at_scale: WordDelay::new(s.numerator_to_scale()),
                        t_num_at_scale: WordDelay::new(s.numerator_to_scale()),
                        u_scale: Mul::new(ops.mul),
                        v_scale: Mul::new(ops.mul),
                        t_scale: Mul::new(ops.mul),
                        u_plus_v: Add::new(ops.add),
                        det_below_eps: Lt::new(ops.lt),
                        det_above_neg_eps: Lt::new(ops.lt),
                        u_below_zero: Lt::new(ops.lt),
                        u_above_one: Lt::new(ops.lt),
                        v_below_zero: Lt::new(ops.lt),
                        sum_above_one: Lt::new(ops.lt),
                        t_above_min: Lt::new(ops.lt),
                        parallel_at_out: Delay::new(s.parallel_to_out()),
                        in_range_at_out: Delay::new(s.range_to_out()),
                        sum_above_one_at_out: Delay::new(s.sum_to_out()),
                        t_out: ToF32::new(ops.to_f32),
                        u_out: ToF32::new(ops.to_f32),
                        v_out: ToF32::new(ops.to_f32),
                        t_at_out: WordDelay::new(s.result_to_out()),
                        u_at_out: WordDelay::new(s.result_to_out()),
                        v_at_out: WordDelay::new(s.result_to_out()),
                        valid_at_out: Delay::new(s.latency),
                        eps: constant(eps),
                        neg_eps: constant(FORMAT.neg(eps)),
                        zero: constant(FORMAT.from_f32(0.0)),
                        one: constant(FORMAT.from_f32(1.0)),
                    }
                }

                /// Cycles from a query at the inputs to its result at the outputs.
                pub fn latency(depth: usize) -> usize {
                    schedule(depth).latency
                }
            }

            impl Logic for MtLane {
                #[hdl_gen]
                fn update(&mut self) {
                    for i in 0..OPERAND_COUNT {
                        clock!(self, clock, load[i]);
                        self.load[i].a.next = self.query[i].val();
                        self.loaded[i].next = self.load[i].y.val();
                        // (Through a word signal: the index inside `bit_cast` would lose
                        // its macro hygiene in hdl_gen's expansion.)
                        self.raw_word.next = self.query[i].val();
                        if self.raw_fp32.val() {
                            self.loaded[i].next = bit_cast::<WIDTH, 32>(self.raw_word.val());
                        }
                    }
                    clock!(
                        self,
                        clock,
                        dir_ring,
                        dot_ring,
                        third_ring,
                        numerator_ring,
                        result_ring,
                        t_min_ring,
                        t_min_at_test
                    );
                    self.t_min_at_test.at.next = self.t_min_ring.at.val();
                    // Word 15 = T_MIN_WORD (a literal: hdl_gen would leak the name).
                    self.t_min_at_test.d.next = self.loaded[15].val();
                    for i in 0..3 {
                        clock!(
                            self,
                            clock,
                            edge1[i],
                            edge2[i],
                            to_origin[i],
                            dir_at_cross[i],
                            dir_at_dot[i],
                            edge1_at_dot[i],
                            edge2_at_dot[i],
                            to_origin_at_dot[i]
                        );
                        self.dir_at_cross[i].at.next = self.dir_ring.at.val();
                        self.dir_at_dot[i].at.next = self.dot_ring.at.val();
                        self.edge1_at_dot[i].at.next = self.dot_ring.at.val();
                        self.edge2_at_dot[i].at.next = self.dot_ring.at.val();
                        self.to_origin_at_dot[i].at.next = self.dot_ring.at.val();
                        // The loads of orig, dir, v0, v1, v2 component i.
                        self.to_origin[i].a.next = self.loaded[i].val();
                        self.dir_at_cross[i].d.next = self.loaded[3 + i].val();
                        self.to_origin[i].b.next = self.loaded[6 + i].val();
                        self.edge1[i].b.next = self.loaded[6 + i].val();
                        self.edge2[i].b.next = self.loaded[6 + i].val();
                        self.edge1[i].a.next = self.loaded[9 + i].val();
                        self.edge2[i].a.next = self.loaded[12 + i].val();
                        // p = dir × e2, q = s × e1.
                        self.p.a[i].next = self.dir_at_cross[i].q.val();
                        self.p.b[i].next = self.edge2[i].y.val();
                        self.q.a[i].next = self.to_origin[i].y.val();
                        self.q.b[i].next = self.edge1[i].y.val();
                        // The dot products' other operands, delayed past the cross products.
                        self.dir_at_dot[i].d.next = self.dir_at_cross[i].q.val();
                        self.edge1_at_dot[i].d.next = self.edge1[i].y.val();
                        self.edge2_at_dot[i].d.next = self.edge2[i].y.val();
                        self.to_origin_at_dot[i].d.next = self.to_origin[i].y.val();
                        self.det.a[i].next = self.edge1_at_dot[i].q.val();
                        self.det.b[i].next = self.p.y[i].val();
                        self.u_num.a[i].next = self.to_origin_at_dot[i].q.val();
                        self.u_num.b[i].next = self.p.y[i].val();
                        self.v_num.a[i].next = self.dir_at_dot[i].q.val();
                        self.v_num.b[i].next = self.q.y[i].val();
                        self.t_num.a[i].next = self.edge2_at_dot[i].q.val();
                        self.t_num.b[i].next = self.q.y[i].val();
                    }
                    clock!(self, clock, p, q, det, u_num, v_num, t_num);
                    self.det.third_at.next = self.third_ring.at.val();
                    self.u_num.third_at.next = self.third_ring.at.val();
                    self.v_num.third_at.next = self.third_ring.at.val();
                    self.t_num.third_at.next = self.third_ring.at.val();
                    // u, v, t = numerator · (1/det).
                    clock!(self, clock, inv_det);
                    self.inv_det.a.next = self.det.y.val();
                    clock!(self, clock, u_num_at_scale, v_num_at_scale, t_num_at_scale);
                    self.u_num_at_scale.at.next = self.numerator_ring.at.val();
                    self.v_num_at_scale.at.next = self.numerator_ring.at.val();
                    self.t_num_at_scale.at.next = self.numerator_ring.at.val();
                    self.u_num_at_scale.d.next = self.u_num.y.val();
                    self.v_num_at_scale.d.next = self.v_num.y.val();
                    self.t_num_at_scale.d.next = self.t_num.y.val();
                    clock!(self, clock, u_scale, v_scale, t_scale);
                    self.u_scale.a.next = self.u_num_at_scale.q.val();
                    self.v_scale.a.next = self.v_num_at_scale.q.val();
                    self.t_scale.a.next = self.t_num_at_scale.q.val();
                    self.u_scale.b.next = self.inv_det.y.val();
                    self.v_scale.b.next = self.inv_det.y.val();
                    self.t_scale.b.next = self.inv_det.y.val();
                    clock!(self, clock, u_plus_v);
                    self.u_plus_v.a.next = self.u_scale.y.val();
                    self.u_plus_v.b.next = self.v_scale.y.val();
                    // The tests: parallel = det < eps && −eps < det, then the ranges.
                    clock!(
                        self,
                        clock,
                        det_below_eps,
                        det_above_neg_eps,
                        u_below_zero,
                        u_above_one,
                        v_below_zero,
                        sum_above_one,
                        t_above_min
                    );
                    self.det_below_eps.a.next = self.det.y.val();
                    self.det_below_eps.b.next = self.eps.val();
                    self.det_above_neg_eps.a.next = self.neg_eps.val();
                    self.det_above_neg_eps.b.next = self.det.y.val();
                    self.u_below_zero.a.next = self.u_scale.y.val();
                    self.u_below_zero.b.next = self.zero.val();
                    self.u_above_one.a.next = self.one.val();
                    self.u_above_one.b.next = self.u_scale.y.val();
                    self.v_below_zero.a.next = self.v_scale.y.val();
                    self.v_below_zero.b.next = self.zero.val();
                    self.sum_above_one.a.next = self.one.val();
                    self.sum_above_one.b.next = self.u_plus_v.y.val();
                    // The lower bound in the format (hw_model::mt::mt_model; t_min = 0: t > 0).
                    self.t_above_min.a.next = self.t_min_at_test.q.val();
                    self.t_above_min.b.next = self.t_scale.y.val();
                    clock!(
                        self,
                        clock,
                        parallel_at_out,
                        in_range_at_out,
                        sum_above_one_at_out
                    );
                    self.parallel_at_out.d.next =
                        self.det_below_eps.y.val() & self.det_above_neg_eps.y.val();
                    self.in_range_at_out.d.next = !self.u_below_zero.y.val()
                        & !self.u_above_one.y.val()
                        & !self.v_below_zero.y.val()
                        & self.t_above_min.y.val();
                    self.sum_above_one_at_out.d.next = self.sum_above_one.y.val();
                    self.hit.next = !self.parallel_at_out.q.val()
                        & self.in_range_at_out.q.val()
                        & !self.sum_above_one_at_out.q.val();
                    // t, u, v back to fp32.
                    clock!(self, clock, t_out, u_out, v_out);
                    self.t_out.a.next = self.t_scale.y.val();
                    self.u_out.a.next = self.u_scale.y.val();
                    self.v_out.a.next = self.v_scale.y.val();
                    clock!(self, clock, t_at_out, u_at_out, v_at_out);
                    self.t_at_out.at.next = self.result_ring.at.val();
                    self.u_at_out.at.next = self.result_ring.at.val();
                    self.v_at_out.at.next = self.result_ring.at.val();
                    self.t_at_out.d.next = self.t_out.y.val();
                    self.u_at_out.d.next = self.u_out.y.val();
                    self.v_at_out.d.next = self.v_out.y.val();
                    if self.raw_fp32.val() {
                        self.t_at_out.d.next = bit_cast::<32, WIDTH>(self.t_scale.y.val());
                        self.u_at_out.d.next = bit_cast::<32, WIDTH>(self.u_scale.y.val());
                        self.v_at_out.d.next = bit_cast::<32, WIDTH>(self.v_scale.y.val());
                    }
                    self.t.next = self.t_at_out.q.val();
                    self.u.next = self.u_at_out.q.val();
                    self.v.next = self.v_at_out.q.val();
                    clock!(self, clock, valid_at_out);
                    self.valid_at_out.d.next = self.valid_in.val();
                    self.valid_out.next = self.valid_at_out.q.val();
                }
            }

            impl $crate::mt::Lane for MtLane {
                const NAME: &'static str = NAME;
                const HW: hw_model::HwFormat = HW;
                const FORMAT: hw_model::Format = FORMAT;
                fn new(depth: usize) -> Self {
                    MtLane::new(depth)
                }
                fn latency(depth: usize) -> usize {
                    MtLane::latency(depth)
                }
                fn clock(&mut self) -> &mut Signal<In, Clock> {
                    &mut self.clock
                }
                fn set_inputs(&mut self, valid: bool, query: &[u32; OPERAND_COUNT]) {
                    self.valid_in.next = valid;
                    for (port, &word) in self.query.iter_mut().zip(query) {
                        port.next = u64::from(word).into();
                    }
                }
                fn outputs(&self) -> $crate::mt::LaneOutput {
                    $crate::mt::LaneOutput {
                        valid: self.valid_out.val(),
                        hit: self.hit.val(),
                        t: self.t.val().to_u64() as u32,
                        u: self.u.val().to_u64() as u32,
                        v: self.v.val().to_u64() as u32,
                    }
                }
            }

            /// Verilog of a lane with `depth` registers per operator, top module `top`
            /// (built on a thread with room for the lane on its stack).
            pub fn mt_lane_verilog(depth: usize) -> String {
                $crate::harness::built_verilog(move || MtLane::new(depth))
            }
        }
    };
}
pub(crate) use mt_lane;
