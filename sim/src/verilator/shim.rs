//! The generated `extern "C"` shim between Rust and a Verilated model.
//!
//! Verilator is run with `--prefix Vmodel`, so the model class is always `Vmodel`. Per cycle the
//! shim sets the inputs, drives the clock low and evaluates, samples the outputs (the values a
//! synchronous testbench sees at the rising edge), then drives the clock high and evaluates.
//! Sampling before the edge makes "L register stages" mean "the result of cycle i's inputs is
//! returned in cycle i + L", and lets a bus driver see `ready` for the handshake of this edge.

use super::interface::Interface;
use super::ports::Port;
use std::collections::HashSet;
use std::fmt::Write;

/// Version of the C ABI below; checked when a model is loaded.
pub const ABI_VERSION: u32 = 1;

/// The C++ member name Verilator gives a Verilog identifier (its `AstNode::encodeName`).
pub fn cpp_name(verilog_name: &str) -> String {
    let name = verilog_name.strip_prefix('\\').unwrap_or(verilog_name);
    let chars: Vec<char> = name.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let plain = if i == 0 {
            c.is_ascii_alphabetic()
        } else {
            c.is_ascii_alphanumeric()
        };
        if plain {
            out.push(c);
        } else if c == '_' {
            if chars.get(i + 1) == Some(&'_') {
                out.push_str("___05F");
                i += 1;
            } else {
                out.push('_');
            }
        } else {
            let _ = write!(out, "__0{:02X}", c as u32);
        }
        i += 1;
    }
    out
}

/// The prefix Verilator puts before a port whose name is a word it reserves (C++ keywords and
/// common words such as `interrupt`; its warning SYMRSVDWORD says so).
const RESERVED_PREFIX: &str = "__SYM__";

/// Ports Verilator renamed with [`RESERVED_PREFIX`], read from the model header `Vmodel.h`
/// it wrote (its list of reserved words changes between versions, so the header is the truth).
pub fn renamed_ports(header: &str, iface: &Interface) -> HashSet<String> {
    let clock = iface.clock.iter();
    let names = iface
        .inputs
        .iter()
        .chain(&iface.outputs)
        .map(|p| &p.name)
        .chain(clock);
    names
        .filter(|name| {
            let member = format!("(&{RESERVED_PREFIX}{},", cpp_name(name));
            header.contains(&member)
        })
        .cloned()
        .collect()
}

/// The model's member for Verilog port `name`, given the ports Verilator renamed.
fn member(name: &str, renamed: &HashSet<String>) -> String {
    if renamed.contains(name) {
        format!("{RESERVED_PREFIX}{}", cpp_name(name))
    } else {
        cpp_name(name)
    }
}

fn mask(bits: u32) -> String {
    if bits == 32 {
        "0xFFFFFFFFu".into()
    } else {
        format!("0x{:X}u", (1u64 << bits) - 1)
    }
}

/// Statements copying packed words at `buf[offset..]` into input port `p`.
fn set_input(code: &mut String, p: &Port, offset: usize, renamed: &HashSet<String>) {
    let m = member(&p.name, renamed);
    let top_bits = (p.width - 1) % 32 + 1;
    match p.words() {
        1 => writeln!(code, "    m->{m} = in[{offset}] & {};", mask(top_bits)),
        2 => writeln!(
            code,
            "    m->{m} = (QData)in[{offset}] | ((QData)(in[{}] & {}) << 32);",
            offset + 1,
            mask(top_bits)
        ),
        n => {
            for w in 0..n {
                let bits = if w + 1 == n { top_bits } else { 32 };
                writeln!(
                    code,
                    "    m->{m}[{w}] = in[{}] & {};",
                    offset + w,
                    mask(bits)
                )
                .unwrap();
            }
            Ok(())
        }
    }
    .unwrap();
}

/// Statements copying output port `p` into packed words at `buf[offset..]`.
fn get_output(code: &mut String, p: &Port, offset: usize, renamed: &HashSet<String>) {
    let m = member(&p.name, renamed);
    match p.words() {
        1 => writeln!(code, "    out[{offset}] = (uint32_t)m->{m};").unwrap(),
        2 => {
            writeln!(code, "    out[{offset}] = (uint32_t)m->{m};").unwrap();
            writeln!(code, "    out[{}] = (uint32_t)(m->{m} >> 32);", offset + 1).unwrap();
        }
        n => {
            for w in 0..n {
                writeln!(code, "    out[{}] = m->{m}[{w}];", offset + w).unwrap();
            }
        }
    }
}

