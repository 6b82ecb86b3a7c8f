//! `hdl::traversal::box_test`.

use hdl::traversal::box_test::*;

#[test]
fn fp32_box_test_latency_counts_the_operators_on_the_path() {
    // sub, mul, lt (order), 3 × lt (folds), lt (enters).
    assert_eq!(max_depth(), 5);
    let l: Vec<usize> = (0..=max_depth() + 1).map(latency).collect();
    assert_eq!(l, [0, 7, 9, 11, 12, 13, 13]);
    let s = schedule(1);
    assert_eq!((s.inv_to_slab(), s.t_hi_to_fold()), (1, 3));
    assert_eq!(
        (0..3).map(|k| s.axis_to_step(k)).collect::<Vec<_>>(),
        [0, 1, 2]
    );
}
