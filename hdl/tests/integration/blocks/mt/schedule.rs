//! `hdl::mt::schedule`.

use hdl::mt::schedule::*;
use hdl::operator::Op;

fn uniform(n: usize) -> OpLatencies {
    OpLatencies {
        add: n,
        sub: n,
        mul: n,
        recip: n,
        lt: n,
        from_f32: n,
        to_f32: n,
        sqrt: n,
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
        sqrt: 0,
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
            to_f32: 1,
            sqrt: 1
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
    assert!(hdl::formats::raw_fp32(fp32));
    assert!(!hdl::formats::raw_fp32(fp16));
    assert!(!hdl::formats::raw_fp32(HwFormat::named("fx16_10")));
    assert_eq!(hdl::mt::max_depth(fp32), 5);
    assert_eq!(hdl::mt::latency(fp32, 5), 40);
    assert_eq!(hdl::mt::latency(fp16, 5), 42);
}
