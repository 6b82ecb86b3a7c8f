# Shared definitions of the Vivado scripts in this directory.
#
# Pure Tcl (no Vivado command is called here), so constraints/check.sh can test it with a
# plain tclsh. The port names are the ones of docs/architecture.md ("The bus"); every script
# takes them from here instead of spelling them again.

namespace eval rtfpga {
    # The board and the accelerator's defaults.
    variable part        xc7z020clg484-1
    variable top         rtfpga_top
    # Preferred ZedBoard board part first; older Vivado releases ship the Avnet board files
    # under the em.avnet.com vendor name.
    variable board_parts {avnet.com:zedboard:part0:1.4 em.avnet.com:zed:part0:1.4 em.avnet.com:zed:part0:1.3}
    # The thesis' best HLS run targeted 4.5 ns (222 MHz).
    variable ooc_period_ns 4.5

    # VLNV of the packaged IP (vendor:library:name:version); the name is the top module.
    variable ip_vendor  rtfpga.org
    variable ip_library accel
    variable ip_version 1.0

    # Ports (Vitis HLS names).
    variable clock_port     ap_clk
    variable reset_port     ap_rst_n
    variable interrupt_port interrupt
    # Block-design port driving ZedBoard LED LD0 (zedboard.xdc) from the first interrupt.
    variable led_port       led_irq
    variable axil_name      s_axi_control
    # AXI4-Lite slave signals and their direction as seen from the accelerator.
    variable axil_signals {
        awvalid in  awready out awaddr in
        wvalid  in  wready  out wdata  in wstrb in
        bvalid  out bready  in  bresp  out
        arvalid in  arready out araddr in
        rvalid  out rready  in  rdata  out rresp out
    }
    # Optional AXI4-Stream front end: s_axis_* in, m_axis_* out.
    variable axis_slave_name  s_axis
    variable axis_master_name m_axis
    variable axis_signals {tdata tvalid tready tlast}

    # Netlist cell counts reported after implementation (get_cells -hierarchical -filter),
    # named like the yosys report of `rtfpga synth`.
    variable cell_count_filters {
        LUT     {IS_PRIMITIVE && REF_NAME =~ LUT*}
        FF      {IS_PRIMITIVE && REF_NAME =~ FD*}
        DSP48E1 {IS_PRIMITIVE && REF_NAME == DSP48E1}
        CARRY4  {IS_PRIMITIVE && REF_NAME == CARRY4}
        BRAM    {IS_PRIMITIVE && REF_NAME =~ RAMB*}
    }

    # The C header `rtfpga verilog` writes next to the Verilog (hdl/src/cgen.rs HEADER_FILE)
    # and the prefix of its address macros.
    variable header_file  xrtfpga_hw.h
    variable macro_prefix XRTFPGA_CONTROL
}

# "s_axi_control_awvalid" ... in the order of axil_signals.
proc rtfpga::axil_ports {} {
    variable axil_name
    variable axil_signals
    set ports {}
    foreach {signal dir} $axil_signals {
        lappend ports ${axil_name}_$signal
    }
    return $ports
}

# AXI logical signal name (AWVALID ...) -> port name, for a bus interface's port map.
proc rtfpga::axil_port_map {} {
    variable axil_name
    variable axil_signals
    set map [dict create]
    foreach {signal dir} $axil_signals {
        dict set map [string toupper $signal] ${axil_name}_$signal
    }
    return $map
}

# Same for an AXI4-Stream interface named `name` (s_axis or m_axis).
proc rtfpga::axis_port_map {name} {
    variable axis_signals
    set map [dict create]
    foreach signal $axis_signals {
        dict set map [string toupper $signal] ${name}_$signal
    }
    return $map
}

# Port name -> direction (in/out) of every port the accelerator always has.
proc rtfpga::required_port_directions {} {
    variable clock_port
    variable reset_port
    variable interrupt_port
    variable axil_name
    variable axil_signals
    set dirs [dict create $clock_port in $reset_port in $interrupt_port out]
    foreach {signal dir} $axil_signals {
        dict set dirs ${axil_name}_$signal $dir
    }
    return $dirs
}

# Port name -> direction of the optional AXI4-Stream ports. The slave's tready is an output,
# the master's an input.
proc rtfpga::axis_port_directions {} {
    variable axis_slave_name
    variable axis_master_name
    variable axis_signals
    set dirs [dict create]
    foreach signal $axis_signals {
        set into [expr {$signal eq "tready" ? "out" : "in"}]
        set from [expr {$signal eq "tready" ? "in" : "out"}]
        dict set dirs ${axis_slave_name}_$signal $into
        dict set dirs ${axis_master_name}_$signal $from
    }
    return $dirs
}

# Parses "-name value" pairs against a dict of defaults. Every option must be known; a
# default of {} marks a required option. Returns the completed dict.
proc rtfpga::parse_args {argv defaults usage} {
    set opts $defaults
    if {[llength $argv] % 2 != 0} {
        error "expected -option value pairs, got: $argv\n$usage"
    }
    foreach {flag value} $argv {
        if {[string index $flag 0] ne "-"} {
            error "expected an option name starting with '-', got '$flag'\n$usage"
        }
        set name [string range $flag 1 end]
        if {![dict exists $defaults $name]} {
            error "unknown option '$flag' (known: -[join [dict keys $defaults] { -}])\n$usage"
        }
        dict set opts $name $value
    }
    dict for {name value} $opts {
        if {$value eq ""} {
            error "option -$name is required\n$usage"
        }
    }
    return $opts
}

