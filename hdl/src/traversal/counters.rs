//! The unit's counters ([`CounterPort`]): rays taken, nodes visited (inner nodes and leaves
//! entered, by a box test or a pop), box tests, Möller-Trumbore tests over all lanes (0 to 3
//! a cycle) and cycles with a ray in the unit. Each wraps at 32 bits; a reset clears them.

use rust_hdl::prelude::*;

use super::ports::CounterPort;

#[derive(LogicBlock)]
pub struct Counters {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    /// What happened this cycle: a ray taken, a box test started, a node entered by the box
    /// port and by the stack port, per lane a query issued, a ray in the unit.
    pub ray: Signal<In, Bit>,
    pub box_test: Signal<In, Bit>,
    pub box_visit: Signal<In, Bit>,
    pub pop_visit: Signal<In, Bit>,
    pub mt_test: Vec<Signal<In, Bit>>,
    /// The wide unit's (none in the binary unit's): a new ray's root node visited (its box
    /// test granted), in the same cycle as the box and the stack port's visits.
    pub root_visit: Vec<Signal<In, Bit>>,
    pub busy: Signal<In, Bit>,
    pub port: CounterPort,
    rays: DFF<Bits<32>>,
    node_visits: DFF<Bits<32>>,
    box_tests: DFF<Bits<32>>,
    mt_tests: DFF<Bits<32>>,
    busy_cycles: DFF<Bits<32>>,
    /// The MT tests so far, lane by lane.
    mt_sum: Signal<Local, Bits<32>>,
}

impl Counters {
    /// The counters of a unit with `lanes` lanes.
    pub fn new(lanes: usize) -> Self {
        Self::with_root_visits(lanes, 0)
    }

    /// The wide unit's: a root node's visit counted besides the ports'.
    pub fn wide(lanes: usize) -> Self {
        Self::with_root_visits(lanes, 1)
    }

    fn with_root_visits(lanes: usize, root_visits: usize) -> Self {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            ray: Default::default(),
            box_test: Default::default(),
            box_visit: Default::default(),
            pop_visit: Default::default(),
            mt_test: crate::defaults(lanes),
            root_visit: crate::defaults(root_visits),
            busy: Default::default(),
            port: Default::default(),
            rays: Default::default(),
            node_visits: Default::default(),
            box_tests: Default::default(),
            mt_tests: Default::default(),
            busy_cycles: Default::default(),
            mt_sum: Default::default(),
        }
    }
}

impl Logic for Counters {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            rays,
            node_visits,
            box_tests,
            mt_tests,
            busy_cycles
        );
        if self.ray.val() {
            self.rays.d.next = self.rays.q.val() + 1;
        }
        if self.box_test.val() {
            self.box_tests.d.next = self.box_tests.q.val() + 1;
        }
        self.mt_sum.next = self.mt_tests.q.val();
        for l in 0..self.mt_test.len() {
            if self.mt_test[l].val() {
                self.mt_sum.next = self.mt_sum.val() + 1;
            }
        }
        self.mt_tests.d.next = self.mt_sum.val();
        if self.box_visit.val() & self.pop_visit.val() {
            self.node_visits.d.next = self.node_visits.q.val() + 2;
        } else if self.box_visit.val() | self.pop_visit.val() {
            self.node_visits.d.next = self.node_visits.q.val() + 1;
        }
        for r in 0..self.root_visit.len() {
            if self.root_visit[r].val() {
                self.node_visits.d.next = self.node_visits.q.val() + 1;
                if self.box_visit.val() & self.pop_visit.val() {
                    self.node_visits.d.next = self.node_visits.q.val() + 3;
                } else if self.box_visit.val() | self.pop_visit.val() {
                    self.node_visits.d.next = self.node_visits.q.val() + 2;
                }
            }
        }
        if self.busy.val() {
            self.busy_cycles.d.next = self.busy_cycles.q.val() + 1;
        }
        if !self.reset_n.val() {
            self.rays.d.next = 0.into();
            self.node_visits.d.next = 0.into();
            self.box_tests.d.next = 0.into();
            self.mt_tests.d.next = 0.into();
            self.busy_cycles.d.next = 0.into();
        }
        self.port.rays.next = self.rays.q.val();
        self.port.node_visits.next = self.node_visits.q.val();
        self.port.box_tests.next = self.box_tests.q.val();
        self.port.mt_tests.next = self.mt_tests.q.val();
        self.port.busy_cycles.next = self.busy_cycles.q.val();
    }
}
