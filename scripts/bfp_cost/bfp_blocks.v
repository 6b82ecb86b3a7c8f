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

// Step 2 (and the truncated cross products of step 3): one block exponent for three
// components (x_k * 2^e_k), W-bit mantissas by an arithmetic shift (truncation towards
// -inf), and the exponent of the largest dropped part (the leading one of each component's
// dropped bits, a 3-way max; dz when nothing was dropped).
module bfp_block #(parameter IW = 29, W = 18) (
    input clk,
    input signed [IW-1:0] x0, x1, x2, input signed [9:0] e0, e1, e2,
    output reg signed [W-1:0] m0, m1, m2, output reg signed [9:0] be,
    output reg signed [9:0] de, output reg dz);
    `include "sign_bits.vh"
    function [6:0] ones(input [IW-1:0] x);  // position of the leading one of x, plus one
        integer i;
        begin
            ones = 0;
            for (i = 0; i < IW; i = i + 1)
                if (x[i]) ones = i + 1;
        end
    endfunction
    wire signed [9:0] t0 = e0 + $signed({3'b0, bits(x0)});
    wire signed [9:0] t1 = e1 + $signed({3'b0, bits(x1)});
    wire signed [9:0] t2 = e2 + $signed({3'b0, bits(x2)});
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
    // The bits below lsb: x masked to its low (lsb - e) bits.
    function [IW-1:0] rest(input [IW-1:0] x, input signed [9:0] e, input signed [9:0] l);
        reg signed [9:0] s;
        begin
            s = l - e;
            if (s <= 0) rest = 0;
            else if (s >= IW) rest = x;
            else rest = x & ~({IW{1'b1}} << s);
        end
    endfunction
    wire [IW-1:0] r0 = rest(x0, e0, lsb), r1 = rest(x1, e1, lsb), r2 = rest(x2, e2, lsb);
    wire signed [9:0] d0 = e0 + $signed({3'b0, ones(r0)});
    wire signed [9:0] d1 = e1 + $signed({3'b0, ones(r1)});
    wire signed [9:0] d2 = e2 + $signed({3'b0, ones(r2)});
    wire signed [9:0] a0 = r0 != 0 ? d0 : -10'sd512, a1 = r1 != 0 ? d1 : -10'sd512;
    wire signed [9:0] a2 = r2 != 0 ? d2 : -10'sd512;
    wire signed [9:0] d01 = a0 > a1 ? a0 : a1;
    always @(posedge clk) begin
        m0 <= place(x0, e0, lsb);
        m1 <= place(x1, e1, lsb);
        m2 <= place(x2, e2, lsb);
        be <= top;
        de <= d01 > a2 ? d01 : a2;
        dz <= (r0 | r1 | r2) == 0;
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

// Step 4: a value's margin in units of its last bit, plus and minus the value. With the
// cross products cut at a fixed exponent, a value's last bit is 2^(E_a + E_b + E_c - K)
// for a wired K, so the fixed term CF is a wired constant and each dropped-part term CD
// sits at the vector's relative dropped exponent ra, rb, rc (D - E, in [-64, 1 - W]; za..zc:
// nothing dropped) and the cut's CP at rx (the leading one in the cut's low bits), each
// plus a wired offset; a term below the last bit counts one unit (rounded up). Constants
// of 5 significant bits (CONSTANT_BITS in the model): 3√3(1 + τ)² → 21·2^-2 and 3.
module bfp_margin #(parameter N = 45, MW = 36, K = 33, KX = 19, CF = 36'd31, CD = 5'd21, CP = 5'd3) (
    input clk, input signed [N-1:0] v,
    input signed [7:0] ra, rb, rc, input [5:0] rx, input za, zb, zc, zx,
    output reg signed [N+1:0] hi, lo);
    function [MW-1:0] place(input [4:0] c, input signed [8:0] off, input z);
        reg [MW+4:0] wide;
        begin
            if (z) place = 0;
            else if (off >= 0) place = {{MW{1'b0}}, c} << off;
            else if (off <= -5) place = 1;
            else begin
                wide = {{MW{1'b0}}, c} >> (-off);
                place = wide[MW-1:0] + (({{MW{1'b0}}, c} & ~({(MW+5){1'b1}} << (-off))) != 0);
            end
        end
    endfunction
    // CD·2^(D - E)·2^(E_a + E_b + E_c) at the last bit 2^(sum - K): offset r + K - 2.
    wire [MW+1:0] e = CF + place(CD, ra + K - 2, za) + place(CD, rb + K - 2, zb)
        + place(CD, rc + K - 2, zc) + place(CP, $signed({3'b0, rx}) - KX, zx);
    always @(posedge clk) begin
        hi <= v + $signed({1'b0, e});
        lo <= v - $signed({1'b0, e});
    end
endmodule

// Step 5: x rounded to an M-bit two's-complement mantissa at its leading bit, outward:
// down (the arithmetic shift alone) or up (plus one if a dropped bit was set; UP = 1).
module bfp_round #(parameter IW = 65, M = 16, UP = 1) (
    input clk, input signed [IW-1:0] x,
    output reg signed [M:0] m, output reg [6:0] sh);
    `include "sign_bits.vh"
    wire [6:0] t = bits(x);
    // Right shift that leaves M bits (sign included): t + 1 - M, at least 0.
    wire [6:0] r = t + 1 > M ? t + 1 - M : 0;
    wire signed [IW-1:0] fl = x >>> r;
    wire sticky = UP && ((x & ~({IW{1'b1}} << r)) != 0);
    always @(posedge clk) begin
        m <= fl[M-1:0] + sticky;
        sh <= r;
    end
endmodule

// Step 5: a < b for short floats (M-bit two's-complement mantissas at their leading bit):
// the signs, then the exponents, then the mantissas.
module bfp_scmp #(parameter M = 17) (
    input clk, input signed [M-1:0] a, b, input signed [9:0] ea, eb, output reg lt);
    wire sa = a[M-1], sb = b[M-1];
    wire za = a == 0, zb = b == 0;
    wire elt = ea < eb, egt = ea > eb;
    // Same sign, non-zero: the larger exponent is the larger magnitude.
    wire mag = elt ? !sa : egt ? sa : a < b;
    always @(posedge clk)
        lt <= (sa != sb) ? sa : za ? !zb && !sb : zb ? sa : mag;
endmodule

// Step 5: down(a + b) for short floats (u + v > 1): align the smaller-exponent operand
// (its dropped bits floored away), add, round down to M bits.
module bfp_sadd #(parameter M = 17) (
    input clk, input signed [M-1:0] a, b, input signed [9:0] ea, eb,
    output reg signed [M-1:0] s, output reg signed [9:0] es);
    wire a_up = ea >= eb;
    wire [9:0] d = a_up ? ea - eb : eb - ea;
    wire [4:0] sh = d > M + 1 ? M + 1 : d[4:0];
    wire signed [M+2:0] big = a_up ? {a, 2'b0} : {b, 2'b0};
    wire signed [M+2:0] small = (a_up ? {b, 2'b0} : {a, 2'b0}) >>> sh;
    wire signed [M+3:0] sum = big + small;
    function [4:0] bits(input [M+3:0] x);
        integer i;
        reg [M+3:0] y;
        begin
            y = x ^ {(M+4){x[M+3]}};
            bits = 0;
            for (i = 0; i < M + 4; i = i + 1)
                if (y[i]) bits = i + 1;
        end
    endfunction
    wire [4:0] t = bits(sum);
    wire [4:0] r = t + 1 > M ? t + 1 - M : 0;
    always @(posedge clk) begin
        s <= sum >>> r;
        es <= (a_up ? ea : eb) - 2 + r;
    end
endmodule

// Step 3: a cross product (three components at one exponent) truncated to a W-bit block:
// bfp_block with its three exponents tied, as the hardware would build it.
module bfp_block_same #(parameter IW = 37, W = 18) (
    input clk, input signed [IW-1:0] x0, x1, x2, input signed [9:0] e,
    output signed [W-1:0] m0, m1, m2, output signed [9:0] be, de, output dz);
    bfp_block #(.IW(IW), .W(W)) b (.clk(clk), .x0(x0), .x1(x1), .x2(x2), .e0(e), .e1(e), .e2(e),
        .m0(m0), .m1(m1), .m2(m2), .be(be), .de(de), .dz(dz));
endmodule

// Step 3: a cross product cut at its fixed block exponent (the top W of IW bits: wires)
// and the exponent of its largest dropped part (the leading one of each component's low
// IW - W bits, a 3-way max; dz when nothing was dropped).
module bfp_cut #(parameter IW = 37, W = 18) (
    input clk, input signed [IW-1:0] x0, x1, x2,
    output reg signed [W-1:0] m0, m1, m2, output reg [5:0] de, output reg dz);
    localparam L = IW - W;
    function [5:0] ones(input [L-1:0] x);
        integer i;
        begin
            ones = 0;
            for (i = 0; i < L; i = i + 1)
                if (x[i]) ones = i + 1;
        end
    endfunction
    wire [5:0] d0 = ones(x0[L-1:0]), d1 = ones(x1[L-1:0]), d2 = ones(x2[L-1:0]);
    wire [5:0] d01 = d0 > d1 ? d0 : d1;
    always @(posedge clk) begin
        m0 <= x0[IW-1:L];
        m1 <= x1[IW-1:L];
        m2 <= x2[IW-1:L];
        de <= d01 > d2 ? d01 : d2;
        dz <= (x0[L-1:0] | x1[L-1:0] | x2[L-1:0]) == 0;
    end
