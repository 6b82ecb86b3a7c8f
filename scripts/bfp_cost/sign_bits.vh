// Included inside a module with parameter IW: bits(x), the position of the leading bit of
// x ^ sign plus one (the bits a two's-complement x needs beside its sign).
function [6:0] bits(input [IW-1:0] x);
    integer i;
    reg [IW-1:0] y;
    begin
        y = x ^ {IW{x[IW-1]}};
        bits = 0;
        for (i = 0; i < IW; i = i + 1)
            if (y[i]) bits = i + 1;
    end
endfunction
