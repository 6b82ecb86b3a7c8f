//! `hdl::traversal::far_end`.

use hdl::traversal::far_end::*;

#[test]
fn far_end_latency_counts_the_operators_on_the_path() {
    // mul, add, add.
    assert_eq!(max_depth(), 5);
    let l: Vec<usize> = (0..=max_depth() + 1).map(latency).collect();
    assert_eq!(l, [0, 3, 6, 9, 11, 13, 13]);
    let s = schedule(2);
    assert_eq!((s.bound_to_sum(), s.pad_slack()), (2, 4));
    assert_eq!((s.pad_to_sum(0), s.pad_to_sum(4)), (4, 0));
}

#[test]
#[should_panic(expected = "at most 4")]
fn a_pad_later_than_the_last_addition_is_refused() {
    schedule(2).pad_to_sum(5);
}
