//! Safe wrappers around a built model's shared object and its instances.

use super::interface::Interface;
use super::shim::ABI_VERSION;
use crate::SimError;
use libloading::Library;
use std::ffi::{c_char, c_int, c_void, CString};
use std::path::{Path, PathBuf};
use std::sync::Arc;

type CreateFn = unsafe extern "C" fn() -> *mut c_void;
type DestroyFn = unsafe extern "C" fn(*mut c_void);
type RunFn = unsafe extern "C" fn(*mut c_void, u64, *const u32, *mut u32);
type EvalFn = unsafe extern "C" fn(*mut c_void, *const u32, *mut u32);
type OpenTraceFn = unsafe extern "C" fn(*mut c_void, *const c_char) -> c_int;
type CloseTraceFn = unsafe extern "C" fn(*mut c_void);
type WordsFn = unsafe extern "C" fn() -> u32;

/// The shim's entry points, resolved once per library.
#[derive(Clone, Copy)]
struct Entries {
    create: CreateFn,
    destroy: DestroyFn,
    run: RunFn,
    eval: EvalFn,
    open_trace: OpenTraceFn,
    close_trace: CloseTraceFn,
}

/// A loaded model library. Create any number of [`VerilatedModel`] instances from it.
pub struct Model {
    // Dropped last: instances hold an `Arc` to it.
    lib: Arc<Library>,
    entries: Entries,
    interface: Arc<Interface>,
    path: PathBuf,
    /// True when the shared object came from the cache rather than being built now.
    pub cached: bool,
    /// True when the model was built with `--trace` (VCD output available).
    pub trace: bool,
}

fn symbol<T: Copy>(lib: &Library, path: &Path, name: &str) -> Result<T, SimError> {
    // SAFETY: the symbol's type is the one the generated shim declares for `name`.
    unsafe { lib.get::<T>(name.as_bytes()) }
        .map(|s| *s)
        .map_err(|source| SimError::Load {
            path: path.to_path_buf(),
            source,
        })
}

impl Model {
    pub(crate) fn load(
        path: &Path,
        interface: Interface,
        cached: bool,
        trace: bool,
    ) -> Result<Self, SimError> {
        // SAFETY: the library is one this crate built from its own shim; its initialisers are
        // Verilator's and the C++ runtime's.
        let lib = unsafe { Library::new(path) }.map_err(|source| SimError::Load {
            path: path.to_path_buf(),
            source,
        })?;
        let abi: WordsFn = symbol(&lib, path, "rtfpga_abi_version")?;
        let in_words: WordsFn = symbol(&lib, path, "rtfpga_in_words")?;
        let out_words: WordsFn = symbol(&lib, path, "rtfpga_out_words")?;
        // SAFETY: argument-less getters of constants.
        let found = unsafe { (abi(), in_words() as usize, out_words() as usize) };
        let expected = (ABI_VERSION, interface.in_words(), interface.out_words());
        if found != expected {
            return Err(SimError::Interface(format!(
                "{} has (ABI, input words, output words) = {found:?}, expected {expected:?}",
                path.display()
            )));
        }
        let entries = Entries {
            create: symbol(&lib, path, "rtfpga_create")?,
            destroy: symbol(&lib, path, "rtfpga_destroy")?,
            run: symbol(&lib, path, "rtfpga_run")?,
            eval: symbol(&lib, path, "rtfpga_eval")?,
            open_trace: symbol(&lib, path, "rtfpga_open_trace")?,
            close_trace: symbol(&lib, path, "rtfpga_close_trace")?,
        };
        Ok(Model {
            lib: Arc::new(lib),
            entries,
            interface: Arc::new(interface),
            path: path.to_path_buf(),
            cached,
            trace,
        })
    }

    /// The clock and data ports, and how they are packed.
    pub fn interface(&self) -> &Interface {
        &self.interface
    }

    /// Path of the shared object.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// A fresh instance in its initial state (registers at their `initial` values).
    pub fn instantiate(&self) -> VerilatedModel {
        // SAFETY: `create` has no preconditions; the handle is destroyed exactly once in Drop.
        let handle = unsafe { (self.entries.create)() };
        VerilatedModel {
            _lib: self.lib.clone(),
            entries: self.entries,
            interface: self.interface.clone(),
            handle,
            cycles: 0,
        }
    }
}

