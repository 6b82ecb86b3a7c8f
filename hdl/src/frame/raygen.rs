//! Ray generation, a ray every two cycles (`hw_model::frame::raygen::INTERVAL`): pixel
//! (i, j) → the primary ray through its centre, `hw_model::frame::raygen::primary` in its
//! operation order, each operator used twice a ray (times from the cycle the pixel is taken):
//!
//! ```text
//! t_coord      = coord                 i, then j, in fp32 (exact)       (the converter)
//! t_scaled     = t_coord + mul         i·dx, then j·dy                  (a multiplier)
//! t_xy         = t_scaled + add        x = i·dx + x0, then y = j·dy + y0 (an adder)
//! t_terms      = t_xy + mul            r0k·x, then r1k·y                (multiplier k = 0..2)
//! t_sum_issue  = t_terms + 1           r0k·x + r1k·y                    (adder k)
//! t_d          = t_sub_issue + add     d_k = (r0k·x + r1k·y) + (−r2k)   (adder k again)
//! t_dir        = t_d + normalise       direction = normalise(d)         (3 mul, 1 add, ...)
//! ```
//!
//! A pixel is taken only in a cycle whose phase (a flip-flop toggled every cycle) is low, so
//! each shared operator's first use falls on one parity of the cycle count and its second
//! on the other: j is held a cycle after i, y follows x a cycle later and meets r1k in the
//! cycle after x met r0k, r0k·x is held a cycle to meet r1k·y, and the subtraction is issued
//! on the adder that made the sum, `t_sub_issue` = t_sum_issue + add rounded up to odd (one
//! register later where the adder's latency is even). The subtraction is the adder with
//! r2k's sign flipped, as fp32's `Sub` is. [`super::normalise`] shares its operators the
//! same way. The pixel index and a valid bit ride beside the arithmetic by delay lines. 7
//! multipliers and 5 adders where a ray a cycle took 14 and 10. `depth` is the pipeline
//! registers per operator, each saturating at its own `max_stages()` (as in
//! [`super::normalise`]). The ray's origin is the camera's: a wire from the constant
//! inputs, not carried.
//!
//! The camera constants (`hw_model::frame::constants::CameraConstants`: dx, x0, dy, y0, the
//! camera-to-world rows, the origin) are inputs, the registers the frame unit loads with the
//! scene; they must hold still while the block holds rays (between frames).
//!
//! **Back-pressure.** The arithmetic cannot stall: every accepted pixel reserves a slot of the
//! ray queue at the end of the pipeline (a credit count of rays accepted and not yet taken),
//! and `pixel_ready` falls only when [`QUEUE_DEPTH`] rays are in flight or queued: the
//! scheme of the stream front end (`top::stream`) and the filter slots (`dual::slot`). The
//! other scheme, a pipeline-wide enable, would need an enable port on every register of every
//! operator and either `ray_ready` on the clock enable of the whole pipeline (3,547
//! flip-flops and 449 SRLs at full depth: a high-fanout path from the consumer) or a skid
//! buffer of a whole ray (117 flip-flops) to register it. The queue keeps its rays in block
//! RAM (yosys maps it to 2) and adds only its pointers and the count to the flip-flops (about
//! 35), so it is the cheaper in registers; and `pixel_ready` and `ray_valid` come from
//! registers, never combinationally from the other side.
//!
//! No reset: the count, the queue and the valid line start from the flip-flops' power-on
//! zeros, and a frame ends with every ray taken.

use hw_model::frame::constants::CameraConstants;
pub use hw_model::frame::raygen::INTERVAL;
use hw_model::frame::FrameLimits;
use rust_hdl::prelude::*;

use super::coord::{CoordToFp32, COORD_BITS};
use super::normalise::{self, odd, Normalise};
use crate::formats::fp32::{self, Add, Mul};
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;
use crate::operator::Op;

type Word = Bits<32>;

