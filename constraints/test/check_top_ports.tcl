# Compares the ports of the generated top (yosys `portlist` output) with the architecture:
# every required port with its direction, the AXI4-Lite widths, and each AXI4-Stream side
# either complete or absent. Usage: tclsh check_top_ports.tcl PORTLIST_FILE. Exits 1 on a
# mismatch, naming it.

set constraints_dir [file dirname [file dirname [file normalize [info script]]]]
source [file join $constraints_dir rtfpga_common.tcl]

set path [lindex $argv 0]
set fd [open $path r]
set ports [dict create]
set lineno 0
foreach line [split [read $fd] "\n"] {
    incr lineno
    if {[regexp {^(input|output|inout) \[(\d+):(\d+)\] (\S+)$} $line -> dir msb lsb name]} {
        dict set ports $name [list [string map {input in output out} $dir] [expr {$msb - $lsb + 1}]]
    } elseif {$line ne "" && ![string match "module *" $line]} {
        puts "$path:$lineno: unexpected portlist line '$line'"
        exit 1
    }
}
close $fd

set problems {}
dict for {name dir} [rtfpga::required_port_directions] {
    if {![dict exists $ports $name]} {
        lappend problems "missing port $name"
    } elseif {[lindex [dict get $ports $name] 0] ne $dir} {
        lappend problems "$name is [lindex [dict get $ports $name] 0], expected $dir"
    }
}
set widths {wdata 32 rdata 32 wstrb 4 bresp 2 rresp 2 awvalid 1 arvalid 1 interrupt 1}
dict for {signal width} $widths {
    set name [expr {$signal eq "interrupt" ? $signal : "${rtfpga::axil_name}_$signal"}]
    if {[dict exists $ports $name] && [lindex [dict get $ports $name] 1] != $width} {
        lappend problems "$name is [lindex [dict get $ports $name] 1] bits wide, expected $width"
    }
}
set aw [dict get [rtfpga::axil_port_map] AWADDR]
set ar [dict get [rtfpga::axil_port_map] ARADDR]
if {[dict exists $ports $aw] && [dict exists $ports $ar] &&
        [lindex [dict get $ports $aw] 1] != [lindex [dict get $ports $ar] 1]} {
    lappend problems "$aw and $ar differ in width"
}
set axis [rtfpga::axis_port_directions]
foreach side [list $rtfpga::axis_slave_name $rtfpga::axis_master_name] {
    set present [lsearch -all -inline [dict keys $ports] ${side}_*]
    if {[llength $present] == 0} {
        continue
    }
    foreach signal $rtfpga::axis_signals {
        set name ${side}_$signal
        if {![dict exists $ports $name]} {
            lappend problems "AXI4-Stream $side is incomplete: no $name"
        } elseif {[lindex [dict get $ports $name] 0] ne [dict get $axis $name]} {
            lappend problems "$name is [lindex [dict get $ports $name] 0], expected [dict get $axis $name]"
        }
    }
}
set expected [concat [dict keys [rtfpga::required_port_directions]] [dict keys $axis]]
foreach name [dict keys $ports] {
    if {$name ni $expected} {
        lappend problems "port $name is not in docs/architecture.md"
    }
}
if {[llength $problems] > 0} {
    puts "$rtfpga::top ports do not match the architecture:\n  [join $problems "\n  "]"
    exit 1
}
puts "$rtfpga::top ports match the architecture ([dict size $ports] ports)"
