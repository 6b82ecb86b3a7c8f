//! `hdl::traversal::ray_setup`.

use hdl::traversal::ray_setup::*;

#[test]
fn ray_setup_latency_counts_the_operators_on_the_path() {
    // The far end's path (3·lt + mul until pad, or the far end's own operators) is the
    // longest at every depth.
    assert_eq!(max_depth(), 5);
    let l: Vec<usize> = (0..=max_depth() + 1).map(latency).collect();
    assert_eq!(l, [0, 5, 7, 9, 11, 13, 13]);
    let s = schedule(1);
    assert_eq!(
        (s.t_pad, s.t_bound, s.pad_after_bound(), s.t_hi),
        (4, 2, 2, 5)
    );
    assert_eq!((s.t_orig_lo, s.t_inv, s.to_out(s.t_inv)), (5, 1, 4));
    let s = schedule(max_depth());
    assert_eq!((s.t_pad, s.t_bound, s.t_orig_lo, s.t_hi), (6, 0, 11, 13));
    for depth in 0..=max_depth() {
        let s = schedule(depth);
        assert_eq!(s.t_hi, s.latency, "depth {depth}");
        assert!(s.pad_after_bound() <= s.far.pad_slack(), "depth {depth}");
    }
}
