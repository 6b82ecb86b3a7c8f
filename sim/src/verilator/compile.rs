//! Turning Verilog into a loadable shared object: `verilator --cc`, then the C++ compiler.

use super::cache;
use super::interface::Interface;
use super::progress::BuildProgress;
use super::shim;
use super::toolchain::{run, Toolchain};
use crate::SimError;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Verilator's runtime sources, compiled once per toolchain into `libverilated.a`.
const RUNTIME_SOURCES: &[&str] = &[
    "verilated.cpp",
    "verilated_vcd_c.cpp",
    "verilated_threads.cpp",
];
const RUNTIME_LIB: &str = "libverilated.a";
/// File name of a built model inside its cache entry.
pub const MODEL_LIB: &str = "model.so";

/// Compiler flags of every translation unit (Verilator's own `verilated.mk` settings).
fn cxx_flags(tc: &Toolchain, trace: bool) -> Vec<String> {
    let t = u8::from(trace);
    let mut flags: Vec<String> = [
        "-fPIC",
        "-faligned-new",
        "-fcf-protection=none",
        "-Wno-bool-operation",
        "-Wno-sign-compare",
        "-Wno-uninitialized",
        "-Wno-unused-but-set-variable",
        "-Wno-unused-parameter",
        "-Wno-unused-variable",
        "-Wno-shadow",
        "-DVM_COVERAGE=0",
        "-DVM_SC=0",
        "-DVM_TRACE_FST=0",
    ]
    .map(String::from)
    .to_vec();
    flags.push(format!("-DVM_TRACE={t}"));
    flags.push(format!("-DVM_TRACE_VCD={t}"));
    flags.push(format!("-I{}", tc.include.display()));
    flags.push(format!("-I{}", tc.include.join("vltstd").display()));
    flags
}

/// How a translation unit is compiled: its optimisation, and the precompiled header it starts
/// with, if any.
#[derive(Clone, Copy)]
struct Level<'a> {
    opt: &'a str,
    pch: Option<&'a Path>,
}

/// A model's per-cycle evaluation, and Verilator's runtime: what a simulation spends its time
/// in.
const EVAL_OPT: &str = "-O3";
/// Construction, initial and settle code (Verilator's `__Slow` files) and the symbol table
/// run once per model, so they are compiled as Verilator's own makefile does: unoptimised.
/// Measured on the 8-wide box stage (2.7 MB of Verilog): its model's C++ took 38 CPU-s with
/// these at -O1 and no precompiled header, 26 with the header, 17 with the header and -O0; a
/// 70 kB operator's 7.1 CPU-s became 1.8.
const ONCE_OPT: &str = "-O0";

/// Compiles each `(source, object, level)` with `flags`, on as many threads as there are
/// cores, counting the files done in `progress` under `stage`.
fn compile_all(
    tc: &Toolchain,
    flags: &[String],
    jobs: &[(PathBuf, PathBuf, Level)],
    include: &Path,
    progress: &BuildProgress,
    stage: &str,
) -> Result<(), SimError> {
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    progress.compiled(stage, 0, jobs.len());
    let first_error: Mutex<Option<SimError>> = Mutex::new(None);
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(jobs.len().max(1));
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some((src, obj, level)) = jobs.get(i) else {
                    break;
                };
                if first_error.lock().unwrap().is_some() {
                    break;
                }
                let command = |pch: Option<&Path>| {
                    let mut cmd = Command::new(&tc.cxx);
                    cmd.arg(level.opt);
                    if let Some(pch) = pch {
                        cmd.arg("-include").arg(pch);
                    }
                    cmd.args(flags)
                        .arg(format!("-I{}", include.display()))
                        .arg("-c")
                        .arg(src)
                        .arg("-o")
                        .arg(obj);
                    cmd
                };
                let what = format!(
                    "compiling {}",
                    src.file_name().unwrap_or_default().to_string_lossy()
                );
                // A precompiled header the compiler refuses (GCC passes over one that does not
                // match, clang stops): the file compiles without it, its own `#include` reads
                // the header.
                let compiled =
                    run(command(level.pch), "c++ compiler", &what).or_else(|e| match level.pch {
                        Some(_) => run(command(None), "c++ compiler", &what),
                        None => Err(e),
                    });
                match compiled {
                    Ok(_) => {
                        let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                        progress.compiled(stage, n, jobs.len());
                    }
                    Err(e) => {
                        first_error.lock().unwrap().get_or_insert(e);
                    }
                }
            });
        }
    });
    first_error.into_inner().unwrap().map_or(Ok(()), Err)
}

