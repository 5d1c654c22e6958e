# Sources of rt_isect for scripts/synth, relative to rtl/, in compile order
# (the generated package is read first by the script).
lib/rt_stall_stages.sv
isect/rt_isect.sv
