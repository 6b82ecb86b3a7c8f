# Packages the accelerator's Verilog as a Vivado IP (IP-XACT component.xml) for IP
# integrator, with the interfaces declared explicitly rather than left to inference:
#   s_axi_control  AXI4-Lite slave (aximm_rtl), its register map from the generated C header
#   ap_clk         clock of every interface
#   ap_rst_n       synchronous reset, active low
#   interrupt      level-sensitive, active high
#   s_axis/m_axis  AXI4-Stream slave/master, only when the Verilog has those ports
#
#   vivado -mode batch -source constraints/package_ip.tcl -tclargs \
#       -verilog DIR -repo IP_REPO [-top rtfpga_top] [-version 1.0] [-work DIR]
#
# The IP lands in IP_REPO/<top> with a copy of the sources; give IP_REPO to zedboard_bd.tcl.

set script_dir [file dirname [file normalize [info script]]]
source [file join $script_dir rtfpga_common.tcl]

set usage "usage: vivado -mode batch -source package_ip.tcl -tclargs -verilog DIR -repo IP_REPO\
 \[-top NAME\] \[-vendor V\] \[-library L\] \[-version X.Y\] \[-part PART\] \[-work DIR\]"
set opts [rtfpga::parse_args $argv [dict create \
    verilog {} \
    repo {} \
    top $rtfpga::top \
    vendor $rtfpga::ip_vendor \
    library $rtfpga::ip_library \
    version $rtfpga::ip_version \
    part $rtfpga::part \
    work packaging_project] $usage]
set top [dict get $opts top]
set verilog_dir [file normalize [dict get $opts verilog]]
set sources [rtfpga::verilog_sources $verilog_dir $top]
set ip_dir [file join [file normalize [dict get $opts repo]] $top]
set work [file normalize [dict get $opts work]]

# A throw-away project holds the sources while they are packaged.
create_project -force rtfpga_packaging $work -part [dict get $opts part]
add_files -norecurse $sources
set_property top $top [current_fileset]
update_compile_order -fileset sources_1

file mkdir $ip_dir
ipx::package_project -root_dir $ip_dir -vendor [dict get $opts vendor] \
    -library [dict get $opts library] -taxonomy /UserIP -import_files -set_current true
set core [ipx::current_core]
set_property name $top $core
set_property version [dict get $opts version] $core
set_property display_name "Ray/triangle intersection accelerator ($top)" $core
set_property description "Moller-Trumbore ray/triangle test with a Vitis-HLS-style s_axi_control register interface (rtfpga)" $core

# Drop whatever the packager inferred; the interfaces are declared below, by name.
ipx::remove_all_bus_interface $core
foreach map [ipx::get_memory_maps -quiet -of_objects $core] {
    ipx::remove_memory_map [get_property NAME $map] $core
}

# Adds a bus interface and maps its logical ports to the physical ones.
proc add_interface {core name mode abstraction bus port_map} {
    set bif [ipx::add_bus_interface $name $core]
    set_property abstraction_type_vlnv $abstraction $bif
    set_property bus_type_vlnv $bus $bif
    set_property interface_mode $mode $bif
    dict for {logical physical} $port_map {
        set map [ipx::add_port_map $logical $bif]
        set_property physical_name $physical $map
    }
    return $bif
}

# Sets a bus parameter, creating it if the interface does not have it yet.
proc set_bus_parameter {bif name value} {
    set param [ipx::get_bus_parameters -quiet $name -of_objects $bif]
    if {$param eq ""} {
        set param [ipx::add_bus_parameter $name $bif]
    }
    set_property value $value $param
}

# Every port the architecture fixes must exist, with its direction.
dict for {port dir} [rtfpga::required_port_directions] {
    set p [ipx::get_ports -quiet $port -of_objects $core]
    if {$p eq ""} {
        error "$top has no port '$port' (docs/architecture.md, \"The bus\")"
    }
    if {[string tolower [get_property DIRECTION $p]] ne $dir} {
        error "$top port '$port' must be an input/output '$dir', is '[get_property DIRECTION $p]'"
    }
}

