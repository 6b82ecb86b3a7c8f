//! The Möller-Trumbore test in any format, in exactly the hardware's operation order.

/// One ray-triangle test, IEEE fp32 at the ports as on the accelerator's bus.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MtQuery {
    pub orig: [f32; 3],
    pub dir: [f32; 3],
    pub v0: [f32; 3],
    pub v1: [f32; 3],
    pub v2: [f32; 3],
}

/// The result of one test. `t`, `u`, `v` are whatever the datapath computed, also on a miss
/// (the hardware always computes them); only `hit` says whether they mean anything.
#[derive(Clone, Copy, Debug, Default)]
pub struct MtResult {
    pub hit: bool,
    pub t: f32,
    pub u: f32,
    pub v: f32,
}

impl MtResult {
    /// Bit-for-bit equality (NaNs compare by their bits).
    pub fn same_bits(&self, other: &MtResult) -> bool {
        self.hit == other.hit
            && self.t.to_bits() == other.t.to_bits()
            && self.u.to_bits() == other.u.to_bits()
            && self.v.to_bits() == other.v.to_bits()
    }
}
