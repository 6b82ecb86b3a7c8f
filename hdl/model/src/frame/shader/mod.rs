//! Shading as programs: the shader core's instruction set ([`isa`]) and its semantics
//! ([`interpret`]), one thread per shaded ray. The frame unit's hardware shades by running
//! these programs on a time-shared fp32 datapath, so the formulas of [`super::shade`] become
//! data loaded with the scene rather than a fixed pipeline per material. [`compile`] writes a
//! scene's programs from its constants; [`thread`] turns a returned ray into a thread and a
//! thread's output into the frame model's records (and settles shadow rays, which run no
//! program).

pub mod compile;
pub mod interpret;
pub mod isa;
pub mod thread;

pub use compile::{compile, CompileError, ProgramKind};
pub use interpret::{run, Program, Pushed, Pushes, RunError, ThreadInput, ThreadOutput};
pub use isa::{Instr, IsaError, Op, Src};
