//! `hdl::pipe`.

use hdl::pipe::placement;

#[test]
fn placement_spreads_registers_and_counts_them() {
    assert_eq!(placement(0, 3), vec![false, false, false]);
    assert_eq!(placement(1, 3), vec![false, true, false]);
    assert_eq!(placement(2, 3), vec![true, false, true]);
    assert_eq!(placement(3, 3), vec![true, true, true]);
    for cuts in 1..40 {
        for stages in 0..=cuts {
            let n = placement(stages, cuts).iter().filter(|&&e| e).count();
            assert_eq!(n, stages, "{stages} of {cuts}");
        }
    }
}

#[test]
#[should_panic(expected = "only 2 cut points")]
fn placement_rejects_too_many_stages() {
    placement(3, 2);
}
