# ZedBoard system: the Zynq PS7 (board preset, DDR and MIO) drives one or more
# accelerators over M_AXI_GP0 and an AXI interconnect/SmartConnect; each accelerator's
# interrupt goes to IRQ_F2P; FCLK_CLK0 clocks the fabric. Builds the bitstream and exports
# the hardware platform (.xsa) for a bare-metal application (Vitis).
#
#   vivado -mode batch -source constraints/zedboard_bd.tcl -tclargs \
#       -ip_repo IP_REPO -out OUT [-instances 1] [-fclk_mhz 100] [-fclk_src io|arm|ddr] ...
#
# IP_REPO is what package_ip.tcl wrote. -instances is the number of accelerator IPs on the
# bus (the thesis tried 1, 2, 4 and 8); it is not the `--lanes` of `rtfpga verilog`, which
# replicates the datapath inside one IP. -fclk_mhz 100 is the thesis' baseline fabric clock,
# 214 its best run (the PS derives FCLK from a PLL by integer division: the frequency it
# actually achieves is printed and written to OUT/summary.txt).
#
# OUT receives the project (OUT/project), the reports, <design>.bit, <design>.xsa,
# addresses.txt (base address and IRQ_F2P line of each instance) and summary.txt.

set script_dir [file dirname [file normalize [info script]]]
source [file join $script_dir rtfpga_common.tcl]

set usage "usage: vivado -mode batch -source zedboard_bd.tcl -tclargs -ip_repo DIR -out DIR\
 \[-instances N\] \[-fclk_mhz MHZ\] \[-fclk_src io|arm|ddr\] \[-board_part auto|none|VLNV\]\
 \[-interconnect auto|axi_interconnect|smartconnect\] \[-leds 0|1\] \[-build project|bitstream\]\
 \[-jobs N\] \[-allow_negative_slack 0|1\] \[-design NAME\] \[-top NAME\] \[-vendor V\] \[-library L\]\
 \[-version X.Y\] \[-part PART\]"
set opts [rtfpga::parse_args $argv [dict create \
    ip_repo {} \
    out {} \
    instances 1 \
    fclk_mhz 100 \
    fclk_src io \
    board_part auto \
    interconnect auto \
    leds 1 \
    build bitstream \
    jobs 2 \
    allow_negative_slack 0 \
    design rtfpga_system \
    top $rtfpga::top \
    vendor $rtfpga::ip_vendor \
    library $rtfpga::ip_library \
    version $rtfpga::ip_version \
    part $rtfpga::part] $usage]

# The PS7 has 16 fabric interrupt lines (IRQ_F2P[15:0]).
set instances [rtfpga::int_in_range "-instances" [dict get $opts instances] 1 16]
set fclk_mhz [rtfpga::positive_number "-fclk_mhz" [dict get $opts fclk_mhz]]
if {$fclk_mhz > 250} {
    error "-fclk_mhz $fclk_mhz is above the 250 MHz the PS7 can give the fabric"
}
set fclk_src [dict get {io {IO PLL} arm {ARM PLL} ddr {DDR PLL}} \
    [rtfpga::choice "-fclk_src" [dict get $opts fclk_src] {io arm ddr}]]
set intc_ip [dict get {auto Auto axi_interconnect {New AXI Interconnect} smartconnect {New AXI SmartConnect}} \
    [rtfpga::choice "-interconnect" [dict get $opts interconnect] {auto axi_interconnect smartconnect}]]
set leds [rtfpga::int_in_range "-leds" [dict get $opts leds] 0 1]
set build [rtfpga::choice "-build" [dict get $opts build] {project bitstream}]
set jobs [rtfpga::int_in_range "-jobs" [dict get $opts jobs] 1 64]
set allow_negative_slack [rtfpga::int_in_range "-allow_negative_slack" [dict get $opts allow_negative_slack] 0 1]
set design [dict get $opts design]
set out [file normalize [dict get $opts out]]
set ip_repo [file normalize [dict get $opts ip_repo]]
set ip_vlnv [join [list [dict get $opts vendor] [dict get $opts library] [dict get $opts top] [dict get $opts version]] :]
file mkdir $out

