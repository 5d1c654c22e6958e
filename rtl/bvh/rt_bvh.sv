// rt_bvh: the BVH traversal unit, feeding rt_isect from memory.
//
// Bit-exact with fx::traverseBvh (sw/golden/bvh.h): for every ray the same
// nodes in the same order (nearest child first, the farther pushed; exact
// ray-box tests over the lattice planes, fx::boxTest), every triangle of every
// entered leaf tested (index-list order), the closest hit by fx::closerResult,
// the cull rule of a candidate whose bound lies before it (fx::culledBy, the
// shell's exit test with exit = entry - 1), and an any-hit ray answered after
// the leaf of its first hit. docs/bvh-unit.md, "Micro-architecture of
// rt_bvh", specifies it cycle by cycle; the SystemC model (systemc/bvh/)
// implements the same text.
//
//   u_shell    rt_trav_shell: ray input and slot allocation, the arbiters and
//              FIFOs of every port, the index and triangle path to rt_isect,
//              the per-slot ray and closest hit, the exit test, the counts,
//              the results (the node port is its node port, not registered:
//              RegRsp = 0)
//   u_setup    rt_mirror_pairs: the per-ray setup (multiplications only,
//              BVH_SETUP_LATENCY stages)
//   u_box      rt_bvh_box: both children's box tests of a node response
//              (BVH_BOX_LATENCY stages, one node a cycle)
//   the walk   RaysInFlight slots (below): walk state, candidates, stacks,
//              the pop lane
//   visit_*    one record per node entered (round robin over slots in ENTER)
//   node port  one node read per interior node entered (round robin)
//   idx port   one index-list read per test (round robin), credit-limited
//   tri port   one triangle read per index response, in index-response order
//   check      one exit test per cycle (round robin over the candidates of
//              bound slots with a non-zero entry)
//   res_*      one record per ray
//
// This module is the walk, beside its rt_trav_shell, which keeps the ray, its
// closest hit, the dominant, the common denominator of the exit test and the
// counts; the two are joined by name (the ports of rt_walk_ports.svh).
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credit-based index responses; nodes and triangles consumed in their cycle).
// Responses per port must come in request order; the tag is the slot.
//
// Latency:    >= 1 + BVH_SETUP_LATENCY (setup) + per interior node ENTER,
//             NODE_REQ, the read, the box test (L + 5 cycles from ENTER to the
//             child's ENTER at memory latency L); per leaf ENTER, the reads
//             and ISECT_LATENCY if it holds triangles, then a pop.
// Throughput: per cycle at most one ray accepted, one node entered, one node
//             read, one box test, one index read, one triangle read, one
//             intersection test, one closest-hit update, one exit test, one
//             pop and one result.
//
// The walk: the ray slots — per-slot state machines, the current candidate
// node {ref, entry}, the stacks and the pop lane — updated by the unit's
// events, each addressed to one slot by index (docs/bvh-unit.md, "Slot state
// machine").
//
//   FREE -alloc-> SETUP -init-> ENTER (the root, entry 0)
//   ENTER -visit grant-> NODE_REQ (interior) | FETCH (leaf, count > 0) | POP (empty leaf)
//   NODE_REQ -node grant-> WAIT_NODE -node response (into rt_bvh_box)-> BOX
//   BOX -the box answer-> candidate(near) [push far] | candidate(the one) | POP (none)
//   FETCH: one index read per index grant; once every result is in
//          -> DONE (an any-hit ray with a hit) | POP
//   POP -pop-lane grant, acting in the next cycle-> candidate(popped) | DONE (stack empty)
//   candidate(x): CHECK if the slot is bound and x's entry != 0, else ENTER
//   CHECK -the exit test's answer-> POP (culled: the bound lies before the node) | ENTER
//   DONE -done grant-> FREE
//   ENTER(x) with cfg_suspend_i, x interior, x's block (x.first >>
//          cfg_block_shift_i) not the slot's (the block of the last interior
//          node it entered) and at most BVH_SUSPEND_ENTRIES entries on its
//          stack: DONE, suspended instead (its result carries the walk:
//          res_suspended_o, res_walk_o); it resumes as a new ray with
//          ray_resume_i, x its candidate (ENTER at init, in x's block)
//
// Which slots act in a cycle. The box answer (one per cycle: one node response
// a cycle) names one slot. FETCH ends the cycle after the result that
// completes the leaf (one per cycle): the registered result slot. The pop
// lane is one round-robin arbiter over the slots in POP whose grant is
// registered: the granted slot pops in the next cycle (and is left out of the
// arbitration meanwhile). The exit test's answer names one slot.
//
// Storage: one-hot state vectors (N bits each, reset); per-slot registers as
// arrays written by index (no reset; written before read). The stacks of all
// slots, entries {ref, entry}, in two parts: each slot's bottom
// BVH_SUSPEND_ENTRIES (the suspend window: a suspension reads them and a
// resumption writes them at once) in flip-flops, and the entries above in one
// memory of N x (BVH_STACK_DEPTH - BVH_SUSPEND_ENTRIES): one write port (the
// box answer's push), one read port (the pop lane), a macro.
//
// Latency: every transition takes one clock edge. Throughput: per cycle one
// allocation, one init, one visit, one node grant, one node response, one box
// answer, one index grant, one result, one end of FETCH, one pop, one exit
// test, one result record.
`include "rt_walk_core.svh"
module rt_bvh #(
  `RT_WALK_UNIT_PARAMS,
  parameter int unsigned NodeRspW = rt_pkg::BVH_NODE_W  // derived: a node response's bits
) (
`include "rt_trav_ports.svh"

  // Configuration, static while rays are in flight.
  input  rt_pkg::bvh_ref_t                       cfg_root_i,   // the root's reference
  // The treelet schedule (docs/scheduling.md): set walks aside where they
  // leave their treelet block of 2^cfg_block_shift_i node-table entries.
  input  logic                                   cfg_suspend_i,
  input  logic [rt_pkg::BVH_BLOCK_SHIFT_W-1:0]   cfg_block_shift_i,

  // With a ray accepted: it resumes the walk of ray_walk_i.
  input  logic                                   ray_resume_i,
  input  rt_pkg::bvh_walk_t                      ray_walk_i,

  // One result per ray (per walk: a suspended walk's result comes with its
  // record, res_walk_o, 0 otherwise), one record per node entered.
  output rt_pkg::bvh_res_t                         res_data_o,
  output logic                                     res_suspended_o,
  output rt_pkg::bvh_walk_t                        res_walk_o,
  output rt_pkg::bvh_visit_t                       visit_data_o
);

  // The figures of the walk's ports toward its shell, and the shell, with
  // the slot core's events and checks (rt_walk_core.svh).
  localparam int unsigned VisitIdW  = 32;
  localparam int unsigned ExitW     = rt_pkg::BVH_ENTRY_W;
  localparam int unsigned DenW      = rt_pkg::BVH_COMMON_W;
  localparam int unsigned RunPorts  = 1;
  localparam bit          RegRsp    = 1'b0;  // node responses straight to the walk
  // A suspended walk's record less its closest hit (the result carries that).
  localparam int unsigned WalkPartW = rt_pkg::BVH_WALK_W - `RT_WALK_HIT_W;
`define RT_WALK_CORE_BODY
`include "rt_walk_core.svh"

  // ---- The walk ----------------------------------------------------------------------
  localparam int P       = rt_pkg::POS_W;
  localparam int ORG_W   = P + 1;
  localparam int PAIR_W  = 2 * (rt_pkg::DIR_W - 1);
  localparam int ADDR_W  = rt_pkg::MEM_ADDR_W;
  localparam int REF_W   = rt_pkg::BVH_REF_W;
  localparam int ENTRY_W = rt_pkg::BVH_ENTRY_W;
  localparam int COUNT_W = rt_pkg::BVH_COUNT_W;
  localparam int STACK   = rt_pkg::BVH_STACK_DEPTH;
  localparam int SP_W    = $clog2(STACK + 1);                    // 0 .. STACK
  localparam int STK_W   = (STACK > 1) ? $clog2(STACK) : 1;
  // The stack in two parts: each slot's bottom BVH_SUSPEND_ENTRIES entries (the
  // suspend window) in flip-flops, which a suspension reads and a resumption
  // writes all at once; the entries above them in one memory of one read and
  // one write port (a macro: docs/silicon.md).
  localparam int WIN     = rt_pkg::BVH_SUSPEND_ENTRIES;
  localparam int UPPER   = STACK - WIN;                          // entries above the window, per slot
  localparam int WIN_AW  = $clog2(N * WIN);
  localparam int UP_AW   = (N * UPPER > 1) ? $clog2(N * UPPER) : 1;
  localparam int CAND_W  = REF_W + ENTRY_W;                      // {ref, entry}

  // bvh_ref_t as plain bits, read into a local struct (Yosys 0.23 reads a
  // package type only outside a struct).
  typedef struct packed {
    logic               leaf;
    logic [COUNT_W-1:0] count;
    logic [31:0]        first;
  } ref_t;

  // Where slot s keeps its stack entry k.
  function automatic logic [WIN_AW-1:0] win_addr(input logic [SlotW-1:0] s, input logic [STK_W-1:0] k);
    win_addr = WIN_AW'(s) * WIN_AW'(WIN) + WIN_AW'(k);
  endfunction
  function automatic logic [UP_AW-1:0] upper_addr(input logic [SlotW-1:0] s, input logic [STK_W-1:0] k);
    logic [STK_W-1:0] above;  // the entry's place above the window
    above = k - STK_W'(WIN);
    upper_addr = UP_AW'(s) * UP_AW'(UPPER) + UP_AW'(above);
  endfunction

  // ---- State vectors (bit s = slot s) -------------------------------------------
  logic [N-1:0] enter_q, node_req_q, wait_node_q, box_q, fetch_q, pop_q, check_q, done_q;
  logic [N-1:0] any_hit_q;   // the ray is an any-hit ray
  logic [N-1:0] hit_seen_q;  // a result of the ray was a hit
  logic         fin_q;       // a slot's last result came in the previous cycle: fin_slot_q
  logic [SlotW-1:0] fin_slot_q;

  // ---- Per-slot registers -------------------------------------------------------------
  logic [2:0]             mirror_q [N];
  logic [2:0]             active_q [N];
  logic [3*ORG_W-1:0]     org_q    [N];   // o' {z, y, x}
  logic [3*PAIR_W-1:0]    pair_q   [N];
  logic [REF_W-1:0]       cur_ref_q   [N];  // the candidate: its reference and entry
  logic [ENTRY_W-1:0]     cur_entry_q [N];
  logic [SP_W-1:0]        sp_q     [N];
  logic [CAND_W-1:0]      win_q    [N * WIN];    // stack entries 0 .. WIN-1 of each slot
  logic [CAND_W-1:0]      upper_q  [N * UPPER];  // entries WIN .. STACK-1
  logic [31:0]            blk_q    [N];     // the last interior node entered (its block: the bits above the shift)
  logic [N-1:0]           suspending_q;     // DONE: the walk is set aside, not over

  // ---- Events ----------------------------------------------------------------------------
  // The walk's own (the shell's are the slot core's: rt_walk_core.svh).
  logic [N-1:0] box_oh, fin_oh, pop_oh;
  assign box_oh   = onehot(box_valid, box_slot);
  assign fin_oh   = onehot(fin_q, fin_slot_q);

  // ---- The ray's setup: rt_mirror_pairs ---------------------------------------------------
  logic [2:0]           init_mirror, init_active;
  logic [3*ORG_W-1:0]   init_origin;
  logic [3*PAIR_W-1:0]  init_pair;
  logic                 unused_s1_valid, unused_s2_valid;
  logic [3*ORG_W-1:0]   unused_s1_org, unused_s2_org;
  logic [3*PAIR_W-1:0]  unused_s2_pair;

  rt_mirror_pairs #(.SlotW(SlotW), .Latency(rt_pkg::BVH_SETUP_LATENCY), .ComW(DenW)) u_setup (
    `RT_WALK_SETUP_PORTS,
    .s1_valid_o  (unused_s1_valid),
    .s2_valid_o  (unused_s2_valid),
    .active_o    (init_active),
    .neg_o       (init_mirror),
    .s1_org_o    (unused_s1_org),
    .s2_org_o    (unused_s2_org),
    .s2_pair_o   (unused_s2_pair),
    .s3_org_o    (init_origin),
    .s3_pair_o   (init_pair),
    .s3_common_o (init_den)
  );

  // ---- The box tester: both children's tests of a node response (rt_bvh_box) ------------
  logic [3*ORG_W-1:0]   box_origin;
  logic [2:0]           box_mirror, box_active;
  logic [3*PAIR_W-1:0]  box_pair;
  logic                 box_valid, box_near;
  logic [SlotW-1:0]     box_slot;
  logic [1:0]           box_hit;
  logic [2*ENTRY_W-1:0] box_entries;
  logic [2*REF_W-1:0]   box_children;

  rt_bvh_box #(.SlotW(SlotW)) u_box (
    .clk_i,
    .rst_ni,
    .valid_i  (node_valid),
    .slot_i   (node_tag),
    .node_i   (node_data),
    .origin_i (box_origin),
    .mirror_i (box_mirror),
    .active_i (box_active),
    .pair_i   (box_pair),
    .valid_o  (box_valid),
    .slot_o   (box_slot),
    .hit_o    (box_hit),
    .entry_o  (box_entries),
    .near_o   (box_near),
    .child_o  (box_children)
  );

  // The visited node's reference decides where the slot goes.
  ref_t             visit_ref;
  logic             visit_empty;
  assign visit_ref   = cur_ref_q[visit_slot];
  assign visit_empty = visit_ref.count == '0;

  // ---- The pop lane ----------------------------------------------------------------------
  // A round robin over the slots in POP, its grant registered: the granted slot
  // pops in the next cycle, out of the arbitration meanwhile.
  logic             pop_arb_go, pop_go_q;
  logic [SlotW-1:0] pop_arb_slot, pop_slot_q;
  logic [N-1:0]     unused_pop_gnt;

  rt_rr_arb #(.N(N)) u_pop_arb (
    .clk_i, .rst_ni, .req_i(pop_q & ~onehot(pop_go_q, pop_slot_q)), .ack_i(pop_arb_go),
    .valid_o(pop_arb_go), .gnt_o(unused_pop_gnt), .idx_o(pop_arb_slot));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pop_go_q <= 1'b0;
    end else begin
      pop_go_q <= pop_arb_go;
    end
  end
  always_ff @(posedge clk_i) begin
    if (pop_arb_go) pop_slot_q <= pop_arb_slot;
  end
  assign pop_oh = onehot(pop_go_q, pop_slot_q);

  // The pop: the top of the stack becomes the candidate, or DONE when it is empty.
  logic [SP_W-1:0]   pop_sp;
  logic              pop_empty;
  logic [CAND_W-1:0] pop_top;
  assign pop_sp    = sp_q[pop_slot_q];
  assign pop_empty = pop_sp == '0;
  logic [STK_W-1:0]  pop_k;
  assign pop_k     = STK_W'(pop_sp - 1'b1);
  assign pop_top   = pop_k < STK_W'(WIN) ? win_q[win_addr(pop_slot_q, pop_k)] : upper_q[upper_addr(pop_slot_q, pop_k)];

  // ---- The box answer --------------------------------------------------------------------
  // Both children entered: the nearer (child 0 on a tie) is the candidate, the
  // farther is pushed; one: it is the candidate; none: POP.
  logic              box_both, box_none, box_pick;   // box_pick: the candidate is child 1
  logic [REF_W-1:0]  box_ref [2];
  logic [ENTRY_W-1:0] box_entry [2];
  assign box_ref[0]   = box_children[0 +: REF_W];
  assign box_ref[1]   = box_children[REF_W +: REF_W];
  assign box_entry[0] = box_entries[0 +: ENTRY_W];
  assign box_entry[1] = box_entries[ENTRY_W +: ENTRY_W];
  assign box_both     = box_hit == 2'b11;
  assign box_none     = box_hit == 2'b00;
  assign box_pick     = box_both ? box_near : box_hit[1];

  // The new candidates' next states (the candidate rule): CHECK if the slot is
  // bound and the entry is not 0, else ENTER.
  logic box_check, pop_check;
  assign box_check = bound[box_slot] && box_entry[box_pick] != '0;
  assign pop_check = bound[pop_slot_q] && pop_top[ENTRY_W-1:0] != '0;

  // ---- Suspension (the treelet schedule) ------------------------------------------------
  // A candidate about to be entered leaves the unit instead when it is an
  // interior node of another block than the slot's and the stack (as it
  // stands after the event) fits the record's window.
  localparam int SUSPEND = rt_pkg::BVH_SUSPEND_ENTRIES;
  // Two nodes share a block when their indices agree above the block's shift:
  // a mask (registered: the configuration is static), not a shifter, after
  // the stack's read.
  logic [31:0] blk_mask_q;
  always_ff @(posedge clk_i) blk_mask_q <= ~((32'(1) << cfg_block_shift_i) - 32'(1));
  // (A reference's leaf bit is its top bit, its first field the low 32: bvh_ref_t.)
  function automatic logic leaves(input logic leaf, input logic [31:0] first, input logic [31:0] last,
                                  input logic [SP_W-1:0] sp);
    leaves = cfg_suspend_i && !leaf && ((first ^ last) & blk_mask_q) != '0 && sp <= SP_W'(SUSPEND);
  endfunction
  logic [REF_W-1:0] pop_ref, check_ref;
  logic box_leaves, pop_leaves, check_leaves;
  assign pop_ref      = pop_top[ENTRY_W +: REF_W];
  assign check_ref    = cur_ref_q[check_slot];
  assign box_leaves   = leaves(box_ref[box_pick][REF_W-1], box_ref[box_pick][31:0], blk_q[box_slot],
                               sp_q[box_slot] + SP_W'(box_both));
  assign pop_leaves   = leaves(pop_ref[REF_W-1], pop_ref[31:0], blk_q[pop_slot_q], pop_sp - 1'b1);
  assign check_leaves = leaves(check_ref[REF_W-1], check_ref[31:0], blk_q[check_slot], sp_q[check_slot]);

  // A resumed walk's record, captured with its ray and carried beside the
  // ray's setup (BVH_SETUP_LATENCY stages, as rt_mirror_pairs): at init the
  // slot takes its candidate, stack and closest hit.
  // bvh_walk_t's fields as bit offsets (Yosys 0.23 takes no element of a
  // packed array field): stack_entry[k] at k * ENTRY_W, stack_ref[k] at
  // W_REF + k * REF_W, then sp, next_entry, next_ref and the closest hit on top.
  localparam int W_REF   = SUSPEND * ENTRY_W;
  localparam int W_SP    = W_REF + SUSPEND * REF_W;
  localparam int W_NEXTE = W_SP + SP_W;
  localparam int W_NEXTR = W_NEXTE + ENTRY_W;
  localparam int W_HIT   = W_NEXTR + REF_W;
  logic [rt_pkg::BVH_WALK_W-1:0] init_walk;
  rt_pipe_regs #(.Width(rt_pkg::BVH_WALK_W), .Stages(rt_pkg::BVH_SETUP_LATENCY)) u_resumed (
    .clk_i, .rst_ni, .valid_i(alloc && ray_resume_i), .data_i(ray_walk_i), .valid_o(init_resume), .data_o(init_walk));
  assign init_hit    = init_walk[W_HIT +: `RT_WALK_HIT_W];
  // The candidate at init: the root, or the resumed walk's next node.
  logic [REF_W-1:0]   init_ref;
  logic [ENTRY_W-1:0] init_entry;
  ref_t               init_ref_s;
  assign init_ref   = init_resume ? init_walk[W_NEXTR +: REF_W] : cfg_root_i;
  assign init_entry = init_resume ? init_walk[W_NEXTE +: ENTRY_W] : '0;
  assign init_ref_s = init_ref;

  // ---- State (reset) ---------------------------------------------------------------------
  // Each vector loses the slots whose event leaves its state and gains those
  // whose event enters it.
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      enter_q     <= '0;
      node_req_q  <= '0;
      wait_node_q <= '0;
      box_q       <= '0;
      fetch_q     <= '0;
      pop_q       <= '0;
      check_q     <= '0;
      done_q      <= '0;
      suspending_q <= '0;
      hit_seen_q  <= '0;
      fin_q       <= 1'b0;
      fin_slot_q  <= '0;
    end else begin : b_next
      logic [N-1:0] visit_node, visit_fetch, visit_pop, box_to_check, box_to_enter, box_to_pop;
      logic [N-1:0] pop_to_done, pop_to_check, pop_to_enter, fin_to_done;
      logic [N-1:0] box_to_leave, pop_to_leave, check_to_enter, check_to_leave, leave;
      logic         fin_done;
      visit_node   = visit_oh & {N{!visit_ref.leaf}};
      visit_fetch  = visit_oh & {N{visit_ref.leaf && !visit_empty}};
      visit_pop    = visit_oh & {N{visit_ref.leaf && visit_empty}};
      box_to_pop   = box_oh & {N{box_none}};
      box_to_check = box_oh & {N{!box_none && box_check}};
      box_to_enter = box_oh & {N{!box_none && !box_check && !box_leaves}};
      box_to_leave = box_oh & {N{!box_none && !box_check && box_leaves}};
      pop_to_done  = pop_oh & {N{pop_empty}};
      pop_to_check = pop_oh & {N{!pop_empty && pop_check}};
      pop_to_enter = pop_oh & {N{!pop_empty && !pop_check && !pop_leaves}};
      pop_to_leave = pop_oh & {N{!pop_empty && !pop_check && pop_leaves}};
      check_to_enter = check_oh & {N{!check_holds && !check_leaves}};
      check_to_leave = check_oh & {N{!check_holds && check_leaves}};
      fin_done     = any_hit_q[fin_slot_q] && hit_seen_q[fin_slot_q];
      fin_to_done  = fin_oh & {N{fin_done}};
      enter_q     <= (enter_q & ~visit_oh) | init_oh | box_to_enter | pop_to_enter | check_to_enter;
      node_req_q  <= (node_req_q & ~node_oh) | visit_node;
      wait_node_q <= (wait_node_q & ~rsp_oh) | node_oh;
      box_q       <= (box_q & ~box_oh) | rsp_oh;
      fetch_q     <= (fetch_q & ~fin_oh) | visit_fetch;
      pop_q       <= (pop_q & ~pop_oh) | visit_pop | box_to_pop | (fin_oh & ~fin_to_done)
                     | (check_oh & {N{check_holds}});
      check_q     <= (check_q & ~check_oh) | box_to_check | pop_to_check;
      leave        = box_to_leave | pop_to_leave | check_to_leave;
      done_q      <= (done_q & ~done_oh) | pop_to_done | fin_to_done | leave;
      // Set when the walk leaves, cleared when the slot takes its next ray.
      suspending_q <= (suspending_q & ~init_oh) | leave;
      hit_seen_q  <= (hit_seen_q & ~init_oh) | onehot(isect_valid && isect_hit, isect_slot);
      // The result that completes the leaf: FETCH ends in the next cycle.
      fin_q       <= res_last;
      fin_slot_q  <= isect_slot;
    end
  end

  // ---- Per-slot registers (no reset: written before read) ------------------------------
  // The candidate and the stack pointer: init, the box answer, the pop (their
  // slots differ: SETUP, BOX and POP).
  always_ff @(posedge clk_i) begin : p_walk
    if (box_valid && !box_none) begin
      cur_ref_q[box_slot]   <= box_ref[box_pick];
      cur_entry_q[box_slot] <= box_entry[box_pick];
      if (box_both) sp_q[box_slot] <= sp_q[box_slot] + 1'b1;
    end
    if (pop_go_q && !pop_empty) begin
      cur_ref_q[pop_slot_q]   <= pop_top[ENTRY_W +: REF_W];
      cur_entry_q[pop_slot_q] <= pop_top[ENTRY_W-1:0];
      sp_q[pop_slot_q]        <= pop_sp - 1'b1;
    end
    if (init) begin
      cur_ref_q[init_slot]   <= init_ref;
      cur_entry_q[init_slot] <= init_entry;
      sp_q[init_slot]        <= init_resume ? init_walk[W_SP +: SP_W] : '0;
    end
  end

  // The last interior node the slot entered (its block: the bits above the shift): at init its first node.
  always_ff @(posedge clk_i) begin : p_block
    if (visit_go && !visit_ref.leaf) blk_q[visit_slot] <= visit_ref.first;
    if (init) blk_q[init_slot] <= init_ref_s.first;
  end

  // The stack: the box answer pushes the farther child; a resumed walk's
  // entries come in at init (the window's; those above its sp are never read).
  always_ff @(posedge clk_i) begin : p_stack
    if (box_valid && box_both) begin
      if (sp_q[box_slot] < SP_W'(WIN)) begin
        win_q[win_addr(box_slot, STK_W'(sp_q[box_slot]))] <= {box_ref[!box_pick], box_entry[!box_pick]};
      end else begin
        upper_q[upper_addr(box_slot, STK_W'(sp_q[box_slot]))] <= {box_ref[!box_pick], box_entry[!box_pick]};
      end
    end
    if (init && init_resume) begin
      for (int k = 0; k < SUSPEND; k++) begin
        win_q[win_addr(init_slot, STK_W'(k))] <= {init_walk[W_REF + k * REF_W +: REF_W],
                                                       init_walk[k * ENTRY_W +: ENTRY_W]};
      end
    end
  end

  // A suspended walk's part of its record, for done_slot: its candidate, sp
  // and the stack's window (entries at or above sp read as 0).
  logic [SUSPEND*REF_W-1:0]   done_stack_ref;    // entry k at k * REF_W
  logic [SUSPEND*ENTRY_W-1:0] done_stack_entry;  // entry k at k * ENTRY_W
  always_comb begin
    for (int k = 0; k < SUSPEND; k++) begin
      {done_stack_ref[k * REF_W +: REF_W], done_stack_entry[k * ENTRY_W +: ENTRY_W]} =
          SP_W'(k) < sp_q[done_slot] ? win_q[win_addr(done_slot, STK_W'(k))] : '0;
    end
  end
  assign done_suspend = suspending_q[done_slot];
  assign done_walk    = {cur_ref_q[done_slot], cur_entry_q[done_slot], sp_q[done_slot], done_stack_ref,
                         done_stack_entry};
  assign res_suspended_o = res_suspend;
  assign res_walk_o      = res_walk;

  // The ray's setup.
  always_ff @(posedge clk_i) begin : p_ray
    if (init) begin
      mirror_q[init_slot] <= init_mirror;
      active_q[init_slot] <= init_active;
      org_q[init_slot]    <= init_origin;
      pair_q[init_slot]   <= init_pair;
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      any_hit_q <= '0;
    end else if (init) begin
      any_hit_q[init_slot] <= init_ray.any_hit;
    end
  end

  // ---- Outputs ----------------------------------------------------------------------------
  // (Whole references read by index: the address takes their first field.)
  ref_t             node_ref, idx_ref;
  logic [REF_W-1-32:0] unused_node_ref, unused_idx_ref;
  assign node_ref        = cur_ref_q[node_slot];
  assign idx_ref         = cur_ref_q[idx_slot];
  assign unused_node_ref = {node_ref.leaf, node_ref.count};
  logic [REF_W-1-32:0] unused_init_ref;
  assign unused_init_ref = {init_ref_s.leaf, init_ref_s.count};
  assign unused_idx_ref  = {idx_ref.leaf, idx_ref.count};
  assign visit_id = visit_ref.first | {visit_ref.leaf, 31'd0};
  // A leaf's triangles are counted when it is entered.
  assign run_start       = visit_go && visit_ref.leaf;
  assign run_slot        = visit_slot;
  assign run_count       = 32'(visit_ref.count);
  assign node_addr     = ADDR_W'(node_ref.first);
  assign idx_addr      = ADDR_W'(idx_ref.first + idx_issued);
  assign check_exit    = cur_entry_q[check_sel] - 1'b1;
  assign box_origin    = org_q[node_tag];
  assign box_mirror    = mirror_q[node_tag];
  assign box_active    = active_q[node_tag];
  assign box_pair      = pair_q[node_tag];

  assign want_visit   = enter_q;
  assign want_node    = node_req_q;
  assign want_check   = check_q;
  assign want_done    = done_q;
  assign fetching     = fetch_q;

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // Events meet slots in the states that expect them.
  `RT_CHECK_IF(a_node_rsp_slot, node_valid, wait_node_q[node_tag])
  `RT_CHECK_IF(a_box_slot, box_valid, box_q[box_slot])
  `RT_CHECK_IF(a_pop_slot, pop_go_q, pop_q[pop_slot_q])
  // A candidate tested is bound (it asked in CHECK; bounds never go away).
  `RT_CHECK(a_check_bound, (check_q & ~bound) == '0)
  // The stack never overflows: a push happens below the levels limit
  // (kBvhMaxLevels; checkImage refuses deeper images).
  `RT_CHECK_IF(a_stack_depth, box_valid && box_both, sp_q[box_slot] < SP_W'(STACK))
  // The record's layout, as bvh_walk_t packs it.
  `RT_ASSERT_STATIC(g_walk_layout_check, W_HIT + `RT_WALK_HIT_W == rt_pkg::BVH_WALK_W && SP_W == rt_pkg::BVH_SP_W,
                    "rt_bvh: the offsets of bvh_walk_t's fields differ from rt_pkg")
`endif

endmodule
