# Out-of-context synthesis and implementation of the accelerator on the ZedBoard's part,
# in Vivado's non-project mode: resource use and timing of the block on its own.
#
#   vivado -mode batch -source constraints/synth_ooc.tcl -tclargs \
#       -verilog DIR -out OUT [-period 4.5] [-top rtfpga_top] [-part xc7z020clg484-1]
#
# DIR is what `rtfpga verilog --out DIR` wrote. OUT receives ooc.xdc with the period used,
# the post-route checkpoint, utilization/timing reports and summary.txt (key=value lines:
# period, WNS, the clock frequency the routed block supports, and cell counts named like
# the yosys report of `rtfpga synth`).

set script_dir [file dirname [file normalize [info script]]]
source [file join $script_dir rtfpga_common.tcl]

set usage "usage: vivado -mode batch -source synth_ooc.tcl -tclargs -verilog DIR -out OUT\
 \[-period NS\] \[-top NAME\] \[-part PART\] \[-directive Default|PerformanceOptimized|...\]"
set opts [rtfpga::parse_args $argv [dict create \
    verilog {} \
    out {} \
    period $rtfpga::ooc_period_ns \
    top $rtfpga::top \
    part $rtfpga::part \
    directive Default] $usage]
set out [file normalize [dict get $opts out]]
set top [dict get $opts top]
set period [rtfpga::positive_number "-period" [dict get $opts period]]
set sources [rtfpga::verilog_sources [file normalize [dict get $opts verilog]] $top]
file mkdir $out

# The constraints with the requested period, kept next to the reports they produced.
set fd [open [file join $script_dir ooc.xdc] r]
set xdc_text [read $fd]
close $fd
set xdc [file join $out ooc.xdc]
set fd [open $xdc w]
puts -nonewline $fd [rtfpga::xdc_with_period $xdc_text $period]
close $fd

# Constraints are read before synthesis so that it is timing driven.
read_verilog $sources
read_xdc -mode out_of_context $xdc
synth_design -top $top -part [dict get $opts part] -mode out_of_context \
    -directive [dict get $opts directive]
report_utilization -file [file join $out utilization_synth.rpt]

opt_design
place_design
phys_opt_design
route_design
write_checkpoint -force [file join $out ${top}_routed.dcp]

report_utilization -file [file join $out utilization.rpt]
report_utilization -hierarchical -file [file join $out utilization_hierarchical.rpt]
report_timing_summary -max_paths 10 -file [file join $out timing_summary.rpt]
report_methodology -file [file join $out methodology.rpt]

# Summary for scripts: the worst setup slack and the cell counts of the routed block.
set worst [get_timing_paths -setup -max_paths 1 -nworst 1]
set wns [get_property SLACK $worst]
set fd [open [file join $out summary.txt] w]
puts $fd "top=$top"
puts $fd "part=[dict get $opts part]"
puts $fd "period_ns=$period"
puts $fd "wns_ns=$wns"
puts $fd "fmax_mhz=[format %.1f [expr {1000.0 / ($period - $wns)}]]"
dict for {name filter} $rtfpga::cell_count_filters {
    puts $fd "$name=[llength [get_cells -hierarchical -filter $filter]]"
}
close $fd
puts "synth_ooc: period $period ns, WNS $wns ns; reports in $out"
