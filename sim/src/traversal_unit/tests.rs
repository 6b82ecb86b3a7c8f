//! The driver against a behavioural unit that keeps the port contract (answers out of order
//! after random latencies, `tready` low while its slots are full, counters from the model)
//! and can break it on purpose: the driver must reproduce the model through gaps and
//! back-pressure, and turn every broken promise into an error, never a hang.

use super::*;
use hdl::traversal::scene_memory::LoadError;
use hdl::traversal::scene_memory_driver::status_result;
use hw_model::lookup;
use hw_model::traversal::scene_image::{SceneImage, MAGIC};
use hw_model::traversal::TraversalModel;
use sw_renderer::bvh::Bvh;
use sw_renderer::hit::NO_BOUND;
use sw_renderer::math::V3;
use sw_renderer::world::WorldTriangle;

/// How the behavioural unit breaks the contract.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Fault {
    None,
    /// The first answer is presented twice.
    Duplicate,
    /// The first ray taken is never answered.
    Drop,
    /// The first answer carries an id no ray has.
    UnknownId,
}

struct FakeUnit {
    model: Option<TraversalModel>,
    stack_depth: usize,
    slots: usize,
    fault: Fault,
    inputs: [u32; 7],
    ray: [u32; RAY_WORDS],
    outputs: [u32; 16],
    hit_out: [u32; HIT_WORDS],
    loading: Option<Vec<u32>>,
    loaded: bool,
    error: Option<(LoadError, u32, u32)>,
    /// (ready at cycle, answer words)
    in_flight: Vec<(u64, [u32; HIT_WORDS])>,
    counts: [u32; 5],
    overflow: Option<u32>,
    answers_given: usize,
    rays_taken: usize,
    cycle: u64,
    rng: StdRng,
}

impl FakeUnit {
    fn new(stack_depth: usize, fault: Fault) -> FakeUnit {
        FakeUnit {
            model: None,
            stack_depth,
            slots: 4,
            fault,
            inputs: [0; 7],
            ray: [0; RAY_WORDS],
            outputs: [0; 16],
            hit_out: [0; HIT_WORDS],
            loading: None,
            loaded: false,
            error: None,
            in_flight: Vec::new(),
            counts: [0; 5],
            overflow: None,
            answers_given: 0,
            rays_taken: 0,
            cycle: 0,
            rng: StdRng::seed_from_u64(99),
        }
    }

    fn input(&self, port: In) -> u32 {
        self.inputs[port as usize]
    }

    /// The answer presented now: the earliest one that is ready.
    fn presented(&self) -> Option<usize> {
        (self.in_flight.iter().enumerate())
            .filter(|(_, (at, _))| *at <= self.cycle)
            .min_by_key(|(_, (at, _))| *at)
            .map(|(k, _)| k)
    }

    fn sample(&mut self) {
        let presented = self.presented();
        let ray_tready = self.loaded && self.in_flight.len() < self.slots;
        let idle = self.in_flight.is_empty();
        let o = &mut self.outputs;
        o.fill(0);
        o[Out::SceneTready as usize] = u32::from(self.loading.is_some());
        o[Out::SceneLoaded as usize] = u32::from(self.loaded);
        if let Some((e, word, value)) = self.error {
            o[Out::SceneError as usize] = 1;
            o[Out::SceneErrorCode as usize] = e.code() as u32;
            o[Out::SceneErrorWord as usize] = word;
            o[Out::SceneErrorValue as usize] = value;
        }
        o[Out::RayTready as usize] = u32::from(ray_tready);
        o[Out::Idle as usize] = u32::from(idle);
        o[Out::Overflow as usize] = u32::from(self.overflow.is_some());
        o[Out::OverflowRay as usize] = self.overflow.unwrap_or(0);
        for (c, &v) in COUNTERS.iter().zip(&self.counts) {
            o[*c as usize] = v;
        }
        match presented {
            Some(k) => {
                o[Out::HitTvalid as usize] = 1;
                self.hit_out = self.in_flight[k].1;
            }
            None => self.hit_out = [0; HIT_WORDS],
        }
    }

