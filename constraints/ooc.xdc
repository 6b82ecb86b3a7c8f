# Out-of-context constraints of the accelerator (rtfpga_top) on its own, without the PS.
#
# Used by synth_ooc.tcl (read_xdc -mode out_of_context). The clock period is the one line
# below: synth_ooc.tcl -period <ns> rewrites it into a copy in its output directory; to use
# this file elsewhere, edit the number. The default 4.5 ns (222 MHz) is the target of the
# thesis' best HLS run ("Run 7"); the ZedBoard fabric clock it then ran at was 214 MHz.
# Only commands of UG903's "valid commands in an XDC file" are used (set, expr, get_*).
# No pin locations: in the system the block connects to the PS and the interconnect only.

set ooc_period_ns 4.5

# The only clock. In the block design it is the PS7's FCLK_CLK0, which reaches the fabric
# through a global buffer: HD.CLK_SRC tells the OOC implementation so, so clock skew and
# insertion delay are modelled as they will be in context (UG905, context constraints).
create_clock -name ap_clk -period $ooc_period_ns [get_ports ap_clk]
set_property HD.CLK_SRC BUFGCTRL_X0Y0 [get_ports ap_clk]

# Margin for the FCLK jitter and the top level's routing that OOC cannot see.
set_clock_uncertainty -setup 0.100 [get_clocks ap_clk]

# Boundary budget. Every other port (AXI4-Lite, ap_rst_n, the optional AXI4-Stream ports)
# is synchronous to ap_clk and connects to registers of the AXI interconnect/SmartConnect
# or the PS7's GP0 port. Those paths get 30 % of the period outside the block, leaving the
# block 70 % from a port to its first register and from its last register to a port; the
# block's own register-to-register paths get the full period.
set_input_delay  -clock ap_clk [expr {0.3 * $ooc_period_ns}] [get_ports -filter {DIRECTION == IN && NAME != ap_clk}]
set_output_delay -clock ap_clk [expr {0.3 * $ooc_period_ns}] [get_ports -filter {DIRECTION == OUT}]