# Checks that a value is an integer within [lo, hi]; returns it.
proc rtfpga::int_in_range {what value lo hi} {
    if {![string is integer -strict $value] || $value < $lo || $value > $hi} {
        error "$what must be an integer from $lo to $hi, got '$value'"
    }
    return $value
}

# Checks that a value is one of `allowed`; returns it.
proc rtfpga::choice {what value allowed} {
    if {$value ni $allowed} {
        error "$what must be one of [join $allowed {, }], got '$value'"
    }
    return $value
}

# Checks that a value is a positive number; returns it.
proc rtfpga::positive_number {what value} {
    if {![string is double -strict $value] || $value <= 0} {
        error "$what must be a positive number, got '$value'"
    }
    return $value
}

# The Verilog sources of a directory (sorted, so runs are reproducible); an error names the
# directory when there is none or when no file defines the top module.
proc rtfpga::verilog_sources {dir top} {
    if {![file isdirectory $dir]} {
        error "Verilog directory '$dir' does not exist (generate it with: rtfpga verilog --out $dir)"
    }
    set files [lsort [glob -nocomplain -directory $dir -types f *.v *.sv]]
    if {[llength $files] == 0} {
        error "no .v/.sv file in '$dir'"
    }
    foreach f $files {
        set fd [open $f r]
        set text [read $fd]
        close $fd
        if {[regexp "(^|\\n)\\s*module\\s+${top}\\M" $text]} {
            return $files
        }
    }
    error "no file in '$dir' defines module '$top'"
}

# The text of ooc.xdc with the period of its `set ooc_period_ns ...` line replaced; the
# line must appear exactly once.
proc rtfpga::xdc_with_period {xdc_text period_ns} {
    positive_number "the clock period (ns)" $period_ns
    set pattern {(?n)^set ooc_period_ns [0-9.]+$}
    set count [regsub -all $pattern $xdc_text "set ooc_period_ns $period_ns" result]
    if {$count != 1} {
        error "ooc.xdc must contain exactly one line 'set ooc_period_ns <ns>', found $count"
    }
    return $result
}

# The registers of the generated C header, in offset order: a list of dicts with name,
# offset, width, description and access (IP-XACT wording). The address macros give names
# and offsets; the header's comment table gives description and access.
proc rtfpga::registers_from_header {path} {
    variable macro_prefix
    set fd [open $path r]
    fconfigure $fd -encoding utf-8
    set lines [split [read $fd] "\n"]
    close $fd

    set regs [dict create]
    set widths [dict create]
    set comments [dict create]
    set lineno 0
    foreach line $lines {
        incr lineno
        if {[regexp "^#define\\s+${macro_prefix}_ADDR_(\\w+?)(_DATA)?\\s+0x(\[0-9a-fA-F\]+)\\s*$" \
                $line -> name data hex]} {
            if {[dict exists $regs $name]} {
                error "$path:$lineno: register $name defined twice"
            }
            dict set regs $name [expr {"0x$hex" + 0}]
        } elseif {[regexp "^#define\\s+${macro_prefix}_BITS_(\\w+)_DATA\\s+(\\d+)\\s*$" \
                $line -> name bits]} {
            dict set widths $name $bits
        } elseif {[regexp {^// 0x([0-9a-fA-F]+) : (\w+) \u2014 (.*) \(([^()]*)\)\s*$} \
                $line -> hex name text access]} {
            dict set comments $name [list [expr {"0x$hex" + 0}] $text [ipxact_access $path $lineno $access]]
        }
    }
    if {[dict size $regs] == 0} {
        error "$path: no '#define ${macro_prefix}_ADDR_* 0x..' line"
    }

    set result {}
    set seen [dict create]
    dict for {name offset} $regs {
        if {[dict exists $seen $offset]} {
            error "$path: registers [dict get $seen $offset] and $name are both at [format 0x%02x $offset]"
        }
        dict set seen $offset $name
        if {![dict exists $comments $name]} {
            error "$path: register $name has no '// 0x.. : $name \u2014 description (access)' line"
        }
        lassign [dict get $comments $name] comment_offset text access
        if {$comment_offset != $offset} {
            error "$path: register $name is at [format 0x%02x $offset] but its comment says [format 0x%02x $comment_offset]"
        }
        set width [expr {[dict exists $widths $name] ? [dict get $widths $name] : 32}]
        lappend result [dict create name $name offset $offset width $width description $text access $access]
    }
    return [lsort -command [list apply {{a b} {expr {[dict get $a offset] - [dict get $b offset]}}}] $result]
}

# The header's access words (Vitis wording) in IP-XACT terms: clear-on-read and
# toggle-on-write bits are reported as read-only and read-write.
proc rtfpga::ipxact_access {path lineno word} {
    switch -- $word {
        Read/Write { return read-write }
        Read       { return read-only }
        Read/COR   { return read-only }
        Read/TOW   { return read-write }
        default    { error "$path:$lineno: unknown access '$word' (expected Read/Write, Read, Read/COR or Read/TOW)" }
    }
}

# The bytes the AXI4-Lite slave decodes with an address port of `bits` bits (IP integrator
# still maps a window of at least 4 KiB, in which the registers repeat).
proc rtfpga::address_range {bits} {
    int_in_range "the AXI address width" $bits 2 32
    return [expr {1 << $bits}]
}