# AXI4-Lite slave.
set axil [add_interface $core $rtfpga::axil_name slave \
    xilinx.com:interface:aximm_rtl:1.0 xilinx.com:interface:aximm:1.0 [rtfpga::axil_port_map]]
set_bus_parameter $axil PROTOCOL AXI4LITE

# Clock, reset and interrupt.
set clk [add_interface $core $rtfpga::clock_port slave \
    xilinx.com:signal:clock_rtl:1.0 xilinx.com:signal:clock:1.0 [dict create CLK $rtfpga::clock_port]]
set rst [add_interface $core $rtfpga::reset_port slave \
    xilinx.com:signal:reset_rtl:1.0 xilinx.com:signal:reset:1.0 [dict create RST $rtfpga::reset_port]]
set_bus_parameter $rst POLARITY ACTIVE_LOW
set irq [add_interface $core $rtfpga::interrupt_port master \
    xilinx.com:signal:interrupt_rtl:1.0 xilinx.com:signal:interrupt:1.0 \
    [dict create INTERRUPT $rtfpga::interrupt_port]]
set_bus_parameter $irq SENSITIVITY LEVEL_HIGH

# Optional AXI4-Stream front end: all four ports of a side, or none.
set clocked [list $rtfpga::axil_name]
foreach {name mode} [list $rtfpga::axis_slave_name slave $rtfpga::axis_master_name master] {
    set port_map [rtfpga::axis_port_map $name]
    set present {}
    dict for {logical port} $port_map {
        if {[ipx::get_ports -quiet $port -of_objects $core] ne ""} {
            lappend present $port
        }
    }
    if {[llength $present] == 0} {
        continue
    }
    if {[llength $present] != [dict size $port_map]} {
        error "$top has only some of the ${name}_* ports ($present); expected [join [dict values $port_map] {, }]"
    }
    add_interface $core $name $mode \
        xilinx.com:interface:axis_rtl:1.0 xilinx.com:interface:axis:1.0 $port_map
    lappend clocked $name
}

# Everything is synchronous to ap_clk and reset by ap_rst_n.
foreach busif $clocked {
    ipx::associate_bus_interfaces -busif $busif -clock $rtfpga::clock_port $core
}
ipx::associate_bus_interfaces -clock $rtfpga::clock_port -reset $rtfpga::reset_port $core

# Memory map of the slave: one register block, the registers from the generated C header
# (the same table the HDL decoder and the driver come from, hdl/src/regmap.rs).
set awaddr [ipx::get_ports [dict get [rtfpga::axil_port_map] AWADDR] -of_objects $core]
set addr_bits [expr {[get_property SIZE_LEFT $awaddr] - [get_property SIZE_RIGHT $awaddr] + 1}]
set mmap [ipx::add_memory_map $rtfpga::axil_name $core]
set_property slave_memory_map_ref $rtfpga::axil_name $axil
set block [ipx::add_address_block Reg $mmap]
set_property range [rtfpga::address_range $addr_bits] $block
set_property width 32 $block
set_property usage register $block

set header [file join $verilog_dir $rtfpga::header_file]
if {[file exists $header]} {
    foreach r [rtfpga::registers_from_header $header] {
        set reg [ipx::add_register [dict get $r name] $block]
        set_property address_offset [format 0x%02X [dict get $r offset]] $reg
        set_property size 32 $reg
        set_property description \
            "[dict get $r description] ([dict get $r access], [dict get $r width] bits)" $reg
    }
} else {
    puts "WARNING: $header not found; the IP's address block has no register descriptions"
}

ipx::create_xgui_files $core
ipx::update_checksums $core
ipx::check_integrity $core
ipx::save_core $core
close_project
puts "package_ip: [dict get $opts vendor]:[dict get $opts library]:$top:[dict get $opts version] in $ip_dir"