/// One simulated instance. `Send`, so each thread may own one; not `Sync`.
pub struct VerilatedModel {
    _lib: Arc<Library>,
    entries: Entries,
    interface: Arc<Interface>,
    handle: *mut c_void,
    cycles: u64,
}

// SAFETY: an instance owns its own Verilator context and model; nothing in it is shared with
// other instances, so moving it to another thread is sound (it is used by one thread at a time).
unsafe impl Send for VerilatedModel {}

impl VerilatedModel {
    pub fn interface(&self) -> &Interface {
        &self.interface
    }

    /// Clock cycles run so far.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }

    fn check(&self, what: &str, len: usize, per_cycle: usize, n: usize) -> Result<(), SimError> {
        if len != per_cycle * n {
            return Err(SimError::Interface(format!(
                "{what} buffer has {len} words, expected {n} cycles × {per_cycle} words"
            )));
        }
        Ok(())
    }

    /// Runs `n` clock cycles; `inputs` holds `n × in_words` packed words (one vector per cycle),
    /// `outputs` receives `n × out_words` words, sampled at each rising edge.
    pub fn run(&mut self, inputs: &[u32], outputs: &mut [u32]) -> Result<(), SimError> {
        let (iw, ow) = (self.interface.in_words(), self.interface.out_words());
        let n = inputs
            .len()
            .checked_div(iw)
            .unwrap_or_else(|| outputs.len() / ow.max(1));
        self.check("input", inputs.len(), iw, n)?;
        self.check("output", outputs.len(), ow, n)?;
        // SAFETY: the buffers hold exactly n cycles' worth of words, as the shim reads/writes.
        unsafe { (self.entries.run)(self.handle, n as u64, inputs.as_ptr(), outputs.as_mut_ptr()) };
        self.cycles += n as u64;
        Ok(())
    }

    /// One clock cycle.
    pub fn step(&mut self, inputs: &[u32], outputs: &mut [u32]) -> Result<(), SimError> {
        self.check("input", inputs.len(), self.interface.in_words(), 1)?;
        self.check("output", outputs.len(), self.interface.out_words(), 1)?;
        self.run(inputs, outputs)
    }

    /// Sets the inputs and evaluates without a clock edge (combinational designs, or to peek).
    pub fn eval(&mut self, inputs: &[u32], outputs: &mut [u32]) -> Result<(), SimError> {
        self.check("input", inputs.len(), self.interface.in_words(), 1)?;
        self.check("output", outputs.len(), self.interface.out_words(), 1)?;
        // SAFETY: buffer sizes checked above.
        unsafe { (self.entries.eval)(self.handle, inputs.as_ptr(), outputs.as_mut_ptr()) };
        Ok(())
    }

    /// Starts writing a VCD of every following cycle to `path` (needs a model built with
    /// `trace: true`). Two time steps per clock cycle: clock low, clock high.
    pub fn open_trace(&mut self, path: &Path) -> Result<(), SimError> {
        let c_path = CString::new(path.to_string_lossy().as_bytes()).map_err(|_| {
            SimError::Interface(format!("trace path {} contains a NUL byte", path.display()))
        })?;
        // SAFETY: valid handle and NUL-terminated path.
        match unsafe { (self.entries.open_trace)(self.handle, c_path.as_ptr()) } {
            0 => Ok(()),
            -1 => Err(SimError::Interface(
                "model was built without tracing: build it with `trace: true`".into(),
            )),
            _ => Err(SimError::io(
                path,
                std::io::Error::other("cannot open the VCD file"),
            )),
        }
    }

    /// Flushes and closes the VCD file, if one is open.
    pub fn close_trace(&mut self) {
        // SAFETY: valid handle; closing without an open trace is a no-op in the shim.
        unsafe { (self.entries.close_trace)(self.handle) }
    }
}

impl Drop for VerilatedModel {
    fn drop(&mut self) {
        // SAFETY: the handle came from `create` and is destroyed once; the library outlives it.
        unsafe { (self.entries.destroy)(self.handle) }
    }
}