endmodule

// The Plücker filter (docs/precision.md, "The Plücker filter"): a * 2^ea + b * 2^eb of two
// N-bit dots, the finer one shifted onto the coarser grid by an arithmetic shift (its lost
// bits truncated; beyond N bits only its sign is left). Out: s * 2^e.
module bfp_align_add #(parameter N = 38) (
    input clk, input signed [N-1:0] a, b, input signed [9:0] ea, eb,
    output reg signed [N:0] s, output reg signed [9:0] e);
    wire a_up = ea >= eb;
    wire signed [9:0] d = a_up ? ea - eb : eb - ea;
    wire [6:0] sh = d > N - 1 ? N - 1 : d[6:0];
    wire signed [N-1:0] fine = a_up ? b : a;
    wire signed [N-1:0] coarse = a_up ? a : b;
    always @(posedge clk) begin
        s <= coarse + (fine >>> sh);
        e <= a_up ? ea : eb;
    end
endmodule

// The Plücker filter's |s| bound for the fallback's margin: orig and v0 components cut to
// their top 9 bits at their block exponents, aligned to the larger, subtracted; the
// largest |difference| (plus the cuts' units, a constant) as an exponent: its leading one.
module plucker_s_bound (
    input clk, input signed [8:0] o0, o1, o2, v0, v1, v2, input signed [9:0] eo, ev,
    output reg [4:0] top, output reg signed [9:0] e);
    wire o_up = eo >= ev;
    wire signed [9:0] d = o_up ? eo - ev : ev - eo;
    wire [3:0] sh = d > 9 ? 4'd9 : d[3:0];
    function signed [9:0] diff(input signed [8:0] o, v);
        diff = o_up ? o - (v >>> sh) : (o >>> sh) - v;
    endfunction
    function [9:0] mag(input signed [9:0] x);
        mag = x[9] ? -x : x;
    endfunction
    wire [9:0] a0 = mag(diff(o0, v0)), a1 = mag(diff(o1, v1)), a2 = mag(diff(o2, v2));
    wire [9:0] m = a0 | a1 | a2;
    function [4:0] lead(input [9:0] x);
        integer i;
        begin
            lead = 0;
            for (i = 0; i < 10; i = i + 1)
                if (x[i]) lead = i + 1;
        end
    endfunction
    always @(posedge clk) begin
        top <= lead(m);
        e <= o_up ? eo : ev;
    end
endmodule
