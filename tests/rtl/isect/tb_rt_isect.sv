// tb_rt_isect: replays golden vectors through rt_isect (Icarus Verilog bench).
//
// Reads the vector files of make_isect_vectors with $readmemh (requests and the
// golden results), measures the latency of the first request through the empty
// pipeline, then streams every request through valid/ready with random input
// bubbles and output stalls, compares every result in order, and checks the
// output stream rule (valid and data hold while valid && !ready).
//
// Plusargs: +vectors=PREFIX  +n=COUNT  [+seed=S] [+stall=PERCENT] [+idle=PERCENT]
// Prints "tb_rt_isect: N passed, M failed" and "PASS" or "FAIL".
module tb_rt_isect;

  localparam int RAY_W       = rt_pkg::ISECT_RAY_W;
  localparam int TRI_W       = rt_pkg::ISECT_TRI_W;
  localparam int RES_W       = rt_pkg::ISECT_RES_W;
  localparam int LATENCY     = rt_pkg::ISECT_LATENCY;
  localparam int MAX_VECTORS = 65536;
  localparam int TIMEOUT     = 1000;  // cycles without progress

  logic             clk;
  logic             rst_n;
  logic             req_valid, req_ready;
  logic [RAY_W-1:0] req_ray;
  logic [TRI_W-1:0] req_tri;
  logic             res_valid, res_ready;
  logic [RES_W-1:0] res_data;

  rt_isect u_dut (
    .clk_i       (clk),
    .rst_ni      (rst_n),
    .req_valid_i (req_valid),
    .req_ready_o (req_ready),
    .req_ray_i   (req_ray),
    .req_tri_i   (req_tri),
    .res_valid_o (res_valid),
    .res_ready_i (res_ready),
    .res_data_o  (res_data)
  );

  logic [RAY_W-1:0] rays     [MAX_VECTORS];
  logic [TRI_W-1:0] tris     [MAX_VECTORS];
  logic [RES_W-1:0] expected [MAX_VECTORS];

  initial begin
    clk = 1'b0;
    forever #5 clk = ~clk;
  end

  string       prefix;
  int          n, seed, stall_pct, idle_pct;
  int          sent, received, passed, failed;
  int          cycle, last_progress, accept_cycle, latency;
  logic        offering, req_fire, res_fire, warmup;
  logic        held_valid;  // last cycle ended with res_valid && !res_ready
  logic [RES_W-1:0] held_data;

  // A percentage draw from the bench's own seeded generator.
  function automatic int percent();
    int r;
    r = $random(seed);
    percent = (r < 0 ? -r : r) % 100;
  endfunction

  initial begin
    if (!$value$plusargs("vectors=%s", prefix) || !$value$plusargs("n=%d", n)) begin
      $display("usage: vvp tb.vvp +vectors=PREFIX +n=COUNT [+seed=S] [+stall=PCT] [+idle=PCT]");
      $finish;
    end
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (!$value$plusargs("stall=%d", stall_pct)) stall_pct = 30;
    if (!$value$plusargs("idle=%d", idle_pct)) idle_pct = 20;
    if (n < 1 || n > MAX_VECTORS) begin
      $display("tb_rt_isect: +n=%0d out of range 1..%0d", n, MAX_VECTORS);
      $display("FAIL");
      $finish;
    end
    $readmemh({prefix, ".ray.hex"}, rays, 0, n - 1);
    $readmemh({prefix, ".tri.hex"}, tris, 0, n - 1);
    $readmemh({prefix, ".res.hex"}, expected, 0, n - 1);

    rst_n      = 1'b0;
    req_valid  = 1'b0;
    res_ready  = 1'b0;
    req_ray    = '0;
    req_tri    = '0;
    offering   = 1'b0;
    warmup     = 1'b1;
    held_valid = 1'b0;
    held_data  = '0;
    sent = 0; received = 0; passed = 0; failed = 0;
    cycle = 0; last_progress = 0; accept_cycle = 0; latency = -1;
    repeat (3) @(negedge clk);
    rst_n = 1'b1;

    while (received < n) begin
      // Drive the inputs in the middle of the cycle.
      @(negedge clk);
      // Producer: offers in order, idles at random, holds an offer until taken.
      // During warm-up the first request goes alone through the empty pipeline.
      if (!offering && sent < n && (warmup ? sent == 0 : percent() >= idle_pct)) begin
        offering = 1'b1;
        req_ray  = rays[sent];
        req_tri  = tris[sent];
      end
      req_valid = offering;
      res_ready = warmup ? 1'b1 : (percent() >= stall_pct);
      #1;
      // The output stream rule, checked where the consumer samples.
      if (held_valid && !(res_valid && res_data == held_data)) begin
        $display("tb_rt_isect: cycle %0d: result %0d changed or vanished while stalled",
                 cycle, received);
        failed = failed + 1;
      end
      req_fire = req_valid && req_ready;
      res_fire = res_valid && res_ready;
      if (res_fire) begin
        if (res_data === expected[received]) begin
          passed = passed + 1;
        end else begin
          failed = failed + 1;
          if (failed <= 10) begin
            $display("tb_rt_isect: MISMATCH result %0d (ray id = vector index)", received);
            $display("  ray      %h", rays[received]);
            $display("  tri      %h", tris[received]);
            $display("  rtl      %h", res_data);
            $display("  golden   %h", expected[received]);
            $display("  xor      %h", res_data ^ expected[received]);
          end
        end
        if (received == 0) begin
          latency = cycle - accept_cycle;
          warmup  = 1'b0;
        end
        received = received + 1;
      end
      held_valid = res_valid && !res_ready;
      held_data  = res_data;
      if (req_fire) begin
        if (sent == 0) accept_cycle = cycle;
        offering = 1'b0;
        sent     = sent + 1;
      end
      if (req_fire || res_fire) last_progress = cycle;
      if (cycle - last_progress > TIMEOUT) begin
        $display("tb_rt_isect: no progress for %0d cycles (%0d sent, %0d received)",
                 TIMEOUT, sent, received);
        failed = failed + 1;
        received = n;
      end
      @(posedge clk);
      cycle = cycle + 1;
    end

    if (latency != LATENCY) begin
      $display("tb_rt_isect: latency %0d cycles, rt_pkg::ISECT_LATENCY is %0d", latency, LATENCY);
      failed = failed + 1;
    end
    $display("tb_rt_isect: %0d passed, %0d failed (%0d vectors, latency %0d, %0d cycles, stall %0d%%, idle %0d%%)",
             passed, failed, n, latency, cycle, stall_pct, idle_pct);
    if (failed == 0 && passed == n) begin
      $display("PASS");
    end else begin
      $display("FAIL");
    end
    $finish;
  end

endmodule
