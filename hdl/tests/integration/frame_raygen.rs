//! The frame unit's ray generation (`hdl::frame::raygen`) in rust-hdl's simulator: whole small
//! images (16×9, 7×5) bit for bit against `hw_model::frame::raygen::primary`, under random
//! gaps between pixels and random back-pressure on the rays (every ray exactly once, in pixel
//! order, with its pixel index, held while not taken; the credits running out), at depth 0,
//! 1 and full depth; pixels offered every cycle with the consumer always ready: a pixel taken
//! every `INTERVAL` cycles, ray n exactly `latency(d)` + `INTERVAL`·n cycles after the first
//! pixel; the pixel coordinate's conversion to fp32 on every coordinate; Verilator's lint.

use hdl::frame::coord::{CoordToFp32, COORD_BITS};
use hdl::frame::raygen::{
    full_depth, latency, raygen_verilog, simulate_raygen, RayGenInput, RayGenOutput, QUEUE_DEPTH,
};
use hdl::operator::simulate_operator;
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::fp32::Fp32;
use hw_model::frame::constants::CameraConstants;
use hw_model::frame::raygen::{primary, INTERVAL};
use rand::{rngs::StdRng, Rng, SeedableRng};
use sw_renderer::scene::{builtin, Mat44, Scene};
use sw_renderer::thesis_scenes::{for_test, SCENE_DIRS};

/// How the test bench offers pixels and takes rays.
#[derive(Clone, Copy, Debug)]
struct Traffic {
    /// Chance that a cycle offers no new pixel.
    gap: f64,
    /// Chance that a cycle does not take a ray.
    stall: f64,
    /// Cycles at the start in which no ray is taken (fills the queue and runs out of credits).
    held: usize,
}

/// Offers a frame's pixels in order (a pixel held until taken, as a stream's sender must) and
/// takes rays as `traffic` says, until every ray is taken and `tail` cycles more have run.
struct Bench {
    camera: CameraConstants,
    width: u32,
    pixels: u32,
    traffic: Traffic,
    rng: StdRng,
    /// The next pixel to offer, and whether it is offered.
    next: u32,
    offered: bool,
    taken: u32,
    last: Option<RayGenInput>,
    cycle: usize,
    tail: usize,
    limit: usize,
}

impl Bench {
    fn drive(&mut self, shown: Option<&RayGenOutput>) -> Option<RayGenInput> {
        if let (Some(last), Some(out)) = (self.last, shown) {
            if last.pixel_valid && out.pixel_ready {
                self.next += 1;
                self.offered = false;
            }
            if last.ray_ready && out.ray_valid {
                self.taken += 1;
            }
        }
        if self.taken >= self.pixels {
            if self.tail == 0 {
                return None;
            }
            self.tail -= 1;
        }
        if self.cycle == self.limit {
            return None;
        }
        self.cycle += 1;
        if !self.offered && self.next < self.pixels {
            self.offered = !self.rng.gen_bool(self.traffic.gap);
        }
        let input = RayGenInput {
            camera: self.camera,
            pixel_valid: self.offered,
            i: self.next % self.width,
            j: self.next / self.width,
            pixel: self.next,
            ray_ready: self.cycle > self.traffic.held && !self.rng.gen_bool(self.traffic.stall),
        };
        self.last = Some(input);
        Some(input)
    }
}

/// One image through the block at `depth`; every ray checked against the model. Returns the
/// simulated cycles (inputs and what the outputs showed).
fn image(
    depth: usize,
    what: &str,
    camera: CameraConstants,
    (width, height): (u32, u32),
    traffic: Traffic,
    seed: u64,
) -> Vec<(RayGenInput, RayGenOutput)> {
    let pixels = width * height;
    let limit = traffic.held + 20 * (pixels as usize + latency(depth)) + 100;
    let mut bench = Bench {
        camera,
        width,
        pixels,
        traffic,
        rng: StdRng::seed_from_u64(seed),
        next: 0,
        offered: false,
        taken: 0,
        last: None,
        cycle: 0,
        tail: latency(depth) + 8,
        limit,
    };
    let cycles = simulate_raygen(depth, move |shown| bench.drive(shown));
    let what = format!("depth {depth}, {what} at {width}×{height}");
    let rays: Vec<RayGenOutput> = (cycles.iter())
        .filter(|(input, out)| input.ray_ready && out.ray_valid)
        .map(|&(_, out)| out)
        .collect();
    assert_eq!(
        rays.len(),
        pixels as usize,
        "{what}: rays taken in {} cycles (limit {limit})",
        cycles.len()
    );
    for (n, ray) in (0..pixels).zip(&rays) {
        let (i, j) = (n % width, n / width);
        let (origin, dir) = primary(&camera, i, j);
        let want = RayGenOutput {
            pixel_ready: ray.pixel_ready,
            ray_valid: true,
            origin: [origin.x, origin.y, origin.z].map(Fp32::bits),
            direction: [dir.x, dir.y, dir.z].map(Fp32::bits),
            pixel: n,
        };
        assert_eq!(*ray, want, "{what}: ray {n} (pixel ({i}, {j}))");
    }
    // A ray shown and not taken is shown again unchanged.
    for pair in cycles.windows(2) {
        let [(input, out), (_, then)] = pair else {
            unreachable!()
        };
        if out.ray_valid && !input.ray_ready {
            assert!(
                then.ray_valid,
                "{what}: a ray withdrawn before it was taken"
            );
            assert_eq!(
                (then.direction, then.pixel),
                (out.direction, out.pixel),
                "{what}: a ray changed before it was taken"
            );
        }
    }
    cycles
}