# The newest version in the IP catalog of the first of `names` that exists.
proc latest_ipdef {names} {
    foreach name $names {
        set vlnvs {}
        foreach def [get_ipdefs -quiet -filter "NAME == $name"] {
            lappend vlnvs [get_property VLNV $def]
        }
        if {[llength $vlnvs] > 0} {
            return [lindex [lsort -dictionary $vlnvs] end]
        }
    }
    error "none of the IPs '[join $names {, }]' is in the IP catalog"
}

# The ZedBoard board part to use, or "" to go without board files.
proc board_part {requested} {
    if {$requested eq "none"} {
        return ""
    }
    if {$requested ne "auto"} {
        if {[llength [get_board_parts -quiet $requested]] == 0} {
            error "board part '$requested' is not installed (see get_board_parts; the Avnet files are in the Xilinx board store)"
        }
        return $requested
    }
    foreach candidate $rtfpga::board_parts {
        if {[llength [get_board_parts -quiet $candidate]] > 0} {
            return $candidate
        }
    }
    set any [lsort -dictionary [get_board_parts -quiet *:zed*:part0:*]]
    return [lindex $any end]
}

create_project -force rtfpga_zedboard [file join $out project] -part [dict get $opts part]
set bp [board_part [dict get $opts board_part]]
if {$bp ne ""} {
    set_property board_part $bp [current_project]
    puts "zedboard_bd: board part $bp"
} else {
    puts "WARNING: no ZedBoard board part installed; configuring the PS7 from its built-in ZedBoard preset"
}
set_property ip_repo_paths [list $ip_repo] [current_project]
update_ip_catalog
if {[llength [get_ipdefs -quiet -filter "VLNV == $ip_vlnv"]] == 0} {
    error "IP $ip_vlnv is not in '$ip_repo' (run package_ip.tcl -repo $ip_repo first)"
}

create_bd_design $design

# Processing system: DDR and MIO from the board preset, then the fabric clock, the GP0
# master and the fabric interrupts.
set ps [create_bd_cell -type ip -vlnv [latest_ipdef processing_system7] ps7]
if {$bp ne ""} {
    apply_bd_automation -rule xilinx.com:bd_rule:processing_system7 \
        -config {make_external "FIXED_IO, DDR" apply_board_preset "1" Master "Disable" Slave "Disable"} $ps
} else {
    set_property CONFIG.preset ZedBoard $ps
    apply_bd_automation -rule xilinx.com:bd_rule:processing_system7 \
        -config {make_external "FIXED_IO, DDR" apply_board_preset "0" Master "Disable" Slave "Disable"} $ps
}
set_property -dict [list \
    CONFIG.PCW_USE_M_AXI_GP0 1 \
    CONFIG.PCW_EN_CLK0_PORT 1 \
    CONFIG.PCW_FCLK0_PERIPHERAL_CLKSRC $fclk_src \
    CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ $fclk_mhz \
    CONFIG.PCW_USE_FABRIC_INTERRUPT 1 \
    CONFIG.PCW_IRQ_F2P_INTR 1] $ps

# The accelerators. The AXI automation puts an interconnect (or SmartConnect) behind GP0,
# a proc_sys_reset on FCLK_RESET0_N, and clocks everything from FCLK_CLK0; later instances
# join the interconnect the first one created.
set interrupts {}
for {set i 0} {$i < $instances} {incr i} {
    set name rtfpga_$i
    create_bd_cell -type ip -vlnv $ip_vlnv $name
    apply_bd_automation -rule xilinx.com:bd_rule:axi4 -config [list \
        Clk_master Auto Clk_slave Auto Clk_xbar Auto \
        Master /ps7/M_AXI_GP0 Slave /$name/$rtfpga::axil_name \
        intc_ip [expr {$i == 0 ? $intc_ip : "Auto"}] master_apm 0] \
        [get_bd_intf_pins $name/$rtfpga::axil_name]
    lappend interrupts [get_bd_pins $name/$rtfpga::interrupt_port]
}