/// What every model of a toolchain shares, compiled once into the cache: Verilator's runtime
/// library and its precompiled header.
pub struct Runtime {
    /// The compiler flags of the models that use it.
    flags: Vec<String>,
    lib: PathBuf,
    eval_pch: PathBuf,
    once_pch: PathBuf,
}

/// The [`Runtime`] for models built with or without `trace`, built on first use (reported in
/// `progress`).
pub fn runtime(
    tc: &Toolchain,
    cache_root: &Path,
    trace: bool,
    progress: &BuildProgress,
) -> Result<Runtime, SimError> {
    let flags = cxx_flags(tc, trace);
    let lib = runtime_lib(tc, cache_root, progress)?;
    progress.stage("precompiling verilated.h");
    Ok(Runtime {
        eval_pch: precompiled_header(tc, cache_root, &flags, EVAL_OPT)?,
        once_pch: precompiled_header(tc, cache_root, &flags, ONCE_OPT)?,
        flags,
        lib,
    })
}

/// Verilator's runtime as a static library in the cache, built on first use (reported in
/// `progress`).
fn runtime_lib(
    tc: &Toolchain,
    cache_root: &Path,
    progress: &BuildProgress,
) -> Result<PathBuf, SimError> {
    let flags = cxx_flags(tc, true);
    let name = format!(
        "runtime-{}",
        &cache::key(&[tc.versions.as_bytes(), flags.join(" ").as_bytes()])[..16]
    );
    let (dir, _) = cache::get_or_build(cache_root, &name, |tmp| {
        let jobs: Vec<_> = RUNTIME_SOURCES
            .iter()
            .map(|src| {
                let level = Level {
                    opt: EVAL_OPT,
                    pch: None,
                };
                (
                    tc.include.join(src),
                    tmp.join(src).with_extension("o"),
                    level,
                )
            })
            .collect();
        compile_all(tc, &flags, &jobs, tmp, progress, "Verilator's runtime")?;
        let mut ar = Command::new("ar");
        ar.arg("rcs")
            .arg(tmp.join(RUNTIME_LIB))
            .args(jobs.iter().map(|j| &j.1));
        run(ar, "ar", "archiving the Verilator runtime")?;
        Ok(())
    })?;
    Ok(dir.join(RUNTIME_LIB))
}

/// The header every translation unit of a model includes first.
const PCH_SOURCE: &str = "rtfpga_pch.h";

/// `verilated.h` precompiled for translation units compiled with `flags` at `opt`, in the
/// cache, built on first use: parsing it took ~1 CPU-s of every file of every model, most of
/// a small model's build. Returns the header to `-include`; GCC reads the `.gch` beside it
/// instead when it matches the compilation, else the header itself, which includes the real
/// one; clang (which reads a `.gch` too) stops at one that does not match, and `compile_all`
/// compiles the file again without it — so a stale or foreign `.gch` costs time, never a wrong
/// build.
fn precompiled_header(
    tc: &Toolchain,
    cache_root: &Path,
    flags: &[String],
    opt: &str,
) -> Result<PathBuf, SimError> {
    let name = format!(
        "pch-{}",
        &cache::key(&[
            tc.versions.as_bytes(),
            flags.join(" ").as_bytes(),
            opt.as_bytes()
        ])[..16]
    );
    let (dir, _) = cache::get_or_build(cache_root, &name, |tmp| {
        let header = tmp.join(PCH_SOURCE);
        std::fs::write(&header, "#include <verilated.h>\n")
            .map_err(|e| SimError::io(&header, e))?;
        // Precompiled from Verilator's own header, not the copy in the temporary directory:
        // clang's precompiled header names the file it was made from and refuses to load once
        // that file is gone (the directory is renamed into the cache); GCC's does not care.
        let mut cmd = Command::new(&tc.cxx);
        cmd.arg(opt)
            .args(flags)
            .args(["-x", "c++-header"])
            .arg(tc.include.join("verilated.h"))
            .arg("-o")
            .arg(tmp.join(format!("{PCH_SOURCE}.gch")));
        run(cmd, "c++ compiler", "precompiling verilated.h")?;
        Ok(())
    })?;
    Ok(dir.join(PCH_SOURCE))
}

