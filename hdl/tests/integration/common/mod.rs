//! Scenes and rays shared by the traversal unit's rust-hdl tests.

#[macro_use]
mod bench;
#[macro_use]
mod loader;

use hw_model::traversal::UnitRay;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use sw_renderer::math::V3;
use sw_renderer::scene::Scene;
use sw_renderer::world::WorldTriangle;

/// `count` random triangles in a box of ±4, every other object casting shadows.
pub fn mesh(seed: u64, count: usize) -> (Vec<WorldTriangle>, Vec<bool>) {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut v = || {
        V3::new(
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
        )
    };
    let tris: Vec<WorldTriangle> = (0..count)
        .map(|k| WorldTriangle {
            verts: [v(), v(), v()],
            normals: [V3::new(0.0, 0.0, 1.0); 3],
            object: (k / 3) as u32,
        })
        .collect();
    let casts = tris.iter().map(|t| t.object % 2 == 0).collect();
    (tris, casts)
}

/// `count` random rays towards the box (closest-hit and any-hit, some with t_max, t_min
/// and an excluded triangle), ids 0, 1, ….
pub fn rays(seed: u64, count: usize, triangles: u32) -> Vec<UnitRay> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..count)
        .map(|id| {
            let orig = [0; 3].map(|_| rng.gen_range(-9.0f32..9.0));
            let target = [0; 3].map(|_| rng.gen_range(-3.0f32..3.0));
            UnitRay {
                orig,
                dir: std::array::from_fn(|k| target[k] - orig[k]),
                t_max: if rng.gen_bool(0.3) {
                    rng.gen_range(0.0..1.5)
                } else {
                    f32::MAX
                },
                t_min: if rng.gen_bool(0.2) {
                    rng.gen_range(0.0..0.5)
                } else {
                    0.0
                },
                exclude: rng.gen_bool(0.2).then(|| rng.gen_range(0..triangles)),
                any_hit: rng.gen_bool(0.4),
                id: id as u32,
            }
        })
        .collect()
}

/// The fp32 words at the format's edges: ±0, subnormals, NaNs (canonical, signalling,
/// negative), ±Inf, ±MAX, ±the least normal.
pub fn fp32_edge_words() -> Vec<u32> {
    vec![
        0x0000_0000, // ±0
        0x8000_0000,
        0x0000_0001, // subnormals
        0x007F_FFFF,
        0x8000_0001,
        0x8040_0000,
        0x7FC0_0000, // NaNs: canonical, signalling, negative
        0x7F80_0001,
        0xFFFF_FFFF,
        f32::INFINITY.to_bits(),
        f32::NEG_INFINITY.to_bits(),
        f32::MAX.to_bits(),
        f32::MIN.to_bits(),
        f32::MIN_POSITIVE.to_bits(),
        (-f32::MIN_POSITIVE).to_bits(),
    ]
}

/// The columns [`print_synthesis_row`] prints after its first.
pub const SYNTHESIS_COLUMNS: &str = "LUT | FF | SRL | LUT RAM | RAMB36E1 | RAMB18E1 | DSP48E1 | CARRY4 | logic depth | Fmax estimate";

/// One Markdown row of yosys `synth_xilinx` figures, `first` in its first column, then the
/// report's critical path on a line of its own.
pub fn print_synthesis_row(first: &str, r: &hdl::synth::SynthReport) {
    let cell = |name: &str| r.cells.get(name).copied().unwrap_or(0);
    println!(
        "| {first} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
        r.lut,
        r.ff,
        r.srl,
        r.lutram,
        cell("RAMB36E1"),
        cell("RAMB18E1"),
        r.dsp48e1,
        r.carry4,
        r.logic_depth,
        r.fmax_mhz_estimate()
            .map_or("–".into(), |f| format!("{f:.0} MHz"))
    );
    print_critical_path(r);
}

/// The report's critical path (start → end, levels, delay), if yosys gave one.
pub fn print_critical_path(r: &hdl::synth::SynthReport) {
    if let Some(path) = &r.critical_path {
        println!(
            "critical path: {} → {}, {} levels, {:.2} ns",
            path.start,
            path.end,
            path.levels,
            path.delay_ps as f64 / 1000.0
        );
    }
}

/// How a block's test bench offers its inputs and takes its outputs: gaps in what it
/// offers, short and long stalls on what it takes.
#[derive(Clone, Copy, Debug)]
pub struct Traffic {
    /// Chance that a cycle offers nothing new.
    pub gap: f64,
    /// Chance that a cycle does not take an output.
    pub stall: f64,
    /// Chance that a cycle starts a long stall, and its cycles.
    pub long_stall: f64,
    pub long: usize,
}

/// Everything offered at once, every output taken at once.
pub const FLOWING: Traffic = Traffic {
    gap: 0.0,
    stall: 0.0,
    long_stall: 0.0,
    long: 0,
};

impl Traffic {
    /// Whether a consumer takes an output this cycle; `stalled` holds the cycles left of its
    /// long stall.
    pub fn ready(&self, rng: &mut StdRng, stalled: &mut usize) -> bool {
        if *stalled == 0 && rng.gen_bool(self.long_stall) {
            *stalled = self.long;
        }
        *stalled = stalled.saturating_sub(1);
        *stalled == 0 && !rng.gen_bool(self.stall)
    }
}

/// The frame model's test scenes (`hdl/model/tests/frame_scenes/`): one a material and light
/// kind.
pub const FRAME_TEST_SCENES: [&str; 5] = [
    "diffuse_distant",
    "diffuse_point",
    "mirror",
    "glass",
    "phong",
];

/// The frame test scene `name`.
pub fn frame_test_scene(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("model/tests/frame_scenes")
        .join(format!("{name}.toml"));
    Scene::load(path.to_str().unwrap()).unwrap()
}
