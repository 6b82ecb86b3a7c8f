# Tests of the Vivado collateral without Vivado: the pure-Tcl helpers, the XDC files in an
# interpreter that only has XDC commands, and dry runs of the three flow scripts against
# vivado_mock.tcl. Usage: tclsh run_tests.tcl ARCHITECTURE_MD [HEADER]
# (HEADER: a C header written by `rtfpga verilog`, to compare with the architecture's map).
# Exits 1 if any check fails.

set test_dir [file dirname [file normalize [info script]]]
set constraints_dir [file dirname $test_dir]
source [file join $constraints_dir rtfpga_common.tcl]

lassign $argv arch_doc real_header
set checks 0
set failures 0

proc check {what ok {detail ""}} {
    incr ::checks
    if {!$ok} {
        incr ::failures
        puts "FAIL: $what $detail"
    }
}

proc check_equal {what actual expected} {
    check $what [expr {$actual eq $expected}] "\n  expected: $expected\n  actual:   $actual"
}

# Runs `body` expecting an error whose message matches the glob `pattern`.
proc check_error {what pattern body} {
    set failed [catch {uplevel 1 $body} message]
    check "$what (error expected)" [expr {$failed && [string match $pattern $message]}] "got: $message"
}

proc write_file {path text} {
    set fd [open $path w]
    fconfigure $fd -encoding utf-8
    puts -nonewline $fd $text
    close $fd
}

set tmp [file join [expr {[info exists env(TMPDIR)] ? $env(TMPDIR) : "/tmp"}] rtfpga_constraints_[pid]]
file delete -force $tmp
file mkdir $tmp

# ---------------------------------------------------------------------------------------
# Helpers of rtfpga_common.tcl.

set defaults [dict create verilog {} out {} period 4.5]
check_equal "parse_args fills defaults" \
    [rtfpga::parse_args {-verilog v -out o} $defaults U] [dict create verilog v out o period 4.5]
check_equal "parse_args overrides" \
    [dict get [rtfpga::parse_args {-out o -period 10 -verilog v} $defaults U] period] 10
check_error "parse_args unknown option" "unknown option '-perod'*" {
    rtfpga::parse_args {-verilog v -out o -perod 3} $defaults U
}
check_error "parse_args required option" "option -out is required*" {
    rtfpga::parse_args {-verilog v} $defaults U
}
check_error "parse_args odd argument count" "expected -option value pairs*" {
    rtfpga::parse_args {-verilog} $defaults U
}
check_error "parse_args value without name" "expected an option name*" {
    rtfpga::parse_args {verilog v} $defaults U
}
check_equal "int_in_range accepts" [rtfpga::int_in_range n 16 1 16] 16
check_error "int_in_range rejects 17" "n must be an integer from 1 to 16, got '17'" {
    rtfpga::int_in_range n 17 1 16
}
check_error "int_in_range rejects text" "*got 'two'" { rtfpga::int_in_range n two 1 16 }
check_error "positive_number rejects 0" "*positive number*" { rtfpga::positive_number p 0 }
check_error "choice rejects" "x must be one of a, b, got 'c'" { rtfpga::choice x c {a b} }
check_equal "address_range of a 7-bit address" [rtfpga::address_range 7] 128
check_equal "17 AXI4-Lite ports" [llength [rtfpga::axil_ports]] 17
check_equal "AXI4-Lite port map" [dict get [rtfpga::axil_port_map] ARADDR] s_axi_control_araddr
check_equal "AXI4-Stream directions" \
    [dict get [rtfpga::axis_port_directions] s_axis_tready][dict get [rtfpga::axis_port_directions] m_axis_tready] outin

set xdc_fixture "# c\nset ooc_period_ns 4.5\ncreate_clock -period \$ooc_period_ns\n"
check_equal "xdc_with_period" [rtfpga::xdc_with_period $xdc_fixture 6.25] \
    "# c\nset ooc_period_ns 6.25\ncreate_clock -period \$ooc_period_ns\n"
