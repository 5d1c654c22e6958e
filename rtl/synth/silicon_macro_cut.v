// Cuts a memory out of the netlist (scripts/silicon maps the $mem_v2 cells it
// chose as macros with this): its read data become inputs and its addresses,
// enables and write data outputs of the top (expose), so the netlist is the
// logic alone and STA times the paths into and out of the macro against its
// access time.
module \$mem_v2 (RD_CLK, RD_EN, RD_ARST, RD_SRST, RD_ADDR, RD_DATA, WR_CLK, WR_EN, WR_ADDR, WR_DATA);
  parameter MEMID = "";
  parameter SIZE = 0;
  parameter OFFSET = 0;
  parameter ABITS = 1;
  parameter WIDTH = 1;
  parameter INIT = 0;
  parameter RD_PORTS = 1;
  parameter RD_CLK_ENABLE = 0;
  parameter RD_CLK_POLARITY = 0;
  parameter RD_TRANSPARENCY_MASK = 0;
  parameter RD_COLLISION_X_MASK = 0;
  parameter RD_WIDE_CONTINUATION = 0;
  parameter RD_CE_OVER_SRST = 0;
  parameter RD_ARST_VALUE = 0;
  parameter RD_SRST_VALUE = 0;
  parameter RD_INIT_VALUE = 0;
  parameter WR_PORTS = 1;
  parameter WR_CLK_ENABLE = 0;
  parameter WR_CLK_POLARITY = 0;
  parameter WR_PRIORITY_MASK = 0;
  parameter WR_WIDE_CONTINUATION = 0;
  input  [RD_PORTS-1:0] RD_CLK, RD_EN, RD_ARST, RD_SRST;
  input  [RD_PORTS*ABITS-1:0] RD_ADDR;
  output [RD_PORTS*WIDTH-1:0] RD_DATA;
  input  [WR_PORTS-1:0] WR_CLK;
  input  [WR_PORTS*WIDTH-1:0] WR_EN;
  input  [WR_PORTS*ABITS-1:0] WR_ADDR;
  input  [WR_PORTS*WIDTH-1:0] WR_DATA;
  (* keep *) wire [RD_PORTS*WIDTH-1:0] macro_rd_data;
  (* keep *) wire [RD_PORTS*ABITS-1:0] macro_rd_addr = RD_ADDR;
  (* keep *) wire [RD_PORTS-1:0] macro_rd_en = RD_EN;
  (* keep *) wire [WR_PORTS*ABITS-1:0] macro_wr_addr = WR_ADDR;
  (* keep *) wire [WR_PORTS*WIDTH-1:0] macro_wr_en = WR_EN;
  (* keep *) wire [WR_PORTS*WIDTH-1:0] macro_wr_data = WR_DATA;
  assign RD_DATA = macro_rd_data;
endmodule
