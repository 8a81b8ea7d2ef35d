O1000 (gear hobbing with the electronic gear box, on egb_lathe.yaml: a 20-tooth helical gear)
G00 X30 Z5 C0 (the safe point)
M03 S300 (the hob turns at 300 rpm)
G81.4 T20 L1 P15 Q2 R0 (C turns 1/20 of S1, tooth phase 0, helix 15 degrees, module 2)
G01 X20 F300 (the hob in to depth)
G01 Z-20 F200 (along the face: Z's travel adds the helical angle)
G00 X30 (out)
G80.4 (C stops within 0.4 s where it reached)
G00 H90 (C on by 90 degrees from there: H is C's increment)
M05
M30