check_error "xdc_with_period needs the line" "*exactly one line*found 0" {
    rtfpga::xdc_with_period "create_clock -period 3\n" 4
}
check_error "xdc_with_period rejects a second line" "*found 2" {
    rtfpga::xdc_with_period "set ooc_period_ns 1\nset ooc_period_ns 2\n" 4
}
check_error "xdc_with_period rejects a bad period" "*positive number*" {
    rtfpga::xdc_with_period $xdc_fixture -1
}

set vdir [file join $tmp verilog]
file mkdir $vdir
write_file [file join $vdir body.v] "module rtfpga_body(input a);\nendmodule\n"
write_file [file join $vdir rtfpga_top.v] "// top\nmodule rtfpga_top (\n  input ap_clk\n);\nendmodule\n"
check_equal "verilog_sources lists every file" \
    [rtfpga::verilog_sources $vdir rtfpga_top] [list [file join $vdir body.v] [file join $vdir rtfpga_top.v]]
check_error "verilog_sources needs the top" "no file in '*' defines module 'rtfpga_to'" {
    rtfpga::verilog_sources $vdir rtfpga_to
}
check_error "verilog_sources needs the directory" "Verilog directory '*' does not exist*" {
    rtfpga::verilog_sources [file join $tmp missing] rtfpga_top
}

# The header format of hdl/src/cgen.rs, a few registers.
set header_fixture [string map [list @ \u2014] {// Generated from hdl/src/regmap.rs — do not edit.
// 0x00 : AP_CTRL @ block-level control (ap_ctrl_hs) (Read/Write)
//        bit 0 - AP_START (Read/Write): write 1 to start
// 0x0c : ISR @ IP interrupt status (Read/TOW)
// 0x10 : ORIG_X @ ray origin x (fp32 bits) (Read/Write)
// 0x50 : RESULT @ result flags (Read)
// 0x54 : T @ distance along the ray (fp32 bits) (Read)

#ifndef XRTFPGA_HW_H
#define XRTFPGA_HW_H

#define XRTFPGA_CONTROL_ADDR_AP_CTRL                     0x00
#define XRTFPGA_CONTROL_ADDR_ISR                         0x0c
#define XRTFPGA_CONTROL_ADDR_ORIG_X_DATA                 0x10
#define XRTFPGA_CONTROL_BITS_ORIG_X_DATA                 32
#define XRTFPGA_CONTROL_ADDR_RESULT_DATA                 0x50
#define XRTFPGA_CONTROL_BITS_RESULT_DATA                 1
#define XRTFPGA_CONTROL_ADDR_T_DATA                      0x54
#define XRTFPGA_CONTROL_BITS_T_DATA                      32
#define XRTFPGA_CONTROL_AP_CTRL_AP_START_MASK            0x00000001u
#endif
}]
set hpath [file join $tmp fixture.h]
write_file $hpath $header_fixture
set regs [rtfpga::registers_from_header $hpath]
set summary {}
foreach r $regs {
    lappend summary [list [dict get $r name] [dict get $r offset] [dict get $r width] [dict get $r access]]
}
check_equal "registers_from_header" $summary \
    {{AP_CTRL 0 32 read-write} {ISR 12 32 read-write} {ORIG_X 16 32 read-write} {RESULT 80 1 read-only} {T 84 32 read-only}}
check_equal "register description keeps inner parentheses" \
    [dict get [lindex $regs 0] description] "block-level control (ap_ctrl_hs)"
