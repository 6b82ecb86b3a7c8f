//! The frame engine's ray ids: which ray-store entries are free, and how many of them the
//! running threads have reserved (docs/frame.md "The frame engine"). An entry's address is
//! its ray's id in the traversal unit. The model's part is `frame::schedule`'s store: a ray
//! takes an entry from generation (or its push) until it is shaded; a thread reserves at
//! its start the entries its pushes may need, its own entry freed; ray generation keeps a
//! spawn reserve free, threads that push reflection or refraction rays the escape reserve.
//!
//! - **Ids**: a counter hands out 0..[`IDS`] − 1 once (no initial contents, no reset); then
//!   freed ids, from two FIFOs, one per freeing source (a shadow ray's answer; a thread's
//!   start), so two frees a cycle need no arbiter. An id in either FIFO is free, so each
//!   holds at most [`IDS`] and never overflows. One id a cycle is taken: by a push (from its
//!   thread's reservation, always granted) or else by ray generation.
//! - **Counts**: ids in use and ids reserved; `available` = [`IDS`] − used − reserved. A
//!   thread start reserves `reservation` (M, the most any program of the scene pushes) and
//!   frees its own entry; a push takes a reserved id; a settle gives back M − spawned.
//!   A freed id counts as free when its FIFO shows it, [`FREE_LATENCY`] cycles after the free.
//! - **Decisions** (from the counts, before this cycle's events): `primary_ready` when
//!   more than `spawn_reserve` ids are available and no push or thread start is in this
//!   cycle (they go first, so generation never takes what they counted on); `fits` when a
//!   thread can start (M available) and `fits_above_reserve` when it can and leave
//!   `escape_reserve` available after it. The schedule model counts the starting thread's
//!   own entry as free at once (available + 1 ≥ M); here it is counted when its FIFO shows
//!   it, so a start needs one more, and the available count never goes below zero. The
//!   escape argument still holds (docs/frame.md "The frame engine": the escape pixel's
//!   entries below the reserve are at most C·D, held by its waiting rays, its deepest among
//!   them).
//!
//! The free lists are [`IdQueue`]s (`valid` from their own counts of the ids they show, not
//! from the FIFOs' `empty`). The caller keeps the protocol: it frees only ids it holds, pushes
//! only within a running thread's reservation, settles only started threads.

use rust_hdl::prelude::*;

use super::id_queue::{Count, Id, IdQueue, SHOW_LATENCY};
pub use super::id_queue::{COUNT_BITS, IDS, ID_BITS};
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::{clock, dff_setup};

/// Bits of the reservation M (a thread pushes at most 8 rays: `accumulate::SPAWNED_BITS`).
pub const RESERVATION_BITS: usize = super::accumulate::SPAWNED_BITS;
/// Cycles from a free to its id counted and taken: its FIFO shows it.
pub const FREE_LATENCY: usize = SHOW_LATENCY;
// The kernel spells the fresh counter's top bit, `ID_BITS`, as a literal.
const _: () = assert!(ID_BITS == 9);

/// Ids taken, freed and reserved; the counts' decisions.
#[derive(LogicBlock)]
pub struct RayIds {
    pub clock: Signal<In, Clock>,
    // Held while a frame runs.
    pub spawn_reserve: Signal<In, Count>,
    pub escape_reserve: Signal<In, Count>,
    pub reservation: Signal<In, Bits<RESERVATION_BITS>>,
    /// The id a take gets this cycle.
    pub id: Signal<Out, Id>,
    /// A push takes `id` from its thread's reservation.
    pub push: Signal<In, Bit>,
    /// Ray generation takes `id` when `primary_ready`.
    pub primary_valid: Signal<In, Bit>,
    pub primary_ready: Signal<Out, Bit>,
    /// A shadow ray's answer frees its id.
    pub shadow_free: Signal<In, Bit>,
    pub shadow_id: Signal<In, Id>,
    /// A thread starts: its own id freed, M reserved.
    pub start: Signal<In, Bit>,
    pub start_id: Signal<In, Id>,
    /// A thread's settle: M − `settle_spawned` given back.
    pub settle: Signal<In, Bit>,
    pub settle_spawned: Signal<In, Bits<RESERVATION_BITS>>,
    pub available: Signal<Out, Count>,
    pub fits: Signal<Out, Bit>,
    pub fits_above_reserve: Signal<Out, Bit>,
    /// Fresh ids handed out (bit 9: all of them).
    fresh: DFF<Count>,
    freed: [IdQueue; 2],
    used: DFF<Count>,
    reserved: DFF<Count>,
    ids: Constant<Count>,
    /// The counts while they are updated.
    used_next: Signal<Local, Count>,
    reserved_next: Signal<Local, Count>,
    take: Signal<Local, Bit>,
    /// The take pops FIFO 0, or FIFO 1.
    pop: [Signal<Local, Bit>; 2],
    m: Signal<Local, Count>,
}