/// What `verilator` is told for a model (besides the output directory and the source file).
pub fn verilator_args(top: &str, trace: bool, extra: &[String]) -> Vec<String> {
    let mut args: Vec<String> = [
        "--cc",
        "-O3",
        "--x-assign",
        "fast",
        "--x-initial",
        "fast",
        "--noassert",
        "--prefix",
        "Vmodel",
        // Cut the generated functions at 2,000 statements: the C++ compiler's time grows
        // faster than linearly with a function's size. Measured on the fp16 d1 l1
        // accelerator (3 MB of Verilog): -O3 compile 57 → 39 CPU-s, simulation speed
        // unchanged within the measurement's noise (±5 %); -O1 instead saved as much
        // compile time and simulated about a third slower.
        "--output-split-cfuncs",
        "2000",
    ]
    .map(String::from)
    .to_vec();
    // rust-hdl's output has width-mismatched literals (WIDTH) and similar lint findings; they
    // are reported by the lint step, not a reason to refuse simulation.
    args.push("-Wno-fatal".into());
    args.extend(["--top-module".to_string(), top.to_string()]);
    if trace {
        args.push("--trace".into());
    }
    args.extend(extra.iter().cloned());
    args
}

/// Builds `dir/model.so` from `verilog` and the shim for `iface` against `runtime`, reporting
/// in `progress`.
pub fn model(
    progress: &BuildProgress,
    tc: &Toolchain,
    runtime: &Runtime,
    dir: &Path,
    verilog: &str,
    verilator_args: &[String],
    iface: &Interface,
) -> Result<(), SimError> {
    let v_path = dir.join("top.v");
    let obj = dir.join("obj");
    std::fs::write(&v_path, verilog).map_err(|e| SimError::io(&v_path, e))?;
    let mut cmd = Command::new(&tc.verilator);
    cmd.args(verilator_args).arg("-Mdir").arg(&obj).arg(&v_path);
    progress.stage("verilating");
    run(cmd, "verilator", "verilating the design")?;

    // The shim names the ports as Verilator did, reserved words renamed included.
    let header_path = obj.join("Vmodel.h");
    let header =
        std::fs::read_to_string(&header_path).map_err(|e| SimError::io(&header_path, e))?;
    let shim = shim::generate(iface, &shim::renamed_ports(&header, iface));
    let shim_path = obj.join("rtfpga_shim.cpp");
    std::fs::write(&shim_path, shim).map_err(|e| SimError::io(&shim_path, e))?;
    let mut jobs = Vec::new();
    for entry in std::fs::read_dir(&obj).map_err(|e| SimError::io(&obj, e))? {
        let src = entry.map_err(|e| SimError::io(&obj, e))?.path();
        if src.extension().is_some_and(|e| e == "cpp") {
            let name = src.file_name().unwrap_or_default().to_string_lossy();
            let level = if name.contains("__Slow") || name.contains("__Syms") {
                Level {
                    opt: ONCE_OPT,
                    pch: Some(&runtime.once_pch),
                }
            } else {
                Level {
                    opt: EVAL_OPT,
                    pch: Some(&runtime.eval_pch),
                }
            };
            jobs.push((src.clone(), src.with_extension("o"), level));
        }
    }
    compile_all(tc, &runtime.flags, &jobs, &obj, progress, "compiling")?;

    let mut link = Command::new(&tc.cxx);
    link.args(["-shared", "-fPIC", "-o"])
        .arg(dir.join(MODEL_LIB))
        .args(jobs.iter().map(|j| &j.1))
        .arg(&runtime.lib)
        // Keep each model's copy of the runtime private, so models loaded side by side don't mix.
        .args([
            "-Wl,--exclude-libs,ALL",
            "-Wl,-Bsymbolic",
            "-pthread",
            "-latomic",
        ]);
    progress.stage("linking");
    run(link, "c++ compiler", "linking the model")?;
    // The intermediate files are large and not needed once the model is linked.
    std::fs::remove_dir_all(&obj).map_err(|e| SimError::io(&obj, e))?;
    Ok(())
}