/// A camera-to-world matrix rotating by `yaw`, `pitch`, `roll` degrees (about y, x, z) and
/// translating to `at`.
fn rotated(yaw: f32, pitch: f32, roll: f32, at: [f32; 3]) -> Mat44 {
    let (sy, cy) = yaw.to_radians().sin_cos();
    let (sp, cp) = pitch.to_radians().sin_cos();
    let (sr, cr) = roll.to_radians().sin_cos();
    let ry = [[cy, 0.0, -sy], [0.0, 1.0, 0.0], [sy, 0.0, cy]];
    let rx = [[1.0, 0.0, 0.0], [0.0, cp, sp], [0.0, -sp, cp]];
    let rz = [[cr, sr, 0.0], [-sr, cr, 0.0], [0.0, 0.0, 1.0]];
    let mul = |a: [[f32; 3]; 3], b: [[f32; 3]; 3]| -> [[f32; 3]; 3] {
        std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| a[r][k] * b[k][c]).sum()))
    };
    let m = mul(mul(rz, rx), ry);
    let mut out = Mat44::IDENTITY;
    for (row, m) in out.0.iter_mut().zip(m) {
        row[..3].copy_from_slice(&m);
    }
    out.0[3][..3].copy_from_slice(&at);
    out
}

/// An axis-aligned camera, a slightly rotated one (the model's test camera) and a strongly
/// rotated, translated one with a wide field of view.
fn synthetic_cameras(width: u32, height: u32) -> Vec<(String, CameraConstants)> {
    let thesis_like = Mat44::from_row_major([
        0.999945, 0.0, 0.0104718, 0.0, 0.00104703, 0.994989, -0.0999803, 0.0, -0.0104193,
        0.0999858, 0.994934, 0.0, -0.978596, 17.911879, 75.483_37, 1.0,
    ]);
    [
        ("axis-aligned camera", Mat44::IDENTITY, 90.0),
        ("slightly rotated camera", thesis_like, 36.87),
        (
            "rotated camera",
            rotated(40.0, -25.0, 10.0, [3.0, -2.0, 7.5]),
            60.0,
        ),
    ]
    .into_iter()
    .map(|(name, m, fov)| (name.into(), CameraConstants::new(&m, fov, width, height)))
    .collect()
}

/// The camera of `scene` at `width`×`height`.
fn scene_camera(scene: &Scene, width: u32, height: u32) -> (String, CameraConstants) {
    let o = &scene.options;
    let camera = CameraConstants::new(&o.camera_to_world, o.fov_deg, width, height);
    (format!("`{}` camera", scene.name), camera)
}

fn builtin_cameras(width: u32, height: u32) -> Vec<(String, CameraConstants)> {
    (builtin::names().into_iter())
        .map(|name| scene_camera(&Scene::load(name).unwrap(), width, height))
        .collect()
}

const NOISY: Traffic = Traffic {
    gap: 0.3,
    stall: 0.4,
    held: 0,
};

/// Pixels offered every cycle and no ray taken for long enough to fill the queue: the credits
/// run out, `pixel_ready` must stay low; then noisy.
fn starved(depth: usize) -> Traffic {
    Traffic {
        gap: 0.0,
        held: INTERVAL as usize * QUEUE_DEPTH + latency(depth) + 20,
        ..NOISY
    }
}

/// Runs every camera through the block at `depth` under noisy traffic, the first one (on an
/// image of more pixels than the block has credits) starved of `ray_ready` at the start.
fn cameras_at_depth(depth: usize, cameras: &[(String, CameraConstants)], size: (u32, u32)) {
    let starve = (size.0 * size.1) as usize > QUEUE_DEPTH;
    for (k, (what, camera)) in cameras.iter().enumerate() {
        let traffic = if k == 0 && starve {
            starved(depth)
        } else {
            NOISY
        };
        let cycles = image(depth, what, *camera, size, traffic, 40 + k as u64);
        if k == 0 && starve {
            // Low for a whole interval: the credits, not the phase.
            let out_of_credits = cycles
                .windows(INTERVAL as usize)
                .any(|w| w.iter().all(|(_, out)| !out.pixel_ready));
            assert!(
                out_of_credits,
                "depth {depth}, {what}: pixel_ready never stayed low with the consumer stalled"
            );
        }
    }
}

