//! The traversal unit's rust-hdl bench, for every unit type.

/// A rust-hdl bench of the unit type `$unit` (the same ports in every format and node
/// format), built by `$make(lanes, advance)`; the bench's module imports the test's (`super::*`:
/// rust-hdl's prelude, `UnitRay`, `UnitCounters`, `Hit`, `LoadStatus`, `Advance`, `StdRng`,
/// `Rng`, the packet helpers).
#[allow(unused_macros)]
macro_rules! unit_bench {
    ($unit:ty, $make:expr) => {
        use super::*;

        pub struct Bench {
            uut: Box<$unit>,
            cycles: u64,
        }

        impl Bench {
            pub fn new(lanes: usize, advance: Advance) -> Self {
                let make: fn(usize, Advance) -> $unit = $make;
                let mut uut = Box::new(make(lanes, advance));
                uut.connect_all();
                let mut b = Bench { uut, cycles: 0 };
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
                self.cycles += 1;
            }

            /// Outputs as the next rising edge will see them.
            fn settle(&mut self) {
                self.uut.clock.next = Clock { clk: false };
                assert!(simulate(self.uut.as_mut(), 1000));
            }

            pub fn load(&mut self, words: &[u32]) -> LoadStatus {
                self.uut.control.scene_start.next = true;
                self.cycle();
                self.uut.control.scene_start.next = false;
                for (i, &w) in words.iter().enumerate() {
                    self.uut.scene.tdata.next = u64::from(w).into();
                    self.uut.scene.tvalid.next = true;
                    self.uut.scene.tlast.next = i + 1 == words.len();
                    self.settle();
                    assert!(self.uut.scene.tready.val(), "scene word {i} not taken");
                    self.cycle();
                }
                self.uut.scene.tvalid.next = false;
                self.cycle();
                self.settle();
                let u = &self.uut;
                LoadStatus {
                    loading: false,
                    loaded: u.control.scene_loaded.val(),
                    error_code: u.control.scene_error_code.val().to_u64(),
                    error_word: u.control.scene_error_word.val().to_u64() as u32,
                    error_value: u.control.scene_error_value.val().to_u64() as u32,
                    nodes: words[2],
                    triangles: words[3],
                }
            }

            /// Streams `rays` in, with the hit stream's `tready` low with chance `stall`, and
            /// returns the answers by id and the counters.
            pub fn run(
                &mut self,
                rays: &[UnitRay],
                rng: &mut StdRng,
                stall: f64,
            ) -> (Vec<Option<Hit>>, UnitCounters) {
                let mut answers: Vec<Option<Option<Hit>>> = vec![None; rays.len()];
                let mut next = 0;
                let mut done = 0;
                let mut quiet = 0;
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
                    self.uut.hit.tready.next = !rng.gen_bool(stall);
                    self.settle();
                    let took_ray = self.uut.ray.tvalid.val() && self.uut.ray.tready.val();
                    let took_hit = self.uut.hit.tvalid.val() && self.uut.hit.tready.val();
                    if took_hit {
                        let packet = self.uut.hit.tdata.val();
                        let words: [u32; HIT_WORDS] =
                            std::array::from_fn(|k| packet.get_bits::<32>(32 * k).to_u64() as u32);
                        let (id, hit) = hit_from_words(&words);
                        let slot = &mut answers[id as usize];
                        assert!(slot.is_none(), "ray {id} answered twice");
                        *slot = Some(hit);
                        done += 1;
                    }
                    self.cycle();
                    if took_ray {
                        next += 1;
                    }
                    quiet = if took_ray || took_hit { 0 } else { quiet + 1 };
                    assert!(
                        quiet < 2000,
                        "the unit hangs: {done} of {} answered",
                        rays.len()
                    );
                }
                self.settle();
                let u = &self.uut;
                let c = |x: Bits<32>| x.to_u64();
                assert!(!u.control.overflow.val(), "stack overflow reported");
                let counters = UnitCounters {
                    rays: c(u.counters.rays.val()),
                    node_visits: c(u.counters.node_visits.val()),
                    box_tests: c(u.counters.box_tests.val()),
                    mt_tests: c(u.counters.mt_tests.val()),
                };
                (answers.into_iter().map(Option::unwrap).collect(), counters)
            }
        }
    };
}
