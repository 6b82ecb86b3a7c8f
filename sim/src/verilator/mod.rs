//! The Verilator model builder: Verilog text in, a loaded simulation model out.
//!
//! `build` runs `verilator --cc` on the Verilog, compiles the C++ together with a generated
//! `extern "C"` shim (see `shim`) and loads the shared object with `libloading`. Results are
//! cached on disk by a SHA-256 of everything that goes into them, and Verilator's runtime is
//! compiled once per toolchain and reused.

mod built;
mod cache;
mod compile;
mod interface;
mod model;
mod pipelined;
mod ports;
mod progress;
mod shim;
mod toolchain;

pub use built::{BuiltModel, BuiltModels};
pub use cache::{default_dir as default_cache_dir, remove_unfinished_builds};
pub use interface::Interface;
pub use model::{Model, VerilatedModel};
pub use pipelined::run_pipelined;
pub use ports::{parse_ports, Direction, Port};
pub use progress::show_build_progress;
pub use toolchain::find_on_path;

use crate::SimError;
use std::ffi::OsString;
use std::path::PathBuf;

/// Bump when the build recipe changes, so old cache entries are not reused.
const RECIPE_VERSION: &str = "rtfpga-verilator-builder-2";

/// The design to build.
#[derive(Clone, Debug)]
pub struct ModelSpec {
    pub verilog: String,
    pub top: String,
    /// The top's ports; `None` reads them from the Verilog.
    pub ports: Option<Vec<Port>>,
    /// The clock input (rust-hdl names it `clock`, the Vitis-style tops `ap_clk`); `None` for a
    /// combinational design, where one "cycle" is one evaluation.
    pub clock: Option<String>,
}

impl ModelSpec {
    /// A rust-hdl design: top module `top`, clock `clock`, ports read from the Verilog.
    pub fn rust_hdl(verilog: impl Into<String>) -> Self {
        ModelSpec {
            verilog: verilog.into(),
            top: "top".into(),
            ports: None,
            clock: Some("clock".into()),
        }
    }
}

/// How to build.
#[derive(Clone, Debug)]
pub struct BuildOptions {
    /// Build the `--trace` variant, whose instances can write VCD files.
    pub trace: bool,
    /// Cache directory; `None` means [`default_cache_dir`].
    pub cache_dir: Option<PathBuf>,
    /// The PATH searched for `verilator` and the C++ compiler; `None` means the process's PATH.
    pub search_path: Option<OsString>,
    /// Names (or paths) of the tools; `cxx: None` takes clang++ when it is on the search path,
    /// else g++ (`toolchain::CXX_PREFERENCE`).
    pub verilator: String,
    pub cxx: Option<String>,
    /// Extra arguments for `verilator`, e.g. `-Wno-UNOPTFLAT`.
    pub verilator_args: Vec<String>,
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions {
            trace: false,
            cache_dir: None,
            search_path: None,
            verilator: "verilator".into(),
            cxx: None,
            verilator_args: Vec::new(),
        }
    }
}

/// Builds (or takes from the cache) and loads the model of `spec`.
pub fn build(spec: &ModelSpec, options: &BuildOptions) -> Result<Model, SimError> {
    let path_var = options
        .search_path
        .clone()
        .or_else(|| std::env::var_os("PATH"));
    let tc = toolchain::Toolchain::locate(
        &options.verilator,
        options.cxx.as_deref(),
        path_var.as_ref(),
    )?;
    let ports = match &spec.ports {
        Some(p) => p.clone(),
        None => parse_ports(&spec.verilog, &spec.top)?,
    };
    let iface = Interface::new(&ports, spec.clock.as_deref())?;
    // The key takes the shim as if no port were renamed: Verilator's renaming follows from
    // the Verilog and its version, which the key holds too.
    let shim_src = shim::generate(&iface, &Default::default());
    let args = compile::verilator_args(&spec.top, options.trace, &options.verilator_args);
    let root = options.cache_dir.clone().unwrap_or_else(default_cache_dir);
    let key = cache::key(&[
        RECIPE_VERSION.as_bytes(),
        tc.versions.as_bytes(),
        spec.verilog.as_bytes(),
        shim_src.as_bytes(),
        args.join("\0").as_bytes(),
    ]);
    let name = format!("model-{key}");
    let (dir, cached) = if root.join(&name).is_dir() {
        (root.join(&name), true)
    } else {
        let progress =
            progress::BuildProgress::start(&format!("the Verilated model {}", &name[..14]), &root);
        let built = compile::runtime(&tc, &root, options.trace, &progress).and_then(|runtime| {
            cache::get_or_build(&root, &name, |tmp| {
                compile::model(&progress, &tc, &runtime, tmp, &spec.verilog, &args, &iface)
            })
        });
        progress.finish(built.is_ok());
        built?
    };
    Model::load(&dir.join(compile::MODEL_LIB), iface, cached, options.trace)
}