/// Bits of a pixel index (j·width + i) carried beside its ray.
pub const PIXEL_BITS: usize = 21;
const _: () =
    assert!(FrameLimits::HW.width as u64 * FrameLimits::HW.height as u64 <= 1 << PIXEL_BITS);
/// Address bits of the ray queue.
pub const QUEUE_ADDR_BITS: usize = 7;
/// Rays the block holds in its pipeline and its queue together: more than the pipeline's
/// latency at full depth, so a consumer that is always ready sees every ray the pipeline
/// makes.
pub const QUEUE_DEPTH: usize = 1 << QUEUE_ADDR_BITS;
/// Width of the credit count (0 to `QUEUE_DEPTH`).
const PENDING_BITS: usize = QUEUE_ADDR_BITS + 1;
/// Bits of a queued ray: the direction's three words, the pixel index above them.
const QUEUED_BITS: usize = 96 + PIXEL_BITS;
// The kernel spells the queued ray's width and the count's top bit as literals.
const _: () = assert!(QUEUED_BITS == 117 && PENDING_BITS == 8);
/// Cycles from a ray written into the queue to the queue showing it when it was empty
/// (rust-hdl's `SynchronousFIFO`: the write, then its delayed write pointer; the RAM is read
/// in the same cycle).
pub const QUEUE_LATENCY: usize = 2;

/// The phase flip-flop alternates: a pixel every two cycles.
const _: () = assert!(INTERVAL == 2);

/// The ray queue (rust-hdl's FIFO: `data_out` shows the head while not `empty`).
type RayQueue = SynchronousFIFO<Bits<QUEUED_BITS>, QUEUE_ADDR_BITS, PENDING_BITS, 1>;

/// When each value of ray generation is ready, from the operators' latencies at a depth,
/// counted from the cycle its pixel is taken (j's, y's and r1k·y's a cycle after i's, x's
/// and r0k·x's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayGenSchedule {
    pub ops: OpLatencies,
    /// i in fp32.
    pub t_coord: usize,
    /// i·dx.
    pub t_scaled: usize,
    /// x.
    pub t_xy: usize,
    /// r0k·x.
    pub t_terms: usize,
    /// r0k·x + r1k·y issued (r1k·y ready).
    pub t_sum_issue: usize,
    /// d issued on the same adder (the other parity).
    pub t_sub_issue: usize,
    /// d (the unnormalised direction).
    pub t_d: usize,
    /// The direction, written into the queue.
    pub t_dir: usize,
    /// An accepted pixel to its ray at the outputs when the queue is empty.
    pub latency: usize,
}

impl RayGenSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        let t_coord = depth.min(CoordToFp32::max_stages());
        let t_scaled = t_coord + ops.mul;
        let t_xy = t_scaled + ops.add;
        let t_terms = t_xy + ops.mul;
        let t_sum_issue = t_terms + 1;
        let t_sub_issue = t_sum_issue + odd(ops.add);
        let t_d = t_sub_issue + ops.add;
        let t_dir = t_d + normalise::latency(depth);
        RayGenSchedule {
            ops,
            t_coord,
            t_scaled,
            t_xy,
            t_terms,
            t_sum_issue,
            t_sub_issue,
            t_d,
            t_dir,
            latency: t_dir + QUEUE_LATENCY,
        }
    }
}

/// Cycles from an accepted pixel to its ray on the outputs, the queue empty and the consumer
/// ready: the one source of it.
pub fn latency(depth: usize) -> usize {
    RayGenSchedule::new(depth).latency
}

/// The depth from which every operator of the block has all its registers (a larger depth
/// builds the same block).
pub fn full_depth() -> usize {
    [Op::Add, Op::Sub, Op::Mul, Op::Recip, Op::Lt, Op::Sqrt]
        .into_iter()
        .map(fp32::max_stages)
        .chain([CoordToFp32::max_stages()])
        .max()
        .unwrap_or(0)
}