impl Default for RayIds {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            spawn_reserve: Default::default(),
            escape_reserve: Default::default(),
            reservation: Default::default(),
            id: Default::default(),
            push: Default::default(),
            primary_valid: Default::default(),
            primary_ready: Default::default(),
            shadow_free: Default::default(),
            shadow_id: Default::default(),
            start: Default::default(),
            start_id: Default::default(),
            settle: Default::default(),
            settle_spawned: Default::default(),
            available: Default::default(),
            fits: Default::default(),
            fits_above_reserve: Default::default(),
            fresh: Default::default(),
            freed: Default::default(),
            used: Default::default(),
            reserved: Default::default(),
            ids: Constant::new((IDS as u64).into()),
            used_next: Default::default(),
            reserved_next: Default::default(),
            take: Default::default(),
            pop: Default::default(),
            m: Default::default(),
        }
    }
}

impl Logic for RayIds {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, fresh);
        clock!(self, clock, used, reserved);
        for k in 0..2 {
            clock!(self, clock, freed[k]);
        }

        // The counts' decisions, before this cycle's events.
        self.m.next = bit_cast::<COUNT_BITS, RESERVATION_BITS>(self.reservation.val());
        self.available.next = (self.ids.val() - self.used.q.val()) - self.reserved.q.val();
        self.fits.next = self.available.val() >= self.m.val();
        self.fits_above_reserve.next =
            self.available.val() >= (self.m.val() + self.escape_reserve.val());
        self.primary_ready.next = !self.push.val()
            & !self.start.val()
            & (self.spawn_reserve.val() < self.available.val());

        // The id: a fresh one, else FIFO 0's head, else FIFO 1's.
        self.take.next = self.push.val() | (self.primary_valid.val() & self.primary_ready.val());
        self.id.next = self.fresh.q.val().get_bits::<ID_BITS>(0);
        self.pop[0].next = false;
        self.pop[1].next = false;
        if self.fresh.q.val().get_bit(9) {
            self.id.next = self.freed[1].head.val();
            if self.freed[0].valid.val() {
                self.id.next = self.freed[0].head.val();
                self.pop[0].next = self.take.val();
            } else {
                self.pop[1].next = self.take.val();
            }
        } else if self.take.val() {
            self.fresh.d.next = self.fresh.q.val() + 1;
        }

        // Frees into their FIFOs, shown `FREE_LATENCY` cycles later.
        self.freed[0].write.next = self.shadow_free.val();
        self.freed[0].data_in.next = self.shadow_id.val();
        self.freed[1].write.next = self.start.val();
        self.freed[1].data_in.next = self.start_id.val();
        self.used_next.next = self.used.q.val();
        if self.take.val() {
            self.used_next.next = self.used_next.val() + 1;
        }
        for k in 0..2 {
            self.freed[k].read.next = self.pop[k].val();
            if self.freed[k].arrived.val() {
                self.used_next.next = self.used_next.val() - 1;
            }
        }
        self.used.d.next = self.used_next.val();

        // Reservations: a start's M, a push's one, a settle's unused ones.
        self.reserved_next.next = self.reserved.q.val();
        if self.start.val() {
            self.reserved_next.next = self.reserved_next.val() + self.m.val();
        }
        if self.push.val() {
            self.reserved_next.next = self.reserved_next.val() - 1;
        }
        if self.settle.val() {
            self.reserved_next.next = (self.reserved_next.val()
                + bit_cast::<COUNT_BITS, RESERVATION_BITS>(self.settle_spawned.val()))
                - self.m.val();
        }
        self.reserved.d.next = self.reserved_next.val();
    }
}

/// One cycle's inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IdsInput {
    pub spawn_reserve: usize,
    pub escape_reserve: usize,
    pub reservation: usize,
    pub push: bool,
    pub primary_valid: bool,
    pub shadow_free: Option<usize>,
    pub start: Option<usize>,
    /// A settle's spawned count.
    pub settle: Option<usize>,
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IdsOutput {
    pub id: usize,
    pub primary_ready: bool,
    pub available: usize,
    pub fits: bool,
    pub fits_above_reserve: bool,
}

impl Stepped for RayIds {
    type Input = IdsInput;
    type Output = IdsOutput;

    fn idle() -> IdsInput {
        IdsInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &IdsInput) {
        self.spawn_reserve.next = (input.spawn_reserve as u64).into();
        self.escape_reserve.next = (input.escape_reserve as u64).into();
        self.reservation.next = (input.reservation as u64).into();
        self.push.next = input.push;
        self.primary_valid.next = input.primary_valid;
        self.shadow_free.next = input.shadow_free.is_some();
        self.shadow_id.next = (input.shadow_free.unwrap_or(0) as u64).into();
        self.start.next = input.start.is_some();
        self.start_id.next = (input.start.unwrap_or(0) as u64).into();
        self.settle.next = input.settle.is_some();
        self.settle_spawned.next = (input.settle.unwrap_or(0) as u64).into();
    }

    fn observe(&self) -> IdsOutput {
        IdsOutput {
            id: self.id.val().index(),
            primary_ready: self.primary_ready.val(),
            available: self.available.val().index(),
            fits: self.fits.val(),
            fits_above_reserve: self.fits_above_reserve.val(),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_ray_ids(
    drive: impl FnMut(Option<&IdsOutput>) -> Option<IdsInput> + Send + 'static,
) -> Vec<(IdsInput, IdsOutput)> {
    simulate_driven(RayIds::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn ray_ids_verilog() -> String {
    built_verilog(RayIds::default)
}
