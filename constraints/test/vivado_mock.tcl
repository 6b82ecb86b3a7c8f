# A stand-in for the Vivado commands the scripts of constraints/ use, so they can be dry-run
# under a plain tclsh (there is no Vivado on the build machines).
#
# Each command is declared with the options it accepts (from the UG835 command reference,
# `NAME=` for an option taking a value); a call with an option not declared, or to a command
# not declared at all, is an error. Calls are logged as {command options positional} for
# the tests to inspect; a few commands answer from the state in `mock::*` (ports of the
# packaged top, installed board parts, IP catalog, timing).

namespace eval mock {
    variable spec [dict create]
    variable handlers [dict create]
    variable log {}
    variable messages {}
    # State a test configures before sourcing a script.
    variable ports [dict create]            ;# port -> {direction width}
    variable board_parts {avnet.com:zedboard:part0:1.4}
    variable ipdefs {xilinx.com:ip:processing_system7:5.5 xilinx.com:ip:xlconcat:2.1}
    variable slack 0.25
    variable progress 100%
    variable fclk_actual 100.000000
    variable wrapper_path ""
    variable project_dir ""
    variable bd_cells {}
}
namespace eval ::ipx {}

proc mock::define {cmd options} {
    variable spec
    dict set spec $cmd [concat $options -quiet -verbose]
    interp alias {} ::$cmd {} ::mock::call $cmd
}

proc mock::handle {cmd params body} {
    variable handlers
    dict set handlers $cmd [list $params $body ::mock]
}

proc mock::call {cmd args} {
    variable spec
    variable handlers
    variable log
    set allowed [dict get $spec $cmd]
    set opts [dict create]
    set pos {}
    for {set k 0} {$k < [llength $args]} {incr k} {
        set a [lindex $args $k]
        if {[string match -* $a] && ![string is double -strict $a]} {
            if {"$a=" in $allowed} {
                incr k
                if {$k >= [llength $args]} {
                    error "$cmd: option $a needs a value"
                }
                dict set opts $a [lindex $args $k]
            } elseif {$a in $allowed} {
                dict set opts $a 1
            } else {
                error "$cmd: unknown option $a"
            }
        } else {
            lappend pos $a
        }
    }
    lappend log [list $cmd $opts $pos]
    if {[dict exists $handlers $cmd]} {
        return [apply [dict get $handlers $cmd] $opts $pos]
    }
    return "obj:$cmd:[join $pos ,]"
}

# Log queries for the tests.
proc mock::calls {cmd} {
    variable log
    set found {}
    foreach entry $log {
        if {[lindex $entry 0] eq $cmd} {
            lappend found $entry
        }
    }
    return $found
}

proc mock::index_of {cmd} {
    variable log
    set i 0
    foreach entry $log {
        if {[lindex $entry 0] eq $cmd} {
            return $i
        }
        incr i
    }
    return -1
}

# Script messages to stdout are collected instead of printed.
rename ::puts ::mock::real_puts
proc ::puts {args} {
    if {[llength $args] == 1} {
        lappend ::mock::messages [lindex $args 0]
        return
    }
    ::mock::real_puts {*}$args
}

# --- project, sources, runs (UG835) ---------------------------------------------------
mock::define create_project {-part= -force -in_memory -ip}
mock::handle create_project {opts pos} {
    variable project_dir [lindex $pos 1]
    return [lindex $pos 0]
}
mock::define current_project {}
mock::define current_fileset {-constrset -simset}
mock::define add_files {-fileset= -norecurse -scan_for_includes}
mock::define get_files {-of_objects= -filter= -all}
mock::define update_compile_order {-fileset=}
mock::define set_property {-dict=}
mock::define get_property {-min -max}
mock::define close_project {-delete}
mock::define get_board_parts {-filter= -latest_file_version}
mock::handle get_board_parts {opts pos} {
    variable board_parts
    set found {}
    foreach bp $board_parts {
        if {[string match [lindex $pos 0] $bp]} {
            lappend found $bp
        }
    }
    return $found
}
mock::define update_ip_catalog {-rebuild}
mock::define get_ipdefs {-filter= -all}
mock::handle get_ipdefs {opts pos} {
    variable ipdefs
    if {![regexp {^(NAME|VLNV) == (\S+)$} [dict get $opts -filter] -> key value]} {
        error "mock get_ipdefs: unsupported filter '[dict get $opts -filter]'"
    }
    set found {}
    foreach vlnv $ipdefs {
        set name [lindex [split $vlnv :] 2]
        if {($key eq "NAME" && $name eq $value) || ($key eq "VLNV" && $vlnv eq $value)} {
            lappend found ipdef:$vlnv
        }
    }
    return $found
}
mock::define launch_runs {-jobs= -to_step=}
mock::handle launch_runs {opts pos} {
    variable project_dir
    if {[lindex $pos 0] eq "impl_1"} {
        set dir [file join $project_dir mock.runs impl_1]
        file mkdir $dir
        close [open [file join $dir mock.bit] w]
    }
    return [lindex $pos 0]
}
mock::define wait_on_run {-timeout=}
mock::define get_runs {-filter=}
mock::define open_run {-name=}
mock::define write_hw_platform {-fixed -include_bit -force -file= -hw -minimal}

