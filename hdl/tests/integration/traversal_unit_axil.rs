//! The traversal unit under AXI4-Lite control (`traversal::unit_axil`) in rust-hdl's
//! simulator, fp32: the id and size words, a scene load started over the bus (a refused
//! image's error code, word and value; then a good image), rays through the streams and the
//! counters read over the bus equal to `TraversalModel`'s, SLVERR for unmapped offsets and
//! read-only registers, RESET clearing the counters; Verilator lint of its Verilog.

use hdl::regmap::unit::{self as map, MemoryWord};
use hdl::regmap::{ConfigWord, RESP_OKAY, RESP_SLVERR};
use hdl::top::with_build_stack;
use hdl::traversal::config::UnitConfig;
use hdl::traversal::scene_memory::LoadError;
use hdl::traversal::unit_axil::{fp32::Axil4x5, unit_axil};
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::traversal::packet::{hit_from_words, HIT_WORDS, RAY_WORDS};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::wide::NodeFormat;
use hw_model::traversal::{TraversalModel, UnitCounters, UnitRay};
use hw_model::{Format, HwFormat};
use rust_hdl::prelude::*;
use sw_renderer::bvh::Bvh;
use sw_renderer::hit::Hit;

use crate::common::{mesh, rays};

fn config() -> UnitConfig {
    let mut c = UnitConfig::new(HwFormat::FP32, 1, 1);
    c.memory.node_bits = 4;
    c.memory.triangle_bits = 5;
    c
}

struct Bench {
    uut: Box<Axil4x5>,
}

impl Bench {
    fn new() -> Self {
        let mut uut = Box::new(Axil4x5::new(&config()));
        uut.connect_all();
        let mut b = Bench { uut };
        b.uut.reset_n.next = false;
        for _ in 0..3 {
            b.cycle();
        }
        b.uut.reset_n.next = true;
        b
    }

    fn cycle(&mut self) {
        self.uut.clock.next = Clock { clk: false };
        assert!(simulate(self.uut.as_mut(), 1000));
        self.uut.clock.next = Clock { clk: true };
        assert!(simulate(self.uut.as_mut(), 1000));
    }

    /// Outputs as the next rising edge will see them.
    fn settle(&mut self) {
        self.uut.clock.next = Clock { clk: false };
        assert!(simulate(self.uut.as_mut(), 1000));
    }

    /// Waits (at most 20 cycles) until `ready` holds after settling.
    fn wait(&mut self, what: &str, ready: impl Fn(&Axil4x5) -> bool) {
        for _ in 0..20 {
            self.settle();
            if ready(&self.uut) {
                return;
            }
            self.cycle();
        }
        panic!("no {what} in 20 cycles");
    }

    /// An AXI4-Lite write of all four bytes; the response code.
    fn write(&mut self, addr: usize, data: u32) -> u32 {
        let a = &mut self.uut.axi;
        a.awvalid.next = true;
        a.awaddr.next = (addr as u64).into();
        a.wvalid.next = true;
        a.wdata.next = u64::from(data).into();
        a.wstrb.next = 0xF.into();
        a.bready.next = true;
        self.wait("awready/wready", |u| {
            u.axi.awready.val() && u.axi.wready.val()
        });
        self.cycle();
        self.uut.axi.awvalid.next = false;
        self.uut.axi.wvalid.next = false;
        self.wait("bvalid", |u| u.axi.bvalid.val());
        let resp = self.uut.axi.bresp.val().to_u64() as u32;
        self.cycle();
        self.uut.axi.bready.next = false;
        resp
    }

    /// An AXI4-Lite read: (data, response code).
    fn read_resp(&mut self, addr: usize) -> (u32, u32) {
        self.uut.axi.arvalid.next = true;
        self.uut.axi.araddr.next = (addr as u64).into();
        self.uut.axi.rready.next = true;
        self.wait("arready", |u| u.axi.arready.val());
        self.cycle();
        self.uut.axi.arvalid.next = false;
        self.wait("rvalid", |u| u.axi.rvalid.val());
        let got = (
            self.uut.axi.rdata.val().to_u64() as u32,
            self.uut.axi.rresp.val().to_u64() as u32,
        );
        self.cycle();
        self.uut.axi.rready.next = false;
        got
    }

    fn read(&mut self, addr: usize) -> u32 {
        let (data, resp) = self.read_resp(addr);
        assert_eq!(resp, RESP_OKAY, "read of 0x{addr:02x}");
        data
    }

