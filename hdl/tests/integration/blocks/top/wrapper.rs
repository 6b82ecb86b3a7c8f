//! `hdl::top::wrapper`.

use hdl::regmap::ADDR_BITS;
use hdl::top::wrapper::*;

#[test]
fn renames_only_the_body_modules() {
    let body = "module top(clock,x);\n    top$a$b b(\n        .x(top_x)\n    );\nendmodule // top\n\nmodule top$a$b(x);\nendmodule // top$a$b\nmodule topper(x);\n";
    let out = rename_body(body);
    assert!(out.contains("module rtfpga_core(clock,x);"), "{out}");
    assert!(out.contains("    rtfpga_core$a$b b("), "{out}");
    assert!(out.contains(".x(top_x)"), "{out}");
    assert!(out.contains("endmodule // rtfpga_core\n"), "{out}");
    assert!(out.contains("module rtfpga_core$a$b(x);"), "{out}");
    assert!(out.contains("module topper(x);"), "{out}");
    assert!(
        !out.contains("module top(") && !out.contains("module top$"),
        "{out}"
    );
}

#[test]
fn port_list_has_the_vitis_names_and_lane_widths() {
    let p = ports(4);
    let names: Vec<&str> = p.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names[..3], ["ap_clk", "ap_rst_n", "s_axi_control_awvalid"]);
    assert_eq!(p.len(), 2 + 17 + 1 + 8);
    let width = |n: &str| p.iter().find(|p| p.name == n).unwrap().width;
    assert_eq!(width("s_axis_tdata"), 4 * 544);
    assert_eq!(width("m_axis_tdata"), 512);
    assert_eq!(width("s_axi_control_awaddr"), ADDR_BITS);
    let v = wrapper_verilog(2);
    assert!(v.contains(".s_tdata$1(s_axis_tdata[1087:544])"), "{v}");
    assert!(v.contains(".m_tdata$0(m_axis_tdata[127:0])"), "{v}");
    assert!(v.contains("output wire [1:0] s_axi_control_bresp,"), "{v}");
}