# --- non-project flow and reports ----------------------------------------------------------
mock::define read_verilog {-library= -sv}
mock::define read_xdc {-mode= -cells= -ref= -unmanaged -no_add}
mock::define synth_design {-top= -part= -mode= -directive= -flatten_hierarchy= -include_dirs= -generic= -verilog_define=}
mock::define opt_design {-directive=}
mock::define place_design {-directive=}
mock::define phys_opt_design {-directive=}
mock::define route_design {-directive=}
mock::define write_checkpoint {-force -cell=}
mock::define report_utilization {-file= -hierarchical -append -name=}
mock::define report_timing_summary {-file= -max_paths= -delay_type= -report_unconstrained -append}
mock::define report_methodology {-file= -append}
mock::define report_power {-file= -append}
mock::define get_timing_paths {-setup -hold -max_paths= -nworst= -delay_type=}
mock::define get_cells {-hierarchical -filter= -of_objects=}
mock::handle get_cells {opts pos} {
    return {cell_a cell_b cell_c}
}

# --- IP packager (ipx::) --------------------------------------------------------------------
mock::define ipx::package_project {-root_dir= -vendor= -library= -taxonomy= -import_files -set_current= -force -generated_files -module=}
mock::define ipx::current_core {}
mock::handle ipx::current_core {opts pos} {
    return core:0
}
mock::define ipx::remove_all_bus_interface {}
mock::define ipx::get_memory_maps {-of_objects= -filter=}
mock::handle ipx::get_memory_maps {opts pos} {
    return {}
}
mock::define ipx::remove_memory_map {}
mock::define ipx::add_bus_interface {}
mock::handle ipx::add_bus_interface {opts pos} {
    return busif:[lindex $pos 0]
}
mock::define ipx::add_port_map {}
mock::handle ipx::add_port_map {opts pos} {
    return portmap:[lindex $pos 1]:[lindex $pos 0]
}
mock::define ipx::get_bus_parameters {-of_objects= -filter=}
mock::handle ipx::get_bus_parameters {opts pos} {
    return {}
}
mock::define ipx::add_bus_parameter {}
mock::handle ipx::add_bus_parameter {opts pos} {
    return busparam:[lindex $pos 1]:[lindex $pos 0]
}
mock::define ipx::get_ports {-of_objects= -filter= -nocase -regexp}
mock::handle ipx::get_ports {opts pos} {
    variable ports
    set name [lindex $pos 0]
    if {[dict exists $ports $name]} {
        return port:$name
    }
    if {![dict exists $opts -quiet]} {
        error "mock ipx::get_ports: no port $name"
    }
    return {}
}
mock::define ipx::associate_bus_interfaces {-busif= -clock= -reset= -remove -clear}
mock::define ipx::add_memory_map {}
mock::handle ipx::add_memory_map {opts pos} {
    return mmap:[lindex $pos 0]
}
mock::define ipx::add_address_block {}
mock::handle ipx::add_address_block {opts pos} {
    return block:[lindex $pos 0]
}
mock::define ipx::add_register {}
mock::handle ipx::add_register {opts pos} {
    return reg:[lindex $pos 0]
}
mock::define ipx::create_xgui_files {}
mock::define ipx::update_checksums {}
mock::define ipx::check_integrity {-kernel -xrt}
mock::define ipx::save_core {}

