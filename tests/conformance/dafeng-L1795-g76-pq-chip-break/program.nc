O1000 (dafeng L1795: the L1829-1835 example with PQ8, a chip break every 8 mm of the roughing passes)
G00 X68 Z50
G76 P010060 R0.2 PQ8
G76 X60.4 Z25 P3.68 Q1.8 F6
M30