    fn edge(&mut self) {
        if self.input(In::ResetN) == 0 {
            self.in_flight.clear();
            self.overflow = None;
            self.counts = [0; 5];
            return;
        }
        if !self.in_flight.is_empty() {
            self.counts[4] = self.counts[4].wrapping_add(1);
        }
        let (valid, data, last) = (
            self.input(In::SceneTvalid) == 1,
            self.input(In::SceneTdata),
            self.input(In::SceneTlast) == 1,
        );
        if self.input(In::SceneStart) == 1 {
            (self.loading, self.loaded, self.error) = (Some(Vec::new()), false, None);
        } else if let (Some(words), true) = (&mut self.loading, valid) {
            words.push(data);
            if words[0] != MAGIC {
                self.error = Some((LoadError::BadMagic, 0, words[0]));
                self.loading = None;
            } else if last {
                let image = SceneImage::from_words(words).unwrap();
                self.model = Some(TraversalModel::new(
                    lookup("fp32").unwrap(),
                    self.stack_depth,
                    image,
                ));
                (self.loading, self.loaded) = (None, true);
            }
        }
        let took_ray = self.outputs[Out::RayTready as usize] == 1 && self.input(In::RayTvalid) == 1;
        if self.outputs[Out::HitTvalid as usize] == 1 && self.input(In::HitTready) == 1 {
            let k = self.presented().unwrap();
            self.answers_given += 1;
            if !(self.fault == Fault::Duplicate && self.answers_given == 1) {
                self.in_flight.remove(k);
            }
        }
        if took_ray {
            let ray = UnitRay::from_words(&self.ray);
            let mut c = UnitCounters::default();
            let hit = match self.model.as_ref().unwrap().trace(&ray, &mut c) {
                Ok(hit) => hit,
                Err(TraversalError::StackOverflow { id, .. }) => {
                    self.overflow.get_or_insert(id);
                    None
                }
            };
            for (n, d) in
                self.counts
                    .iter_mut()
                    .zip([c.rays, c.node_visits, c.box_tests, c.mt_tests])
            {
                *n = n.wrapping_add(d as u32);
            }
            let mut words = hw_model::traversal::packet::hit_to_words(ray.id, hit);
            let first = self.rays_taken == 0;
            self.rays_taken += 1;
            if self.fault == Fault::UnknownId && first {
                words[0] ^= 0x8000_0000;
            }
            if !(self.fault == Fault::Drop && first) {
                let at = self.cycle + self.rng.gen_range(3..40);
                self.in_flight.push((at, words));
            }
        }
    }
}

impl UnitPorts for FakeUnit {
    fn set(&mut self, port: In, value: u32) {
        self.inputs[port as usize] = value;
    }
    fn ray_data(&mut self) -> &mut [u32; RAY_WORDS] {
        &mut self.ray
    }
    fn get(&self, port: Out) -> u32 {
        self.outputs[port as usize]
    }
    fn hit_data(&self) -> [u32; HIT_WORDS] {
        self.hit_out
    }
    fn cycle(&mut self) -> Result<(), SimError> {
        self.sample();
        self.edge();
        self.cycle += 1;
        Ok(())
    }
    fn cycles(&self) -> u64 {
        self.cycle
    }
}

const MEMORY: MemoryConfig = MemoryConfig {
    node_bits: 6,
    triangle_bits: 7,
};

/// A random mesh of `n` triangles on a coarse grid (duplicates and shared vertices likely).
fn mesh(n: usize, seed: u64) -> (Vec<WorldTriangle>, Vec<bool>) {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut v = || {
        V3::new(
            rng.gen_range(-4..=4) as f32,
            rng.gen_range(-4..=4) as f32,
            rng.gen_range(-4..=4) as f32,
        ) * 0.5
    };
    let tris: Vec<WorldTriangle> = (0..n)
        .map(|k| WorldTriangle {
            verts: [v(), v(), v()],
            normals: [V3::new(0.0, 0.0, 1.0); 3],
            object: (k / 8) as u32,
        })
        .collect();
    let casts = tris.iter().map(|t| t.object % 2 == 0).collect();
    (tris, casts)
}

fn image(n: usize) -> SceneImage {
    let (tris, casts) = mesh(n, 5);
    SceneImage::from_bvh(&Bvh::build(&tris), &tris, &casts)
}

/// Rays from around the mesh towards it, closest- and any-hit, ids `1000 + 7k`.
fn rays(n: usize) -> Vec<UnitRay> {
    let mut rng = StdRng::seed_from_u64(11);
    (0..n)
        .map(|k| {
            let o = [rng.gen_range(-3.0..3.0), rng.gen_range(-3.0..3.0), 4.0];
            let target = [rng.gen_range(-2.0..2.0), rng.gen_range(-2.0..2.0), 0.0f32];
            UnitRay {
                orig: o,
                dir: [target[0] - o[0], target[1] - o[1], target[2] - o[2]],
                t_max: if k % 5 == 0 { 0.9 } else { NO_BOUND },
                t_min: 0.0,
                exclude: None,
                any_hit: k % 3 == 0,
                id: 1000 + 7 * k as u32,
            }
        })
        .collect()
}

fn driver(fault: Fault, stack_depth: usize) -> UnitDriver<FakeUnit> {
    UnitDriver::new(
        FakeUnit::new(stack_depth, fault),
        MEMORY,
        NodeLayout::Binary,
        stack_depth,
    )
    .unwrap()
}