# Interrupts: IRQ_F2P[i] is instance i (GIC IDs 61..68 for lines 0..7, 84..91 for 8..15).
set first_loads {}
if {$instances == 1} {
    lappend first_loads [get_bd_pins ps7/IRQ_F2P]
} else {
    set concat [create_bd_cell -type ip -vlnv [latest_ipdef {xlconcat ilconcat}] irq_concat]
    set_property CONFIG.NUM_PORTS $instances $concat
    connect_bd_net [get_bd_pins irq_concat/dout] [get_bd_pins ps7/IRQ_F2P]
    lappend first_loads [get_bd_pins irq_concat/In0]
    for {set i 1} {$i < $instances} {incr i} {
        connect_bd_net [lindex $interrupts $i] [get_bd_pins irq_concat/In$i]
    }
}
if {$leds} {
    lappend first_loads [create_bd_port -dir O $rtfpga::led_port]
    add_files -fileset constrs_1 -norecurse [file join $script_dir zedboard.xdc]
}
connect_bd_net [lindex $interrupts 0] {*}$first_loads

assign_bd_address
validate_bd_design
save_bd_design

set fclk_actual [get_property CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ $ps]
puts "zedboard_bd: FCLK_CLK0 requested $fclk_mhz MHz from $fclk_src, achieved $fclk_actual MHz"

# Base address and interrupt line of each instance, for the bare-metal program.
set fd [open [file join $out addresses.txt] w]
puts $fd "# instance base_address range irq_f2p_line gic_interrupt_id"
for {set i 0} {$i < $instances} {incr i} {
    set seg [get_bd_addr_segs -of_objects [get_bd_addr_spaces ps7/Data] -filter "NAME =~ *rtfpga_${i}_*"]
    if {[llength $seg] != 1} {
        error "expected one address segment of rtfpga_$i in ps7/Data, found [llength $seg]"
    }
    set gic [expr {$i < 8 ? 61 + $i : 84 + $i - 8}]
    puts $fd "rtfpga_$i [get_property OFFSET $seg] [get_property RANGE $seg] $i $gic"
}
close $fd

set wrapper [make_wrapper -files [get_files $design.bd] -top]
if {![file exists $wrapper]} {
    # Older releases return nothing; the wrapper lies under .srcs or .gen.
    set wrapper [lindex [glob -nocomplain [file join $out project *.{gen,srcs} sources_1 bd $design hdl ${design}_wrapper.v]] 0]
}
add_files -norecurse $wrapper
set_property top ${design}_wrapper [current_fileset]
update_compile_order -fileset sources_1

if {$build eq "project"} {
    close_project
    puts "zedboard_bd: project in [file join $out project]"
    return
}

launch_runs synth_1 -jobs $jobs
wait_on_run synth_1
if {[get_property PROGRESS [get_runs synth_1]] ne "100%"} {
    error "synthesis failed: [get_property STATUS [get_runs synth_1]]"
}
launch_runs impl_1 -to_step write_bitstream -jobs $jobs
wait_on_run impl_1
if {[get_property PROGRESS [get_runs impl_1]] ne "100%"} {
    error "implementation failed: [get_property STATUS [get_runs impl_1]]"
}

open_run impl_1
report_timing_summary -max_paths 10 -file [file join $out timing_summary.rpt]
report_utilization -file [file join $out utilization.rpt]
report_power -file [file join $out power.rpt]
set bit [lindex [glob -nocomplain [file join $out project *.runs impl_1 *.bit]] 0]
file copy -force $bit [file join $out $design.bit]
write_hw_platform -fixed -include_bit -force -file [file join $out $design.xsa]

set wns [get_property SLACK [get_timing_paths -setup -max_paths 1 -nworst 1]]
set fd [open [file join $out summary.txt] w]
puts $fd "instances=$instances"
puts $fd "fclk_requested_mhz=$fclk_mhz"
puts $fd "fclk_actual_mhz=$fclk_actual"
puts $fd "wns_ns=$wns"
dict for {name filter} $rtfpga::cell_count_filters {
    puts $fd "$name=[llength [get_cells -hierarchical -filter $filter]]"
}
close $fd
close_project
puts "zedboard_bd: $design.bit and $design.xsa in $out (WNS $wns ns)"
if {$wns < 0 && !$allow_negative_slack} {
    error "timing not met at $fclk_actual MHz (WNS $wns ns): lower -fclk_mhz, or pass -allow_negative_slack 1 to accept it as the thesis' overclocked runs did"
}