/// Pixels (i, j and the index carried beside them) in when `pixel_valid` and `pixel_ready`
/// (every other cycle at most), primary rays out in the same order, each shown from
/// `ray_valid` until `ray_ready` takes it.
#[derive(LogicBlock)]
pub struct RayGen {
    pub clock: Signal<In, Clock>,
    // The camera (fp32 words), held while the block holds rays.
    pub dx: Signal<In, Word>,
    pub x0: Signal<In, Word>,
    pub dy: Signal<In, Word>,
    pub y0: Signal<In, Word>,
    /// Rows 0 to 2 of camera-to-world.
    pub row0: [Signal<In, Word>; 3],
    pub row1: [Signal<In, Word>; 3],
    pub row2: [Signal<In, Word>; 3],
    pub camera_origin: [Signal<In, Word>; 3],
    // Pixels in.
    pub pixel_valid: Signal<In, Bit>,
    pub pixel_ready: Signal<Out, Bit>,
    pub i: Signal<In, Bits<COORD_BITS>>,
    pub j: Signal<In, Bits<COORD_BITS>>,
    pub pixel: Signal<In, Bits<PIXEL_BITS>>,
    // Rays out.
    pub ray_valid: Signal<Out, Bit>,
    pub ray_ready: Signal<In, Bit>,
    pub origin: [Signal<Out, Word>; 3],
    pub direction: [Signal<Out, Word>; 3],
    pub ray_pixel: Signal<Out, Bits<PIXEL_BITS>>,
    /// Low in the cycles a pixel may be taken.
    phase: DFF<Bit>,
    /// j, for the cycle after its pixel's.
    j_held: DFF<Bits<COORD_BITS>>,
    coord: CoordToFp32,
    scaled: Mul,
    xy: Add,
    term: [Mul; 3],
    /// r0k·x, for the cycle r1k·y is ready.
    x_term: [DFF<Word>; 3],
    /// r0k·x + r1k·y, then d_k.
    sum: [Add; 3],
    sum_at_sub: [Delay<Word>; 3],
    dir: Normalise,
    valid_at_dir: Delay<Bit>,
    pixel_at_dir: Delay<Bits<PIXEL_BITS>>,
    // The parities of the shared operators' first uses.
    scaled_odd: Constant<Bit>,
    xy_odd: Constant<Bit>,
    terms_odd: Constant<Bit>,
    sum_odd: Constant<Bit>,
    d_odd: Constant<Bit>,
    sign: Constant<Word>,
    queue: RayQueue,
    pending: DFF<Bits<PENDING_BITS>>,
    /// The credit count while it is updated.
    count: Signal<Local, Bits<PENDING_BITS>>,
    accept: Signal<Local, Bit>,
    take: Signal<Local, Bit>,
}

impl RayGen {
    pub fn new(depth: usize) -> Self {
        let s = RayGenSchedule::new(depth);
        assert!(
            s.latency < QUEUE_DEPTH,
            "ray generation's latency {} at depth {depth} needs a deeper queue than {QUEUE_DEPTH} \
             for every ray it makes",
            s.latency
        );
        Self {
            clock: Default::default(),
            dx: Default::default(),
            x0: Default::default(),
            dy: Default::default(),
            y0: Default::default(),
            row0: Default::default(),
            row1: Default::default(),
            row2: Default::default(),
            camera_origin: Default::default(),
            pixel_valid: Default::default(),
            pixel_ready: Default::default(),
            i: Default::default(),
            j: Default::default(),
            pixel: Default::default(),
            ray_valid: Default::default(),
            ray_ready: Default::default(),
            origin: Default::default(),
            direction: Default::default(),
            ray_pixel: Default::default(),
            phase: Default::default(),
            j_held: Default::default(),
            coord: CoordToFp32::new(s.t_coord),
            scaled: Mul::new(s.ops.mul),
            xy: Add::new(s.ops.add),
            term: std::array::from_fn(|_| Mul::new(s.ops.mul)),
            x_term: Default::default(),
            sum: std::array::from_fn(|_| Add::new(s.ops.add)),
            sum_at_sub: Delay::lines(s.t_sub_issue - s.t_sum_issue - s.ops.add),
            dir: Normalise::new(depth),
            valid_at_dir: Delay::new(s.t_dir),
            pixel_at_dir: Delay::new(s.t_dir),
            scaled_odd: Constant::new(s.t_coord % 2 == 1),
            xy_odd: Constant::new(s.t_scaled % 2 == 1),
            terms_odd: Constant::new(s.t_xy % 2 == 1),
            sum_odd: Constant::new(s.t_sum_issue % 2 == 1),
            d_odd: Constant::new(s.t_d % 2 == 1),
            sign: Constant::new(Word::from(1u64 << 31)),
            queue: Default::default(),
            pending: Default::default(),
            count: Default::default(),
            accept: Default::default(),
            take: Default::default(),
        }
    }
}

