// Cost blocks of the block-floating-point filter (docs/precision.md, "The block-floating-point
// filter"): hand-written Verilog for a yosys estimate, not the filter. Each block registers
// its outputs, as one pipeline stage would.

// Step 1: a - b of two fp32 numbers, aligned to the larger exponent with G guard bits,
// the smaller operand's lost bits dropped (arithmetic shift). Out: d * 2^(e - 150 - G).
module bfp_translate #(parameter G = 3) (
    input clk, input [31:0] a, input [31:0] b,
    output reg signed [25+G:0] d, output reg [7:0] e);
    wire [7:0] ea = a[30:23], eb = b[30:23];
    wire [23:0] ma = ea == 0 ? 24'd0 : {1'b1, a[22:0]};
    wire [23:0] mb = eb == 0 ? 24'd0 : {1'b1, b[22:0]};
    wire signed [25+G:0] sa = a[31] ? -$signed({2'b0, ma, {G{1'b0}}}) : $signed({2'b0, ma, {G{1'b0}}});
    wire signed [25+G:0] sb = b[31] ? -$signed({2'b0, mb, {G{1'b0}}}) : $signed({2'b0, mb, {G{1'b0}}});
    wire a_big = ea >= eb;
    wire [7:0] diff = a_big ? ea - eb : eb - ea;
    wire [4:0] sh = diff > 8'd31 ? 5'd31 : diff[4:0];
    wire signed [25+G:0] a_al = a_big ? sa : sa >>> sh;
    wire signed [25+G:0] b_al = a_big ? sb >>> sh : sb;
    always @(posedge clk) begin
        d <= a_al - b_al;
        e <= a_big ? ea : eb;
    end
endmodule

// Step 2: one block exponent for three components (x_k * 2^e_k), W-bit mantissas by an
// arithmetic shift (truncation towards -inf).
module bfp_block #(parameter IW = 29, W = 18) (
    input clk,
    input signed [IW-1:0] x0, x1, x2, input signed [9:0] e0, e1, e2,
    output reg signed [W-1:0] m0, m1, m2, output reg signed [9:0] be);
    function [5:0] bits(input [IW-1:0] x);  // position of the leading bit of x ^ sign
        integer i;
        reg [IW-1:0] y;
        begin
            y = x ^ {IW{x[IW-1]}};
            bits = 0;
            for (i = 0; i < IW; i = i + 1)
                if (y[i]) bits = i + 1;
        end
    endfunction
    wire signed [9:0] t0 = e0 + $signed({4'b0, bits(x0)});
    wire signed [9:0] t1 = e1 + $signed({4'b0, bits(x1)});
    wire signed [9:0] t2 = e2 + $signed({4'b0, bits(x2)});
    wire signed [9:0] t01 = t0 > t1 ? t0 : t1;
    wire signed [9:0] top = t01 > t2 ? t01 : t2;
    wire signed [9:0] lsb = top - (W - 1);
    function signed [W-1:0] place(input signed [IW-1:0] x, input signed [9:0] e, input signed [9:0] l);
        reg signed [IW+W-1:0] ext;
        reg signed [9:0] s;
        begin
            ext = {x, {W{1'b0}}};
            s = l - e + W;  // right shift of ext
            if (s < 0) s = 0;
            if (s > IW + W - 1) s = IW + W - 1;
            place = ext >>> s;
        end
    endfunction
    always @(posedge clk) begin
        m0 <= place(x0, e0, lsb);
        m1 <= place(x1, e1, lsb);
        m2 <= place(x2, e2, lsb);
        be <= top;
    end
endmodule

module bfp_mul #(parameter A = 18, B = 18) (
    input clk, input signed [A-1:0] a, input signed [B-1:0] b, output reg signed [A+B-1:0] p);
    reg signed [A-1:0] ar;
    reg signed [B-1:0] br;
    always @(posedge clk) begin
        ar <= a;
        br <= b;
        p <= ar * br;
    end
endmodule

module bfp_add #(parameter N = 40) (
    input clk, input signed [N-1:0] a, b, output reg signed [N:0] s);
    always @(posedge clk) s <= a + b;
endmodule

// a * 2^ea < b * 2^eb for N-bit mantissas: the larger-exponent operand shifted left by the
// exponent difference (saturating: beyond N bits its sign decides), then compared.
module bfp_cmp #(parameter N = 96) (
    input clk, input signed [N-1:0] a, b, input signed [9:0] ea, eb, output reg lt);
    wire a_up = ea > eb;
    wire signed [9:0] d = a_up ? ea - eb : eb - ea;
    wire [6:0] sh = d > N - 1 ? N - 1 : d[6:0];
    wire signed [N-1:0] up = a_up ? a : b;
    wire signed [2*N-1:0] shifted = $signed(up) <<< sh;
    wire signed [2*N-1:0] aa = a_up ? shifted : a;
    wire signed [2*N-1:0] bb = a_up ? b : shifted;
    always @(posedge clk) lt <= aa < bb;
endmodule