# --- IP integrator (UG994) --------------------------------------------------------------------
mock::define create_bd_design {-dir=}
mock::define create_bd_cell {-type= -vlnv= -reference=}
mock::handle create_bd_cell {opts pos} {
    variable bd_cells
    lappend bd_cells [lindex $pos 0]
    return /[lindex $pos 0]
}
mock::define apply_bd_automation {-rule= -config= -dict= -opts=}
mock::define get_bd_cells {-of_objects= -filter=}
mock::define get_bd_pins {-of_objects= -filter=}
mock::handle get_bd_pins {opts pos} {
    return /[lindex $pos 0]
}
mock::define get_bd_intf_pins {-of_objects= -filter=}
mock::handle get_bd_intf_pins {opts pos} {
    return /[lindex $pos 0]
}
mock::define create_bd_port {-dir= -type= -from= -to= -freq_hz=}
mock::handle create_bd_port {opts pos} {
    return /[lindex $pos 0]
}
mock::define connect_bd_net {-net=}
mock::define assign_bd_address {-offset= -range= -target_address_space= -force}
mock::define validate_bd_design {-force}
mock::define save_bd_design {}
mock::define get_bd_addr_spaces {-of_objects= -filter=}
mock::define get_bd_addr_segs {-of_objects= -filter=}
mock::handle get_bd_addr_segs {opts pos} {
    variable bd_cells
    set found {}
    foreach cell $bd_cells {
        set seg SEG_${cell}_Reg
        if {[string match -nocase [lindex [dict get $opts -filter] end] $seg]} {
            lappend found seg:$seg
        }
    }
    return $found
}
mock::define make_wrapper {-files= -top -fileset= -import}
mock::handle make_wrapper {opts pos} {
    variable wrapper_path
    return $wrapper_path
}

# Properties the scripts read.
mock::handle get_property {opts pos} {
    variable ports
    lassign $pos name object
    switch -- $name {
        DIRECTION  { return [lindex [dict get $ports [string range $object 5 end]] 0] }
        SIZE_LEFT  { return [expr {[lindex [dict get $ports [string range $object 5 end]] 1] - 1}] }
        SIZE_RIGHT { return 0 }
        VLNV       { return [string range $object 6 end] }
        PROGRESS   { variable progress; return $progress }
        STATUS     { return "mock run status" }
        SLACK      { variable slack; return $slack }
        OFFSET     {
            regexp {rtfpga_(\d+)_} $object -> i
            return [format 0x%08X [expr {0x43C00000 + $i * 0x10000}]]
        }
        RANGE      { return 64K }
        CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ { variable fclk_actual; return $fclk_actual }
        default    { error "mock get_property: property $name is not modelled" }
    }
}

# --- XDC (UG903 "valid commands in an XDC file") ------------------------------------------
mock::define create_clock {-name= -period= -waveform= -add}
mock::define get_clocks {-of_objects= -filter= -include_generated_clocks}
mock::define set_clock_uncertainty {-setup -hold -from= -to=}
mock::define set_input_delay {-clock= -max -min -add_delay -clock_fall -reference_pin=}
mock::define set_output_delay {-clock= -max -min -add_delay -clock_fall -reference_pin=}
mock::define set_false_path {-from= -to= -through= -setup -hold}
mock::define get_ports {-filter= -regexp -nocase -of_objects=}
mock::handle get_ports {opts pos} {
    variable ports
    set found {}
    dict for {name info} $ports {
        if {[llength $pos] > 0 && ![string match [lindex $pos 0] $name]} {
            continue
        }
        if {[dict exists $opts -filter] && ![port_matches $name [lindex $info 0] [dict get $opts -filter]]} {
            continue
        }
        lappend found $name
    }
    if {[llength $found] == 0 && ![dict exists $opts -quiet]} {
        error "mock get_ports: no port matches '$pos' [dict get $opts]"
    }
    return $found
}

# Evaluates a `PROP op value && ...` filter on a port (DIRECTION is IN or OUT).
proc mock::port_matches {name direction filter} {
    set props [dict create NAME $name DIRECTION [string toupper $direction]]
    foreach term [split [string map {&& \x01} $filter] \x01] {
        if {![regexp {^\s*(\w+)\s*(==|!=|=~)\s*"?([^"\s]+)"?\s*$} $term -> prop op value]} {
            error "mock filter: cannot read '$term'"
        }
        set actual [dict get $props $prop]
        switch -- $op {
            == { set ok [expr {$actual eq $value}] }
            != { set ok [expr {$actual ne $value}] }
            =~ { set ok [string match $value $actual] }
        }
        if {!$ok} {
            return 0
        }
    }
    return 1
}