    /// LOAD_START over the bus, then the image on the scene stream; the STATUS word after.
    fn load(&mut self, words: &[u32]) -> u32 {
        assert_eq!(self.write(map::CONTROL, map::LOAD_START), RESP_OKAY);
        for (i, &w) in words.iter().enumerate() {
            self.uut.scene.tdata.next = u64::from(w).into();
            self.uut.scene.tvalid.next = true;
            self.uut.scene.tlast.next = i + 1 == words.len();
            self.wait("scene tready", |u| u.scene.tready.val());
            self.cycle();
        }
        self.uut.scene.tvalid.next = false;
        self.cycle();
        self.read(map::STATUS)
    }

    fn counters(&mut self) -> [u32; 5] {
        map::COUNTERS.map(|offset| self.read(offset))
    }

    /// Streams `rays` in one at a time and collects the answers by id.
    fn run(&mut self, rays: &[UnitRay]) -> Vec<Option<Hit>> {
        let mut answers: Vec<Option<Option<Hit>>> = vec![None; rays.len()];
        self.uut.hit.tready.next = true;
        let (mut next, mut done, mut quiet) = (0, 0, 0);
        while done < rays.len() {
            let mut data = Bits::<{ 32 * RAY_WORDS }>::default();
            if next < rays.len() {
                for (k, w) in rays[next].to_words().iter().enumerate() {
                    data = data
                        | (bit_cast::<{ 32 * RAY_WORDS }, 32>(u64::from(*w).into())
                            << (32 * k) as u64);
                }
            }
            self.uut.ray.tdata.next = data;
            self.uut.ray.tvalid.next = next < rays.len();
            self.settle();
            let took_ray = self.uut.ray.tvalid.val() && self.uut.ray.tready.val();
            if self.uut.hit.tvalid.val() {
                let packet = self.uut.hit.tdata.val();
                let words: [u32; HIT_WORDS] =
                    std::array::from_fn(|k| packet.get_bits::<32>(32 * k).to_u64() as u32);
                let (id, hit) = hit_from_words(&words);
                assert!(
                    answers[id as usize].replace(hit).is_none(),
                    "ray {id} twice"
                );
                done += 1;
            }
            let moved = took_ray || self.uut.hit.tvalid.val();
            self.cycle();
            next += usize::from(took_ray);
            quiet = if moved { 0 } else { quiet + 1 };
            assert!(
                quiet < 2000,
                "the unit hangs: {done} of {} answered",
                rays.len()
            );
        }
        self.uut.ray.tvalid.next = false;
        answers.into_iter().map(Option::unwrap).collect()
    }
}