#[test]
fn raygen_matches_the_model_at_depth_1() {
    cameras_at_depth(1, &synthetic_cameras(16, 9), (16, 9));
    cameras_at_depth(1, &builtin_cameras(7, 5), (7, 5));
}

#[test]
fn raygen_matches_the_model_at_depth_0() {
    cameras_at_depth(0, &synthetic_cameras(16, 9), (16, 9));
}

#[test]
fn raygen_matches_the_model_at_full_depth() {
    let depth = full_depth();
    cameras_at_depth(depth, &synthetic_cameras(16, 9)[1..], (16, 9));
    cameras_at_depth(depth, &builtin_cameras(7, 5)[5..], (7, 5));
}

#[test]
fn raygen_matches_the_model_on_the_thesis_cameras() {
    let Some(dir) = for_test("frame_raygen::raygen_matches_the_model_on_the_thesis_cameras") else {
        return;
    };
    let cameras: Vec<_> = (SCENE_DIRS.iter())
        .map(|d| scene_camera(&Scene::load(dir.join(d).to_str().unwrap()).unwrap(), 7, 5))
        .collect();
    cameras_at_depth(1, &cameras, (7, 5));
}

/// With pixels offered every cycle and the consumer always ready, the block takes a pixel
/// every `INTERVAL` cycles (its credits never run out) and shows ray n exactly `latency(d)`
/// cycles after it took pixel n, `latency(d)` + `INTERVAL`·n from the first: the latency the
/// schedule derives is the hardware's.
#[test]
fn raygen_takes_a_pixel_every_interval_and_answers_after_its_latency() {
    let (width, height) = (16, 9);
    let pixels = (width * height) as usize;
    let interval = INTERVAL as usize;
    assert!(pixels > QUEUE_DEPTH, "more rays than credits");
    let flowing = Traffic {
        gap: 0.0,
        stall: 0.0,
        held: 0,
    };
    let (what, camera) = &synthetic_cameras(width, height)[2];
    for depth in [0, 1, full_depth()] {
        let cycles = image(depth, what, *camera, (width, height), flowing, 1);
        for (c, (input, out)) in cycles.iter().enumerate() {
            if input.pixel_valid {
                assert_eq!(
                    out.pixel_ready,
                    c % interval == 0,
                    "depth {depth}: pixel {} at cycle {c}",
                    input.pixel
                );
                assert_eq!(
                    input.pixel as usize,
                    c.div_ceil(interval),
                    "depth {depth}: a pixel every {interval} cycles"
                );
            }
            let ray = (c.checked_sub(latency(depth)))
                .filter(|n| n % interval == 0)
                .map(|n| n / interval)
                .filter(|&n| n < pixels);
            assert_eq!(
                out.ray_valid.then_some(out.pixel as usize),
                ray,
                "depth {depth}: rays at cycle {c} (latency {})",
                latency(depth)
            );
        }
    }
    assert_eq!(
        latency(1),
        1 + 5 + 1 + 6 + 2,
        "coord, five operators, r0k·x held a cycle, normalise, queue"
    );
}

#[test]
fn coord_to_fp32_is_exact_on_every_coordinate() {
    let inputs: Vec<(u64, u64)> = (0..1u64 << COORD_BITS).map(|i| (i, 0)).collect();
    for stages in 0..=CoordToFp32::max_stages() {
        let out = simulate_operator::<CoordToFp32>(stages, &inputs);
        for (&(i, _), y) in inputs.iter().zip(out) {
            let want = Fp32::of_int(i as u32).bits();
            assert_eq!(
                y as u32, want,
                "stages {stages}: {i} gave {y:#x}, want {want:#x}"
            );
        }
    }
}

#[test]
fn raygen_verilog_passes_verilator_lint() {
    // UNOPTFLAT waived as for the shader core (`UNIT_VERILATOR_WAIVERS`): a shared adder's
    // or multiplier's output comes back to its input through a register (the second use),
    // which Verilator sees as a loop between always blocks.
    for depth in [0, 3] {
        if let Err(e) = verilator_lint_waiving(&raygen_verilog(depth), UNIT_VERILATOR_WAIVERS) {
            panic!("ray generation depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

/// yosys `synth_xilinx` of ray generation at depth 1 and full depth (slow):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture
/// frame_raygen::raygen_synthesis`.
#[test]
#[ignore]
fn raygen_synthesis() {
    use crate::common::{print_synthesis_row, SYNTHESIS_COLUMNS};
    use hdl::synth::{synthesize, SynthOptions};
    println!("| depth (latency) | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for depth in [1, full_depth()] {
        let r = synthesize(&raygen_verilog(depth), "top", &SynthOptions::default())
            .expect("yosys synth_xilinx");
        print_synthesis_row(&format!("{depth} ({})", latency(depth)), &r);
    }
}
