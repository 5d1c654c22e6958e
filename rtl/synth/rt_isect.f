# Sources of rt_isect for scripts/synth, relative to rtl/, in compile order
# (the generated package is read first by the script).
isect/rt_isect.sv
