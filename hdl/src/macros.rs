//! rust-hdl's `clock!` and `dff_setup!`, also taking an element of a `Vec` or array of blocks
//! (`clock!(self, clock, lanes[l])` inside `for l in …`): rust-hdl's own macros take plain
//! field names only, while `#[hdl_gen]`, which reads an invocation by its name and not through
//! the macro, takes any field path. A module that clocks elements imports these
//! (`use crate::macros::{clock, dff_setup};`, which shadows the prelude's glob), or in a
//! module a per-format macro expands, where that import would be ambiguous beside the glob,
//! [`prelude`] in place of rust-hdl's; the others use rust-hdl's.
//!
//! Clock lines are written with one of the two everywhere but where neither can say them: a
//! `RAM`'s `read_clock` and `write_clock` (rust-hdl's `RAM` has two clock inputs and no
//! `clock`).

/// Clocks blocks: `clock!(self, clock, a, b[i])`.
macro_rules! clock {
    ($self:ident, $clock:ident, $($block:ident $([$index:expr])?),+ $(,)?) => {
        $($self.$block$([$index])?.clock.next = $self.$clock.val();)+
    };
}

/// Clocks flip-flops that hold their value unless the kernel says otherwise:
/// `dff_setup!(self, clock, a, b[i])`.
macro_rules! dff_setup {
    ($self:ident, $clock:ident, $($dff:ident $([$index:expr])?),+ $(,)?) => {
        $($self.$dff$([$index])?.clock.next = $self.$clock.val();)+
        $($self.$dff$([$index])?.d.next = $self.$dff$([$index])?.q.val();)+
    };
}
pub(crate) use {clock, dff_setup};

/// rust-hdl's prelude with [`clock!`] in place of its own.
pub(crate) mod prelude {
    pub(crate) use super::clock;
    pub use rust_hdl::prelude::*;
}