#[test]
fn the_unit_is_controlled_and_counted_over_axi4_lite() {
    with_build_stack(|| {
        let config = config();
        let mut b = Bench::new();
        assert_eq!(b.read(map::ID), map::ID_VALUE);
        assert_eq!(
            ConfigWord::unpack(b.read(map::CONFIG)),
            ConfigWord {
                format_code: HwFormat::FP32.code(),
                depth: 1,
                lanes: 1
            }
        );
        let memory = MemoryWord::unpack(b.read(map::MEMORY));
        assert_eq!((memory.node_bits, memory.triangle_bits), (4, 5));
        assert_eq!(memory.slots as usize, config.slots);
        assert_eq!(memory.stack_depth as usize, config.stack_depth);
        assert_eq!(b.read(map::STATUS), map::IDLE);

        // Bad addresses and read-only registers answer SLVERR, as the accelerator's slave.
        let beyond = map::BUSY_CYCLES + 4;
        assert_eq!(b.read_resp(beyond), (0, RESP_SLVERR));
        assert_eq!(b.write(beyond, 1), RESP_SLVERR);
        for offset in [map::STATUS, map::ID, map::RAYS] {
            assert_eq!(b.write(offset, 0), RESP_SLVERR, "write 0x{offset:02x}");
        }
        assert_eq!(b.read(map::ID), map::ID_VALUE);

        // A refused image: the error code, the word and its value.
        let (tris, casts) = mesh(11, 24);
        let words = SceneImage::from_bvh(&Bvh::build(&tris), &tris, &casts).to_words();
        let mut bad = words.clone();
        bad[1] ^= 0x40;
        let status = b.load(&bad);
        assert_eq!(
            status & (map::SCENE_LOADED | map::SCENE_ERROR),
            map::SCENE_ERROR
        );
        assert_eq!(
            u64::from(status >> map::ERROR_CODE_LSB),
            LoadError::BadVersion.code(),
            "status 0x{status:08x}"
        );
        assert_eq!(b.read(map::SCENE_ERROR_WORD), 1);
        assert_eq!(b.read(map::SCENE_ERROR_VALUE), bad[1]);

        // The image: loaded, its length counted.
        let status = b.load(&words);
        assert_eq!(
            status,
            map::IDLE | map::SCENE_LOADED,
            "status 0x{status:08x}"
        );
        assert_eq!(b.read(map::SCENE_WORDS) as usize, words.len());

        // Rays: answers and the counters over the bus equal the model's.
        let rays = rays(3, 16, tris.len() as u32);
        let image = SceneImage::from_words(&words).unwrap();
        let model = TraversalModel::new(Format::FP32, config.stack_depth, image);
        let mut want_counters = UnitCounters::default();
        let want: Vec<Option<Hit>> = (rays.iter())
            .map(|r| model.trace(r, &mut want_counters).unwrap())
            .collect();
        let before = b.counters();
        let got = b.run(&rays);
        let bits = |h: &Option<Hit>| h.map(|h| (h.triangle, h.t.to_bits(), h.u.to_bits()));
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            assert_eq!(bits(g), bits(w), "ray {k}");
        }
        assert_eq!(b.read(map::STATUS) & map::IDLE, map::IDLE);
        let after = b.counters();
        let diff: Vec<u64> = (0..5)
            .map(|k| u64::from(after[k].wrapping_sub(before[k])))
            .collect();
        let c = want_counters;
        assert_eq!(
            diff[..4],
            [c.rays, c.node_visits, c.box_tests, c.mt_tests],
            "rays, node visits, box tests, MT tests"
        );
        assert!(diff[4] >= c.box_tests, "busy cycles {}", diff[4]);

        // RESET: held for RESET_CYCLES, then the counters read 0 and the unit is idle.
        assert_eq!(b.write(map::CONTROL, map::RESET), RESP_OKAY);
        assert_ne!(b.read(map::STATUS) & map::RESETTING, 0);
        for _ in 0..map::RESET_CYCLES {
            b.cycle();
        }
        assert_eq!(
            b.read(map::STATUS) & (map::RESETTING | map::IDLE),
            map::IDLE
        );
        assert_eq!(b.counters(), [0; 5]);
    });
}

#[test]
fn the_axi4_lite_units_verilog_passes_verilator_lint() {
    let top = unit_axil(&config(), true).unwrap();
    let verilog = top.verilog.unwrap();
    verilator_lint_waiving(&verilog, UNIT_VERILATOR_WAIVERS).unwrap();
    // The ports of config.json are the Verilog's.
    for p in &top.ports {
        let decl = if p.width > 1 {
            format!("[{}:0] {}", p.width - 1, p.name)
        } else {
            p.name.clone()
        };
        assert!(verilog.contains(&decl), "no port `{decl}`");
    }
    assert!(top.ports.iter().any(|p| p.name == "axi$awaddr"));
}

/// The top holds the unit its configuration names: a wide configuration's Verilog is the wide
/// unit's (`rtfpga verilog --unit traversal --nodes bvh8-q8` once wrote the binary unit beside
/// a config.json of the wide one). `alpha_scaled` is a field of the wide box stage
/// (`WideBoxStage`), `far_before_near` of the binary box test (`BoxTest`); rust-hdl names
/// modules after fields.
#[test]
fn the_axi4_lite_top_holds_the_configured_node_format() {
    for nodes in [NodeFormat::Bvh2Fp32, NodeFormat::Bvh4Q8, NodeFormat::Bvh8Q8] {
        let mut c = config().with_nodes(nodes);
        (c.memory.node_bits, c.memory.triangle_bits) = (4, 5);
        let top = unit_axil(&c, true).unwrap();
        let verilog = top.verilog.unwrap();
        let wide = nodes.width().is_some();
        assert_eq!(verilog.contains("$alpha_scaled"), wide, "{nodes:?}");
        assert_eq!(verilog.contains("$far_before_near"), !wide, "{nodes:?}");
    }
}

/// yosys resources of the unit's register slave alone (the unit's are BENCHMARKS.md
/// "Traversal unit: resources"):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture traversal_unit_axil::control_resources`.
#[test]
#[ignore]
fn control_resources() {
    let mut control =
        hdl::traversal::unit_axil::UnitControl::new(&UnitConfig::new(HwFormat::FP32, 5, 1));
    control.connect_all();
    let verilog = generate_verilog(&control);
    let designs = [("unit register slave (regmap::unit)".to_string(), verilog)];
    println!("{}", hdl::synth::markdown_table(&designs).unwrap());
}
