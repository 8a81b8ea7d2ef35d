O1000 (gsk A.6.41: G92.1 P1, interpolated repair of a two-start thread at S300)
G00 X40 Z5
M14
G92.1 X38 Z-20 F1.5 L2 S300 P1
X37.4
G00 X60
M30
