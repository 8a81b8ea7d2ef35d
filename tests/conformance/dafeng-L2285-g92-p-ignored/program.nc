O1000 (dafeng L2285: G92 P, the thread feed start height, is ignored with a warning: the D2-5 cycle)
G00 X60 Z5
G92 X48 Z-30 F2 P1.5
M30