/// The C++ source of the shim for `iface`, whose ports in `renamed` Verilator prefixed with
/// [`RESERVED_PREFIX`] (see [`renamed_ports`]).
pub fn generate(iface: &Interface, renamed: &HashSet<String>) -> String {
    let mut set = String::new();
    let mut offset = 0;
    for p in &iface.inputs {
        set_input(&mut set, p, offset, renamed);
        offset += p.words();
    }
    let mut get = String::new();
    offset = 0;
    for p in &iface.outputs {
        get_output(&mut get, p, offset, renamed);
        offset += p.words();
    }
    let (clock_low, clock_high) = match &iface.clock {
        Some(c) => (
            format!("m->{} = 0;", member(c, renamed)),
            format!("m->{} = 1;", member(c, renamed)),
        ),
        None => (String::new(), String::new()),
    };
    let cycle_body = if iface.clock.is_some() {
        format!(
            "        set_inputs(m, in);\n        {clock_low}\n        m->eval();\n        dump(h);\n        \
             get_outputs(m, out);\n        {clock_high}\n        m->eval();\n        dump(h);\n"
        )
    } else {
        "        set_inputs(m, in);\n        m->eval();\n        dump(h);\n        get_outputs(m, out);\n".into()
    };
    format!(
        r#"// Generated by the rtfpga model builder: do not edit.
#include "Vmodel.h"
#include "verilated.h"
#if VM_TRACE
#include "verilated_vcd_c.h"
#endif
#include <cstdint>

#define RT_EXPORT extern "C" __attribute__((visibility("default")))

namespace {{
const uint32_t IN_WORDS = {in_words};
const uint32_t OUT_WORDS = {out_words};

struct Handle {{
    VerilatedContext* ctx;
    Vmodel* m;
    uint64_t time;
#if VM_TRACE
    VerilatedVcdC* tfp;
#endif
}};

inline void set_inputs(Vmodel* m, const uint32_t* in) {{
    (void)m; (void)in;
{set}}}

inline void get_outputs(const Vmodel* m, uint32_t* out) {{
    (void)m; (void)out;
{get}}}

inline void dump(Handle* h) {{
#if VM_TRACE
    if (h->tfp) h->tfp->dump(h->time);
#endif
    h->time++;
}}
}}  // namespace

RT_EXPORT uint32_t rtfpga_abi_version() {{ return {abi}; }}
RT_EXPORT uint32_t rtfpga_in_words() {{ return IN_WORDS; }}
RT_EXPORT uint32_t rtfpga_out_words() {{ return OUT_WORDS; }}

RT_EXPORT void* rtfpga_create() {{
    Handle* h = new Handle();
    h->ctx = new VerilatedContext();
#if VM_TRACE
    h->ctx->traceEverOn(true);
    h->tfp = nullptr;
#endif
    h->m = new Vmodel(h->ctx, "TOP");
    h->time = 0;
    Vmodel* m = h->m;
    (void)m;
    {clock_low}
    h->m->eval();
    return h;
}}

RT_EXPORT int rtfpga_open_trace(void* hp, const char* path) {{
#if VM_TRACE
    Handle* h = static_cast<Handle*>(hp);
    if (h->tfp) {{ h->tfp->close(); delete h->tfp; }}
    h->tfp = new VerilatedVcdC();
    h->m->trace(h->tfp, 99);
    h->tfp->open(path);
    if (!h->tfp->isOpen()) {{ delete h->tfp; h->tfp = nullptr; return -2; }}
    return 0;
#else
    (void)hp; (void)path;
    return -1;
#endif
}}

RT_EXPORT void rtfpga_close_trace(void* hp) {{
#if VM_TRACE
    Handle* h = static_cast<Handle*>(hp);
    if (h->tfp) {{ h->tfp->close(); delete h->tfp; h->tfp = nullptr; }}
#else
    (void)hp;
#endif
}}

RT_EXPORT void rtfpga_destroy(void* hp) {{
    Handle* h = static_cast<Handle*>(hp);
    rtfpga_close_trace(hp);
    h->m->final();
    delete h->m;
    delete h->ctx;
    delete h;
}}

// n cycles: in holds n * IN_WORDS words, out receives n * OUT_WORDS words.
RT_EXPORT void rtfpga_run(void* hp, uint64_t n, const uint32_t* in, uint32_t* out) {{
    Handle* h = static_cast<Handle*>(hp);
    Vmodel* m = h->m;
    for (uint64_t i = 0; i < n; ++i, in += IN_WORDS, out += OUT_WORDS) {{
{cycle_body}    }}
}}

// Combinational evaluation without a clock edge.
RT_EXPORT void rtfpga_eval(void* hp, const uint32_t* in, uint32_t* out) {{
    Handle* h = static_cast<Handle*>(hp);
    set_inputs(h->m, in);
    h->m->eval();
    get_outputs(h->m, out);
}}
"#,
        in_words = iface.in_words(),
        out_words = iface.out_words(),
        abi = ABI_VERSION,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_encoded_like_verilator() {
        assert_eq!(cpp_name("b$x"), "b__024x");
        assert_eq!(cpp_name("ap_clk"), "ap_clk");
        assert_eq!(cpp_name("a__b"), "a___05Fb");
        assert_eq!(cpp_name("\\odd.name"), "odd__02Ename");
    }

    #[test]
    fn reserved_ports_are_found_in_the_header() {
        use crate::verilator::{Direction, Port};
        let ports = [
            Port::new("clk", Direction::Input, 1),
            Port::new("interrupt", Direction::Output, 1),
            Port::new("a$b", Direction::Input, 8),
        ];
        let iface = Interface::new(&ports, Some("clk")).unwrap();
        let header = "    VL_IN8(&clk,0,0);\n    VL_OUT8(&__SYM__interrupt,0,0);\n    VL_IN8(&a__024b,7,0);\n";
        let renamed = renamed_ports(header, &iface);
        assert_eq!(renamed, HashSet::from(["interrupt".to_string()]));
        let shim = generate(&iface, &renamed);
        assert!(shim.contains("(uint32_t)m->__SYM__interrupt;"), "{shim}");
        assert!(shim.contains("m->a__024b = in[0]"), "{shim}");
        assert!(shim.contains("m->clk = 1;"), "{shim}");
    }

    #[test]
    fn masks_cover_the_top_word() {
        assert_eq!(mask(1), "0x1u");
        assert_eq!(mask(32), "0xFFFFFFFFu");
        assert_eq!(mask(8), "0xFFu");
    }
}