#[test]
fn answers_and_counters_equal_the_model_through_gaps_and_back_pressure() {
    let img = image(60);
    let model = TraversalModel::new(lookup("fp32").unwrap(), 32, img.clone());
    let rays = rays(200);
    let mut expected_counters = UnitCounters::default();
    let expected: Vec<Option<Hit>> = (rays.iter())
        .map(|r| model.trace(r, &mut expected_counters).unwrap())
        .collect();
    assert!(expected.iter().filter(|h| h.is_some()).count() > 20);
    let mut d = driver(Fault::None, 32);
    d.load(&img.to_words()).unwrap();
    for traffic in [
        Traffic::FULL_SPEED,
        Traffic {
            ray_gap: 0.5,
            hit_stall: 0.7,
            seed: 3,
        },
    ] {
        let mut answers = vec![None; rays.len()];
        let run = d.run(&rays, &mut answers, traffic).unwrap();
        assert_eq!(answers, expected, "{traffic:?}");
        assert_eq!(run.counters, expected_counters, "{traffic:?}");
        assert!(run.cycles > 0 && run.busy_cycles > 0 && run.busy_cycles <= run.cycles + 1);
        // Four slots: the stream waits for them.
        assert!(run.ray_stalls > 0, "{run:?}");
    }
}

#[test]
fn a_broken_answer_stream_is_an_error_not_a_hang() {
    let img = image(30);
    let rays = rays(20);
    for (fault, needle) in [
        (Fault::Duplicate, "answered twice"),
        (Fault::UnknownId, "which is not among the 20 rays"),
        (Fault::Drop, "unanswered ids [1000]"),
    ] {
        let mut d = driver(fault, 32);
        d.load(&img.to_words()).unwrap();
        let err = d
            .run(&rays, &mut vec![None; 20], Traffic::FULL_SPEED)
            .unwrap_err();
        assert!(err.to_string().contains(needle), "{fault:?}: {err}");
    }
}

#[test]
fn a_stack_overflow_is_an_error_naming_the_ray_and_the_unit_recovers() {
    let img = image(60);
    let rays = rays(40);
    let mut d = driver(Fault::None, 1);
    d.load(&img.to_words()).unwrap();
    let err = d
        .run(&rays, &mut vec![None; 40], Traffic::FULL_SPEED)
        .unwrap_err();
    match err {
        UnitError::Traversal(TraversalError::StackOverflow {
            id,
            capacity,
            depth,
        }) => {
            assert!(rays.iter().any(|r| r.id == id));
            assert_eq!((capacity, depth), (1, img.depth()));
        }
        e => panic!("{e}"),
    }
    // Reset: the scene must be loaded again.
    let again = d
        .run(&rays, &mut vec![None; 40], Traffic::FULL_SPEED)
        .unwrap_err();
    assert!(again.to_string().contains("no scene is loaded"), "{again}");
}

#[test]
fn bad_requests_and_images_are_errors_naming_what_is_wrong() {
    let img = image(30);
    let mut d = driver(Fault::None, 32);
    let mut rays = rays(3);
    let e = d
        .run(&rays, &mut [None; 3], Traffic::FULL_SPEED)
        .unwrap_err();
    assert!(e.to_string().contains("no scene is loaded"), "{e}");
    d.load(&img.to_words()).unwrap();
    rays[2].id = rays[0].id;
    let e = d
        .run(&rays, &mut [None; 3], Traffic::FULL_SPEED)
        .unwrap_err();
    assert!(
        e.to_string().contains("rays 0 and 2 share the id 1000"),
        "{e}"
    );
    let bad = Traffic {
        ray_gap: 1.0,
        ..Traffic::FULL_SPEED
    };
    let e = d.run(&rays[..1], &mut [None], bad).unwrap_err();
    assert!(e.to_string().contains("ray_gap = 1"), "{e}");

    // Too big for 64 nodes and 128 triangles: the driver's check names both sizes.
    let e = d.load(&image(300).to_words()).unwrap_err().to_string();
    assert!(
        e.contains("300 triangles") && e.contains("128 triangles"),
        "{e}"
    );
    // A damaged link: the software's checking loader refuses it before streaming.
    let mut words = img.to_words();
    words[16 + 12] = 9999;
    let e = d.load(&words).unwrap_err().to_string();
    assert!(e.contains("9999"), "{e}");
    // Streamed as is, the unit's loader refuses a bad magic word; the status names it.
    words[0] = 0x1234;
    let status = d.stream_image(&words).unwrap();
    let e = status_result(&status, &words, MEMORY)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("0x00001234") && e.contains("header word 0"),
        "{e}"
    );
}

#[test]
fn counter_differences_wrap_at_32_bits() {
    let before = Counts([u32::MAX - 1, u32::MAX, 5, 0, u32::MAX]);
    let after = Counts([3, 1, 9, 7, 2]);
    let (c, busy) = after.since(before);
    assert_eq!(
        (c.rays, c.node_visits, c.box_tests, c.mt_tests, busy),
        (5, 2, 4, 7, 3)
    );
}