impl Logic for RayGen {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, phase, j_held, coord, scaled, xy, dir);
        self.phase.d.next = !self.phase.q.val();
        self.pixel_ready.next = !self.phase.q.val() & !self.pending.q.val().get_bit(7);
        self.accept.next = self.pixel_valid.val() & self.pixel_ready.val();

        // x = i·dx + x0, then y = j·dy + y0 a cycle later.
        self.j_held.d.next = self.j.val();
        self.coord.a.next = self.i.val();
        if self.phase.q.val() {
            self.coord.a.next = self.j_held.q.val();
        }
        self.scaled.a.next = self.coord.y.val();
        self.scaled.b.next = self.dx.val();
        if self.phase.q.val() ^ self.scaled_odd.val() {
            self.scaled.b.next = self.dy.val();
        }
        self.xy.a.next = self.scaled.y.val();
        self.xy.b.next = self.x0.val();
        if self.phase.q.val() ^ self.xy_odd.val() {
            self.xy.b.next = self.y0.val();
        }

        // d = (row0·x + row1·y) + (−row2), then its normalisation.
        self.dir.phase.next = self.phase.q.val() ^ self.d_odd.val();
        for k in 0..3 {
            clock!(self, clock, term[k], x_term[k], sum[k], sum_at_sub[k]);
            self.term[k].a.next = self.row0[k].val();
            if self.phase.q.val() ^ self.terms_odd.val() {
                self.term[k].a.next = self.row1[k].val();
            }
            self.term[k].b.next = self.xy.y.val();
            self.x_term[k].d.next = self.term[k].y.val();
            self.sum_at_sub[k].d.next = self.sum[k].y.val();
            if self.phase.q.val() ^ self.sum_odd.val() {
                self.sum[k].a.next = self.sum_at_sub[k].q.val();
                self.sum[k].b.next = self.row2[k].val() ^ self.sign.val();
            } else {
                self.sum[k].a.next = self.x_term[k].q.val();
                self.sum[k].b.next = self.term[k].y.val();
            }
            self.dir.v[k].next = self.sum[k].y.val();
        }

        // The pixel's valid and index beside the arithmetic; the ray into its reserved slot.
        clock!(self, clock, valid_at_dir, pixel_at_dir, queue, pending);
        self.valid_at_dir.d.next = self.accept.val();
        self.pixel_at_dir.d.next = self.pixel.val();
        self.queue.write.next = self.valid_at_dir.q.val();
        self.queue.data_in.next = bit_cast::<117, 32>(self.dir.y[0].val())
            | (bit_cast::<117, 32>(self.dir.y[1].val()) << 32)
            | (bit_cast::<117, 32>(self.dir.y[2].val()) << 64)
            | (bit_cast::<117, PIXEL_BITS>(self.pixel_at_dir.q.val()) << 96);

        // Rays out: the queue's head.
        self.ray_valid.next = !self.queue.empty.val();
        self.take.next = self.ray_ready.val() & !self.queue.empty.val();
        // The queue ignores a read while empty; driving `read` from `empty` would be a loop
        // through the queue's one `always` block in Verilator's view.
        self.queue.read.next = self.ray_ready.val();
        for k in 0..3 {
            self.origin[k].next = self.camera_origin[k].val();
            self.direction[k].next = self.queue.data_out.val().get_bits::<32>(32 * k);
        }
        self.ray_pixel.next = self.queue.data_out.val().get_bits::<PIXEL_BITS>(96);

        // Credits: one per pixel accepted, back when its ray is taken.
        self.count.next = self.pending.q.val();
        if self.accept.val() {
            self.count.next = self.count.val() + 1;
        }
        if self.take.val() {
            self.count.next = self.count.val() - 1;
        }
        self.pending.d.next = self.count.val();
    }
}

