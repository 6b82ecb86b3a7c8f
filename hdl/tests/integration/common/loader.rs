//! Driving a scene memory's loader (binary or wide: `scene_memory_block!` gives both the same
//! loader ports) from a rust-hdl bench.

/// The loader methods of a bench struct with fields `uut` (a scene memory), `rng` (`StdRng`)
/// and `gap` (the chance of an idle cycle before each beat); the test module imports
/// rust-hdl's prelude, `LoadStatus` and `Rng`.
#[allow(unused_macros)]
macro_rules! scene_loader_methods {
    () => {
        /// One clock cycle with the inputs as set; returns `s_tready` as the edge saw it.
        fn cycle(&mut self) -> bool {
            self.uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut self.uut, 200));
            let ready = self.uut.s_tready.val();
            self.uut.clock.next = Clock { clk: true };
            assert!(simulate(&mut self.uut, 200));
            ready
        }

        fn idle(&mut self) {
            self.uut.start_load.next = false;
            self.uut.s_tvalid.next = false;
            self.uut.s_tlast.next = false;
            self.cycle();
        }

        /// Starts a load and streams `words` up to `tlast` on word `last` (all of them
        /// without), with random idle cycles; every beat must be taken at once (`s_tready` is
        /// high from `start_load` to the packet's `tlast`). Then idles a few cycles and
        /// returns the status.
        fn load(&mut self, words: &[u32], last: Option<usize>) -> LoadStatus {
            let words = &words[..last.map_or(words.len(), |l| l + 1)];
            self.uut.start_load.next = true;
            assert!(!self.cycle(), "s_tready must be low with start_load");
            self.uut.start_load.next = false;
            for (i, &w) in words.iter().enumerate() {
                while self.rng.gen_bool(self.gap) {
                    self.uut.s_tvalid.next = false;
                    self.cycle();
                }
                self.uut.s_tdata.next = u64::from(w).into();
                self.uut.s_tvalid.next = true;
                self.uut.s_tlast.next = Some(i) == last;
                assert!(self.cycle(), "beat {i} of {} not taken", words.len());
            }
            for _ in 0..3 {
                self.idle();
            }
            self.status()
        }

        fn status(&mut self) -> LoadStatus {
            self.uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut self.uut, 200));
            let u = &self.uut;
            LoadStatus {
                loading: u.loading.val(),
                loaded: u.loaded.val(),
                error_code: u.error_code.val().to_u64(),
                error_word: u.error_word.val().to_u64() as u32,
                error_value: u.error_value.val().to_u64() as u32,
                nodes: u.nodes.val().to_u64() as u32,
                triangles: u.triangles.val().to_u64() as u32,
            }
        }

        /// One clock edge with the inputs as set, then the outputs it produced.
        fn sample_after_edge(&mut self) {
            self.cycle();
            self.uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut self.uut, 200));
        }
    };
}