write_file $hpath [string map {"// 0x54 : T" "// 0x58 : T"} $header_fixture]
check_error "registers_from_header: comment and macro disagree" "*register T is at 0x54 but its comment says 0x58" {
    rtfpga::registers_from_header $hpath
}
write_file $hpath [string map {"(Read)\n// 0x54" "(Sometimes)\n// 0x54"} $header_fixture]
check_error "registers_from_header: unknown access" "*:6: unknown access 'Sometimes'*" {
    rtfpga::registers_from_header $hpath
}
write_file $hpath [string map {"// 0x10 : ORIG_X" "// 0x10 : ORIGX"} $header_fixture]
check_error "registers_from_header: register without comment" "*register ORIG_X has no*" {
    rtfpga::registers_from_header $hpath
}
write_file $hpath [string map {"0x54" "0x50"} $header_fixture]
check_error "registers_from_header: two registers at one offset" "*registers RESULT and T are both at 0x50" {
    rtfpga::registers_from_header $hpath
}
write_file $hpath "// nothing\n"
check_error "registers_from_header: no macro" "*no '#define XRTFPGA_CONTROL_ADDR_*" {
    rtfpga::registers_from_header $hpath
}
write_file $hpath $header_fixture

# ---------------------------------------------------------------------------------------
# docs/architecture.md ("The bus") against the port list and, if given, the real header.

set fd [open $arch_doc r]
fconfigure $fd -encoding utf-8
set arch [read $fd]
close $fd