/// One cycle's inputs: the camera (held), a pixel if `pixel_valid`, and the consumer's ready.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayGenInput {
    pub camera: CameraConstants,
    pub pixel_valid: bool,
    pub i: u32,
    pub j: u32,
    pub pixel: u32,
    pub ray_ready: bool,
}

/// What the outputs show in a cycle (fp32 words).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayGenOutput {
    pub pixel_ready: bool,
    pub ray_valid: bool,
    pub origin: [u32; 3],
    pub direction: [u32; 3],
    pub pixel: u32,
}

fn word(x: hw_model::fp32::Fp32) -> Word {
    Word::from(u64::from(x.bits()))
}

impl Stepped for RayGen {
    type Input = RayGenInput;
    type Output = RayGenOutput;

    fn idle() -> RayGenInput {
        use hw_model::fp32::{Fp32, Vec3};
        RayGenInput {
            camera: CameraConstants {
                origin: Vec3::ZERO,
                rows: [Vec3::ZERO; 3],
                dx: Fp32::ZERO,
                x0: Fp32::ZERO,
                dy: Fp32::ZERO,
                y0: Fp32::ZERO,
            },
            pixel_valid: false,
            i: 0,
            j: 0,
            pixel: 0,
            ray_ready: false,
        }
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &RayGenInput) {
        let c = &input.camera;
        self.dx.next = word(c.dx);
        self.x0.next = word(c.x0);
        self.dy.next = word(c.dy);
        self.y0.next = word(c.y0);
        for (ports, row) in [&mut self.row0, &mut self.row1, &mut self.row2]
            .into_iter()
            .zip(c.rows)
        {
            for (port, x) in ports.iter_mut().zip([row.x, row.y, row.z]) {
                port.next = word(x);
            }
        }
        for (port, x) in self
            .camera_origin
            .iter_mut()
            .zip([c.origin.x, c.origin.y, c.origin.z])
        {
            port.next = word(x);
        }
        self.pixel_valid.next = input.pixel_valid;
        self.i.next = u64::from(input.i).into();
        self.j.next = u64::from(input.j).into();
        self.pixel.next = u64::from(input.pixel).into();
        self.ray_ready.next = input.ray_ready;
    }

    fn observe(&self) -> RayGenOutput {
        let words = |ports: &[Signal<Out, Word>; 3]| -> [u32; 3] {
            std::array::from_fn(|k| ports[k].val().to_u64() as u32)
        };
        RayGenOutput {
            pixel_ready: self.pixel_ready.val(),
            ray_valid: self.ray_valid.val(),
            origin: words(&self.origin),
            direction: words(&self.direction),
            pixel: self.ray_pixel.val().to_u64() as u32,
        }
    }
}

/// Runs a freshly built block at `depth` in rust-hdl's simulator, the inputs of each cycle
/// chosen by `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_raygen(
    depth: usize,
    drive: impl FnMut(Option<&RayGenOutput>) -> Option<RayGenInput> + Send + 'static,
) -> Vec<(RayGenInput, RayGenOutput)> {
    simulate_driven(move || RayGen::new(depth), drive)
}

/// Verilog of the block at `depth`, top module `top`.
pub fn raygen_verilog(depth: usize) -> String {
    built_verilog(move || RayGen::new(depth))
}
