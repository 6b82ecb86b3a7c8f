# Project hook of rtfpga.core's `synth` target: FuseSoC (edalize) sources it while creating
# the Vivado project, after reading the Verilog and constraints/ooc.xdc. It makes synth_1 an
# out-of-context run of rtfpga_top, like constraints/synth_ooc.tcl does in non-project mode:
# no I/O buffers on the 700-odd ports (more than the xc7z020clg484 has pins), and
# ooc.xdc's clock and boundary delays apply. Not run: Vivado is not available here.
set_property USED_IN {synthesis implementation out_of_context} \
    [get_files -of_objects [get_filesets constrs_1] *ooc.xdc]
set_property -name {STEPS.SYNTH_DESIGN.ARGS.MORE OPTIONS} -value {-mode out_of_context} \
    -objects [get_runs synth_1]