if {![regexp {Ports use the Vitis names:(.*?)\n\n} $arch -> port_text]} {
    check "architecture.md has the 'Ports use the Vitis names:' paragraph" 0
    set port_text ""
}
set arch_ports {}
foreach {- span} [regexp -all -inline {`([^`]+)`} $port_text] {
    set span [regsub -all {\s} $span ""]
    if {[regexp {^(\w*)\{([\w,]+)\}$} $span -> prefix alternatives]} {
        foreach a [split $alternatives ,] {
            lappend arch_ports $prefix$a
        }
    } elseif {[regexp {^\w+$} $span]} {
        lappend arch_ports $span
    }
}
check_equal "port names of architecture.md = rtfpga_common.tcl" \
    [lsort $arch_ports] [lsort [dict keys [rtfpga::required_port_directions]]]

# Directions by the AXI rule, independently of the table: the master drives VALID and the
# payload of AW, W and AR and READY of B and R; the slave drives the rest.
dict for {port dir} [rtfpga::required_port_directions] {
    if {![regexp {^s_axi_control_(aw|ar|w|b|r)(\w+)$} $port -> channel signal]} {
        continue
    }
    set master_payload [expr {$channel in {aw w ar}}]
    set is_ready [expr {$signal eq "ready"}]
    check_equal "AXI4-Lite slave direction of $port" $dir [expr {$master_payload != $is_ready ? "in" : "out"}]
}

# Every port-like name the scripts and XDC files spell out is a port of the architecture
# or of the optional AXI4-Stream front end (the LED port is checked by the XDC run below).
set known [concat [dict keys [rtfpga::required_port_directions]] [dict keys [rtfpga::axis_port_directions]]]
foreach f [glob -directory $constraints_dir *.tcl *.xdc] {
    set fd [open $f r]
    set text [read $fd]
    close $fd
    foreach name [lsort -unique [regexp -all -inline {\m(?:s_axi_control_\w+|[sm]_axis_\w+|ap_rst\w*|ap_clk\w*)} $text]] {
        check "[file tail $f] names a known port: $name" [expr {$name in $known}]
    }
}

set arch_offsets {}
foreach line [split $arch "\n"] {
    if {![regexp {^\| 0x} $line]} {
        continue
    }
    foreach item [regexp -all -inline {0x[0-9A-Fa-f]+(?:\u2013|-)0x[0-9A-Fa-f]+|0x[0-9A-Fa-f]+} $line] {
        if {[regexp {^(0x[0-9A-Fa-f]+)(?:\u2013|-)(0x[0-9A-Fa-f]+)$} $item -> lo hi]} {
            for {set o $lo} {$o <= $hi} {incr o 4} {
                lappend arch_offsets [expr {$o}]
            }
        } else {
            lappend arch_offsets [expr {$item}]
        }
    }
}
check_equal "architecture.md register table has 26 registers" [llength [lsort -unique $arch_offsets]] 26
if {$real_header ne ""} {
    set offsets {}
    if {[catch {rtfpga::registers_from_header $real_header} real_regs]} {
        check "the generated header can be read" 0 $real_regs
        set real_regs {}
    }
    foreach r $real_regs {
        lappend offsets [dict get $r offset]
    }
    check_equal "generated header offsets = architecture.md" \
        [lsort -integer $offsets] [lsort -integer -unique $arch_offsets]
}

# ---------------------------------------------------------------------------------------
# Dry runs against the mock.

# The ports of the top as the architecture defines them: direction and width.
proc top_ports {{with_axis 0}} {
    set widths {s_axi_control_awaddr 7 s_axi_control_araddr 7 s_axi_control_wdata 32
        s_axi_control_rdata 32 s_axi_control_wstrb 4 s_axi_control_bresp 2 s_axi_control_rresp 2}
    set ports [dict create]
    dict for {name dir} [rtfpga::required_port_directions] {
        dict set ports $name [list $dir [expr {[dict exists $widths $name] ? [dict get $widths $name] : 1}]]
    }
    if {$with_axis} {
        dict for {name dir} [rtfpga::axis_port_directions] {
            dict set ports $name [list $dir [expr {[string match *tdata $name] ? 32 : 1}]]
        }
    }
    return $ports
}

# Sources `script` with `args` in a fresh interpreter holding the mock; `setup` runs there
# first. Returns the interpreter and the error message ("" on success).
proc dry_run {script args setup} {
    set i [interp create]
    $i eval [list source [file join $::test_dir vivado_mock.tcl]]
    $i eval $setup
    $i eval [list set ::argv $args]
    $i eval [list set ::argc [llength $args]]
    if {[catch {$i eval [list source [file join $::constraints_dir $script]]} message]} {
        return [list $i $message]
    }
    return [list $i ""]
}

proc calls {i cmd} {
    return [$i eval [list mock::calls $cmd]]
}

# Positional arguments of every call of `cmd`.
proc positional {i cmd} {
    set result {}
    foreach c [calls $i $cmd] {
        lappend result [lindex $c 2]
    }
    return $result
}

proc read_text {path} {
    if {![file exists $path]} {
        check "$path exists" 0
        return ""
    }
    set fd [open $path r]
    set text [read $fd]
    close $fd
    return $text
}

# ooc.xdc in an interpreter offering only XDC commands (and the XDC subset of Tcl).
proc xdc_run {xdc_text ports} {
    set host [interp create]
    $host eval [list source [file join $::test_dir vivado_mock.tcl]]
    $host eval [list set mock::ports $ports]
    set x [interp create]
    foreach cmd [$x eval {info commands}] {
        if {$cmd ni {set expr list}} {
            $x hide $cmd
        }
    }
    foreach cmd {create_clock get_clocks get_ports set_property set_clock_uncertainty
                 set_input_delay set_output_delay set_false_path} {
        interp alias $x $cmd $host ::mock::call $cmd
    }
    if {[catch {$x eval $xdc_text} message]} {
        return [list $host $message]
    }
    interp delete $x
    return [list $host ""]
}

set ooc_xdc [read_text [file join $constraints_dir ooc.xdc]]
foreach period {4.5 10} {
    lassign [xdc_run [rtfpga::xdc_with_period $ooc_xdc $period] [top_ports 1]] x err
    check_equal "ooc.xdc at $period ns evaluates with XDC commands only" $err ""
    set clock [lindex [calls $x create_clock] 0]
    check_equal "ooc.xdc clock period" [dict get [lindex $clock 1] -period] $period
    check_equal "ooc.xdc clock port" [lindex $clock 2] ap_clk
    check_equal "ooc.xdc HD.CLK_SRC" [lindex [positional $x set_property] 0] {HD.CLK_SRC BUFGCTRL_X0Y0 ap_clk}
    set inputs {}
    set outputs {}
    dict for {name info} [top_ports 1] {
        if {$name eq "ap_clk"} continue
        lappend [expr {[lindex $info 0] eq "in" ? "inputs" : "outputs"}] $name
    }
    set in_call [lindex [calls $x set_input_delay] 0]
    set out_call [lindex [calls $x set_output_delay] 0]
    check_equal "ooc.xdc input delay on every input but the clock" [lsort [lindex $in_call 2 1]] [lsort $inputs]
    check_equal "ooc.xdc output delay on every output" [lsort [lindex $out_call 2 1]] [lsort $outputs]
    check_equal "ooc.xdc input delay is 30 % of the period" [lindex $in_call 2 0] [expr {0.3 * $period}]
    check_equal "ooc.xdc delays are relative to ap_clk" \
        [dict get [lindex $in_call 1] -clock][dict get [lindex $out_call 1] -clock] ap_clkap_clk
    interp delete $x
}

lassign [xdc_run [read_text [file join $constraints_dir zedboard.xdc]] \
    [dict create $rtfpga::led_port {out 1}]] x err
check_equal "zedboard.xdc evaluates with XDC commands only" $err ""
check_equal "zedboard.xdc puts the LED on LD0 (T22, LVCMOS33)" [positional $x set_property] \
    [list [list PACKAGE_PIN T22 $rtfpga::led_port] [list IOSTANDARD LVCMOS33 $rtfpga::led_port]]
interp delete $x

# synth_ooc.tcl
set out [file join $tmp ooc]
lassign [dry_run synth_ooc.tcl [list -verilog $vdir -out $out -period 5] {set mock::slack 0.25}] i err
check_equal "synth_ooc.tcl dry run" $err ""
check_equal "synth_ooc reads every Verilog file" [positional $i read_verilog] \
    [list [list [list [file join $vdir body.v] [file join $vdir rtfpga_top.v]]]]
set synth [lindex [calls $i synth_design] 0]
check_equal "synth_ooc synthesises out of context for the ZedBoard part" [lindex $synth 1] \
    {-top rtfpga_top -part xc7z020clg484-1 -mode out_of_context -directive Default}
check "synth_ooc reads the XDC before synthesis" \
    [expr {[$i eval {mock::index_of read_xdc}] < [$i eval {mock::index_of synth_design}]}]
check_equal "synth_ooc reads its OOC XDC copy" [lindex [calls $i read_xdc] 0] \
    [list read_xdc {-mode out_of_context} [list [file join $out ooc.xdc]]]
check "synth_ooc's XDC has the requested period" \
    [string match "*\nset ooc_period_ns 5\n*" [read_text [file join $out ooc.xdc]]]
foreach step {opt_design place_design route_design} {
    check "synth_ooc runs $step after synthesis" \
        [expr {[$i eval [list mock::index_of $step]] > [$i eval {mock::index_of synth_design}]}]
}
set summary [read_text [file join $out summary.txt]]
check "synth_ooc summary: period, WNS and Fmax" \
    [string match "*period_ns=5\nwns_ns=0.25\nfmax_mhz=210.5\n*" $summary] $summary
check "synth_ooc summary: cell counts" [string match "*\nDSP48E1=3\n*" $summary] $summary
interp delete $i
lassign [dry_run synth_ooc.tcl [list -verilog $vdir] {}] i err
check "synth_ooc without -out fails" [string match "option -out is required*" $err] $err
interp delete $i
lassign [dry_run synth_ooc.tcl [list -verilog $vdir -out $out -period fast] {}] i err
check "synth_ooc with a bad period fails" [string match "-period must be a positive number*" $err] $err
interp delete $i

# package_ip.tcl
proc package_run {with_axis ports_setup} {
    file copy -force $::hpath [file join $::vdir $rtfpga::header_file]
    return [dry_run package_ip.tcl [list -verilog $::vdir -repo [file join $::tmp repo] -work [file join $::tmp work]] \
        "set mock::ports [list [top_ports $with_axis]]; $ports_setup"]
}
lassign [package_run 0 {}] i err
check_equal "package_ip.tcl dry run" $err ""
check_equal "package_ip interfaces" [positional $i ipx::add_bus_interface] \
    {{s_axi_control core:0} {ap_clk core:0} {ap_rst_n core:0} {interrupt core:0}}
set axil_maps {}
foreach p [positional $i ipx::add_port_map] {
    if {[lindex $p 1] eq "busif:s_axi_control"} {
        lappend axil_maps [lindex $p 0]
    }
}
check_equal "package_ip maps the 17 AXI4-Lite signals" [lsort $axil_maps] [lsort [dict keys [rtfpga::axil_port_map]]]
set props [positional $i set_property]
foreach expected {
    {value ACTIVE_LOW busparam:busif:ap_rst_n:POLARITY}
    {value LEVEL_HIGH busparam:busif:interrupt:SENSITIVITY}
    {value AXI4LITE busparam:busif:s_axi_control:PROTOCOL}
    {interface_mode slave busif:s_axi_control}
    {interface_mode master busif:interrupt}
    {abstraction_type_vlnv xilinx.com:interface:aximm_rtl:1.0 busif:s_axi_control}
    {physical_name s_axi_control_awaddr portmap:busif:s_axi_control:AWADDR}
    {range 128 block:Reg}
    {name rtfpga_top core:0}
    {version 1.0 core:0}
} {
    check "package_ip sets $expected" [expr {$expected in $props}]
}
check_equal "package_ip associates clock and reset" [lmap c [calls $i ipx::associate_bus_interfaces] {lindex $c 1}] \
    {{-busif s_axi_control -clock ap_clk} {-clock ap_clk -reset ap_rst_n}}
check_equal "package_ip adds the header's registers" [lmap p [positional $i ipx::add_register] {lindex $p 0}] \
    {AP_CTRL ISR ORIG_X RESULT T}
check "package_ip register offset" [expr {{address_offset 0x54 reg:T} in $props}]
check_equal "package_ip saves the core" [llength [calls $i ipx::save_core]] 1
interp delete $i

lassign [package_run 1 {}] i err
check_equal "package_ip.tcl dry run with AXI4-Stream" $err ""
check_equal "package_ip stream interfaces" [lrange [positional $i ipx::add_bus_interface] 4 end] \
    {{s_axis core:0} {m_axis core:0}}
check "package_ip m_axis is a master" [expr {{interface_mode master busif:m_axis} in [positional $i set_property]}]
check_equal "package_ip clocks the streams by ap_clk" [lmap c [lrange [calls $i ipx::associate_bus_interfaces] 0 2] {lindex $c 1}] \
    {{-busif s_axi_control -clock ap_clk} {-busif s_axis -clock ap_clk} {-busif m_axis -clock ap_clk}}
interp delete $i

lassign [package_run 0 {dict unset mock::ports interrupt}] i err
check "package_ip without an interrupt port fails" [string match "rtfpga_top has no port 'interrupt'*" $err] $err
interp delete $i
lassign [package_run 0 {dict set mock::ports interrupt {in 1}}] i err
check "package_ip with an input interrupt fails" [string match "*port 'interrupt' must be*'out'*" $err] $err
interp delete $i
lassign [package_run 1 {dict unset mock::ports m_axis_tlast}] i err
check "package_ip with half a stream fails" [string match "rtfpga_top has only some of the m_axis_* ports*" $err] $err
interp delete $i

# zedboard_bd.tcl
set repo [file join $tmp repo]
set ip_vlnv "$rtfpga::ip_vendor:$rtfpga::ip_library:$rtfpga::top:$rtfpga::ip_version"
set wrapper [file join $tmp rtfpga_system_wrapper.v]
write_file $wrapper "// wrapper\n"
proc bd_run {args_extra setup} {
    set out [file join $::tmp bd]
    file delete -force $out
    return [dry_run zedboard_bd.tcl [concat [list -ip_repo $::repo -out $out] $args_extra] \
        "lappend mock::ipdefs [list $::ip_vlnv]; set mock::wrapper_path [list $::wrapper]; $setup"]
}

lassign [bd_run {} {}] i err
check_equal "zedboard_bd.tcl dry run (1 instance)" $err ""
set out [file join $tmp bd]
set props [positional $i set_property]
check "zedboard_bd sets the ZedBoard board part" \
    [expr {{board_part avnet.com:zedboard:part0:1.4 obj:current_project:} in $props}]
set ps_dict [lindex [lsearch -inline -index 0 [lmap c [calls $i set_property] {list [dict exists [lindex $c 1] -dict] [lindex $c 1]}] 1] 1]
set ps_config [dict get $ps_dict -dict]
check_equal "zedboard_bd FCLK_CLK0 100 MHz" [dict get $ps_config CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ] 100
check_equal "zedboard_bd FCLK from the IO PLL" [dict get $ps_config CONFIG.PCW_FCLK0_PERIPHERAL_CLKSRC] "IO PLL"
check_equal "zedboard_bd fabric interrupts" \
    [dict get $ps_config CONFIG.PCW_USE_FABRIC_INTERRUPT][dict get $ps_config CONFIG.PCW_IRQ_F2P_INTR] 11
set autos [lmap c [calls $i apply_bd_automation] {dict get [lindex $c 1] -rule}]
check_equal "zedboard_bd automations" $autos {xilinx.com:bd_rule:processing_system7 xilinx.com:bd_rule:axi4}
check "zedboard_bd PS automation applies the board preset" \
    [string match {*apply_board_preset "1"*} [dict get [lindex [calls $i apply_bd_automation] 0 1] -config]]
set axi_config [dict get [lindex [calls $i apply_bd_automation] 1 1] -config]
check_equal "zedboard_bd connects GP0 to the slave" \
    [list [dict get $axi_config Master] [dict get $axi_config Slave]] {/ps7/M_AXI_GP0 /rtfpga_0/s_axi_control}
check_equal "zedboard_bd instances" [lmap p [positional $i create_bd_cell] {lindex $p 0}] {ps7 rtfpga_0}
check_equal "zedboard_bd interrupt to IRQ_F2P and LD0" [positional $i connect_bd_net] \
    {{/rtfpga_0/interrupt /ps7/IRQ_F2P /led_irq}}
check "zedboard_bd adds zedboard.xdc with the LED" \
    [expr {[list [file join $constraints_dir zedboard.xdc]] in [positional $i add_files]}]
check "zedboard_bd adds the wrapper" [expr {[list $wrapper] in [positional $i add_files]}]
check_equal "zedboard_bd exports the .xsa with the bitstream" [lindex [calls $i write_hw_platform] 0 1] \
    [list -fixed 1 -include_bit 1 -force 1 -file [file join $out rtfpga_system.xsa]]
check "zedboard_bd copies the bitstream" [file exists [file join $out rtfpga_system.bit]]
check_equal "zedboard_bd addresses.txt" [read_text [file join $out addresses.txt]] \
    "# instance base_address range irq_f2p_line gic_interrupt_id\nrtfpga_0 0x43C00000 64K 0 61\n"
interp delete $i

lassign [bd_run {-instances 10 -fclk_mhz 214 -fclk_src ddr -leds 0 -interconnect smartconnect} \
    {set mock::fclk_actual 213.333328}] i err
check_equal "zedboard_bd.tcl dry run (10 instances, 214 MHz)" $err ""
set ps_config [dict get [lindex [lsearch -inline -index 0 [lmap c [calls $i set_property] {list [dict exists [lindex $c 1] -dict] [lindex $c 1]}] 1] 1] -dict]
check_equal "zedboard_bd FCLK 214 MHz from the DDR PLL" \
    [list [dict get $ps_config CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ] [dict get $ps_config CONFIG.PCW_FCLK0_PERIPHERAL_CLKSRC]] \
    {214 {DDR PLL}}
set axi_calls [lrange [calls $i apply_bd_automation] 1 end]
check_equal "zedboard_bd one AXI automation per instance" [llength $axi_calls] 10
check_equal "zedboard_bd first instance gets a SmartConnect, the others join it" \
    [lmap c $axi_calls {dict get [dict get [lindex $c 1] -config] intc_ip}] \
    [concat [list {New AXI SmartConnect}] [lrepeat 9 Auto]]
check "zedboard_bd concatenates 10 interrupts" [expr {{CONFIG.NUM_PORTS 10 /irq_concat} in [positional $i set_property]}]
set nets [positional $i connect_bd_net]
check "zedboard_bd instance 9 drives In9" [expr {{/rtfpga_9/interrupt /irq_concat/In9} in $nets}]
check "zedboard_bd concat drives IRQ_F2P" [expr {{/irq_concat/dout /ps7/IRQ_F2P} in $nets}]
check "zedboard_bd without LEDs has no LED port" [expr {[llength [calls $i create_bd_port]] == 0}]
set lines [split [string trim [read_text [file join $out addresses.txt]]] "\n"]
check_equal "zedboard_bd addresses of 10 instances" [llength $lines] 11
check_equal {zedboard_bd instance 9 on IRQ_F2P[9] = GIC 85} [lindex $lines end] "rtfpga_9 0x43C90000 64K 9 85"
check "zedboard_bd summary has the achieved FCLK" \
    [string match "*fclk_actual_mhz=213.333328*" [read_text [file join $out summary.txt]]]
interp delete $i

lassign [bd_run {-build project} {}] i err
check_equal "zedboard_bd.tcl -build project" $err ""
check_equal "zedboard_bd -build project launches no run" [llength [calls $i launch_runs]] 0
interp delete $i

lassign [bd_run {} {set mock::board_parts {}}] i err
check_equal "zedboard_bd without board files" $err ""
check "zedboard_bd falls back to the PS7's ZedBoard preset" \
    [expr {{CONFIG.preset ZedBoard /ps7} in [positional $i set_property]}]
check "zedboard_bd sets no board part" \
    [expr {[lsearch -index 0 [positional $i set_property] board_part] < 0}]
interp delete $i

lassign [bd_run {} {set mock::board_parts {em.avnet.com:zed:part0:1.3}}] i err
check "zedboard_bd takes an older ZedBoard board part" \
    [expr {{board_part em.avnet.com:zed:part0:1.3 obj:current_project:} in [positional $i set_property]}] $err
interp delete $i

lassign [bd_run {-board_part vendor:other:part0:1.0} {}] i err
check "zedboard_bd with a missing requested board part fails" [string match "board part 'vendor:other:part0:1.0' is not installed*" $err] $err
interp delete $i
lassign [bd_run {-instances 17} {}] i err
check "zedboard_bd with 17 instances fails" [string match "-instances must be an integer from 1 to 16*" $err] $err
interp delete $i
lassign [bd_run {-fclk_mhz 300} {}] i err
check "zedboard_bd above 250 MHz fails" [string match "*above the 250 MHz*" $err] $err
interp delete $i
lassign [bd_run {} {set mock::ipdefs {xilinx.com:ip:processing_system7:5.5}}] i err
check "zedboard_bd without the packaged IP fails" [string match "IP $ip_vlnv is not in*package_ip.tcl*" $err] $err
interp delete $i
lassign [bd_run {} {set mock::slack -0.2}] i err
check "zedboard_bd fails on negative slack" [string match "timing not met*" $err] $err
check "zedboard_bd still exports the .xsa on negative slack" [expr {[llength [calls $i write_hw_platform]] == 1}]
interp delete $i
lassign [bd_run {-allow_negative_slack 1} {set mock::slack -0.2}] i err
check_equal "zedboard_bd accepts negative slack on request" $err ""
interp delete $i
lassign [bd_run {} {set mock::progress 50%}] i err
check "zedboard_bd reports a failed synthesis" [string match "synthesis failed*" $err] $err
interp delete $i

file delete -force $tmp
puts "constraints: $checks checks, $failures failed"
exit [expr {$failures > 0}]
